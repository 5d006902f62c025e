// The checkpoints of `tmlab fit` and `tmlab discover` (issue 12; docs/robustness.md, "Long runs
// resume"). The engines (tmlab::fit, tmlab::discover) do no file I/O: they report each finished
// unit through a hook (fit::FitResume, discover::FitLog, discover::BenchmarkLog) and take the
// restored units in; this file turns the units into CheckpointData and back, and UnitCheckpoint
// decides when to write the file (core/results/checkpoint.hpp: tmlab-checkpoint/1).
//
// Every double is stored as it is (float64 datasets: an exact round trip, NaN and infinities
// included); the text of a unit (names, stop reasons, notes, the flags and counts) is one JSON entry,
// never a number printed as decimal text.
#pragma once

#include "calibration/discover/benchmark.hpp"
#include "calibration/discover/discover.hpp"
#include "calibration/fit/fitter.hpp"
#include "core/base/interrupt.hpp"
#include "core/results/checkpoint.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace tmlab::cli {

/// The units of one fit (the global stage, the local runs, the profile points).
void put_fit_units(CheckpointData& d, const fit::FitUnits& u);
fit::FitUnits get_fit_units(const CheckpointData& d);
/// "the global stage, 2 local run(s) and 3 profile point(s)".
std::string describe(const fit::FitUnits& u);

/// A whole fit result under `prefix` (1-40 characters of the checkpoint's entry names).
void put_fit_result(CheckpointData& d, const std::string& prefix, const fit::FitResult& r);
fit::FitResult get_fit_result(const CheckpointData& d, const std::string& prefix);

/// The fits of a discover loop, in the order they ran.
void put_fit_outcomes(CheckpointData& d, const std::vector<discover::FitOutcome>& v);
std::vector<discover::FitOutcome> get_fit_outcomes(const CheckpointData& d);

/// The finished sets of a discover benchmark, in set order.
void put_benchmark_entries(CheckpointData& d, const std::vector<discover::BenchmarkEntry>& v);
std::vector<discover::BenchmarkEntry> get_benchmark_entries(const CheckpointData& d);

/// --resume of a result directory that holds a complete result (its summary.json): tmlab::Error
/// "nothing to resume: DIR holds a complete WHAT (summary.json); run without --resume to redo it".
/// Checked before the checkpoint is read and before the result directory is opened.
void refuse_resume_of_complete(const std::filesystem::path& dir, const std::string& what);

/// "0123456789abcdef": a file's FNV-1a-64 hash for a fingerprint (tmlab::Error naming a missing file).
std::string file_hash(const std::filesystem::path& path);

/// The checkpoint file of a command that finishes in units (<result dir>/.incomplete/checkpoint.h5):
/// written after a unit when the schedule says so (--checkpoint-every: every N units or T seconds)
/// or a stop was requested, and at the stop itself when the latest finished unit is not in it yet.
class UnitCheckpoint {
 public:
  /// `snapshot` gives the state after the latest finished unit (every unit so far).
  UnitCheckpoint(std::filesystem::path path, std::string kind, nlohmann::json fingerprint,
                 CheckpointSchedule schedule, std::function<CheckpointData()> snapshot);

  /// The checkpoint of the interrupted command (--resume): tmlab::Error when there is none or it
  /// is of another configuration (read_checkpoint names the keys).
  CheckpointData read() const;
  /// What the checkpoint read back holds ("the global stage and 1 local run(s)"): an INTERRUPTED
  /// marker written before the next unit finishes points at it.
  void resumed_from(const std::string& what) { written_ = what; }
  /// A unit finished; `what` says what the checkpoint then holds.
  void unit_finished(const std::string& what);
  /// At a stop: writes the latest state if it is not in the file yet, and returns `e` with where
  /// the checkpoint is and how to continue (or that there is none).
  Interrupted stopped(const Interrupted& e);
  /// The result is complete: it holds no checkpoint.
  void remove() const { remove_checkpoint(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  void write();
  std::filesystem::path path_;
  std::string kind_;
  nlohmann::json fingerprint_;
  CheckpointClock clock_;
  std::function<CheckpointData()> snapshot_;
  long units_ = 0;
  bool pending_ = false;  ///< a finished unit is not in the file yet
  std::string latest_, written_;
};

}  // namespace tmlab::cli
