// The checkpoint entries of a fit (issue 12; docs/robustness.md, "Long runs resume"): the finished
// units of one fit (fit::FitUnits, what `tmlab fit --resume` takes back) and a whole FitResult (the
// fits of a discovery). The engine does no file I/O; the command owns the file
// (core/results/unit_checkpoint.hpp) and turns the units into CheckpointData and back with these.
//
// Every double is stored as it is (float64 datasets: an exact round trip, NaN and infinities
// included); the text of a unit (names, stop reasons, notes, the flags and counts) is one JSON entry,
// never a number printed as decimal text.
#pragma once

#include "calibration/fit/fitter.hpp"
#include "core/results/checkpoint.hpp"

#include <string>

namespace tmlab::fit {

/// The units of one fit (the global stage, the local runs, the profile points).
void put_fit_units(CheckpointData& d, const FitUnits& u);
FitUnits get_fit_units(const CheckpointData& d);
/// "the global stage, 2 local run(s) and 3 profile point(s)".
std::string describe(const FitUnits& u);

/// A whole fit result under `prefix` (1-40 characters of the checkpoint's entry names).
void put_fit_result(CheckpointData& d, const std::string& prefix, const FitResult& r);
FitResult get_fit_result(const CheckpointData& d, const std::string& prefix);

}  // namespace tmlab::fit
