// The checkpoint entries of a discovery and of its benchmark (issue 12; docs/robustness.md, "Long
// runs resume"): the fits of the loop in the order they ran (discover::FitLog) and the finished
// benchmark sets (discover::BenchmarkLog). The engine does no file I/O; the command owns the file
// (core/results/unit_checkpoint.hpp) and turns the units into CheckpointData and back with these.
#pragma once

#include "calibration/discover/benchmark.hpp"
#include "calibration/discover/discover.hpp"
#include "core/results/checkpoint.hpp"

#include <vector>

namespace tmlab::discover {

/// The fits of a discover loop, in the order they ran.
void put_fit_outcomes(CheckpointData& d, const std::vector<FitOutcome>& v);
std::vector<FitOutcome> get_fit_outcomes(const CheckpointData& d);

/// The finished sets of a discover benchmark, in set order.
void put_benchmark_entries(CheckpointData& d, const std::vector<BenchmarkEntry>& v);
std::vector<BenchmarkEntry> get_benchmark_entries(const CheckpointData& d);

}  // namespace tmlab::discover
