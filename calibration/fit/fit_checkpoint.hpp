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
#include "core/results/unit_checkpoint.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <ostream>

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

/// The checkpoint of one fit (`tmlab fit`, docs/robustness.md): <dir>/.incomplete/checkpoint.h5
/// after the global stage, each local run and each profile point as `schedule` says (and at a stop).
/// Not copyable or movable (its writer refers to the latest units).
class FitCheckpoint {
 public:
  FitCheckpoint(const std::filesystem::path& dir, const nlohmann::json& fingerprint,
                const CheckpointSchedule& schedule);
  FitCheckpoint(const FitCheckpoint&) = delete;
  FitCheckpoint& operator=(const FitCheckpoint&) = delete;
  /// --resume: the units of the interrupted fit handed to `o` (taken instead of computed), said on
  /// `log`. tmlab::Error when there is no checkpoint or it is of another configuration.
  void restore(FitOptions& o, std::ostream& log);
  /// Each unit `o`'s fit finishes is recorded (a checkpoint when one is due).
  void record(FitOptions& o);
  UnitCheckpoint& file() { return ck_; }

 private:
  FitUnits restored_, latest_;
  UnitCheckpoint ck_;
};

}  // namespace tmlab::fit
