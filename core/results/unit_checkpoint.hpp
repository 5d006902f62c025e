// The checkpoint file of a command that finishes in units (issue 12; docs/robustness.md, "Long runs
// resume"): `tmlab fit` (the global stage, each local run, each profile point), `tmlab discover`
// (each fit of the loop) and its benchmark (each set). The engines do no file I/O: they report each
// finished unit through a hook; UnitCheckpoint decides when to write the file (checkpoint.hpp:
// tmlab-checkpoint/1) and what an INTERRUPTED marker says about it.
#pragma once

#include "core/base/error.hpp"

#include "core/base/interrupt.hpp"
#include "core/results/checkpoint.hpp"
#include "core/results/result_dir.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace tmlab {

/// --resume of a result directory that holds a complete result (its summary.json): tmlab::Error
/// "nothing to resume: DIR holds a complete WHAT (summary.json); run without --resume to redo it".
/// Checked before the checkpoint is read and before the result directory is opened.
void refuse_resume_of_complete(const std::filesystem::path& dir, const std::string& what);

/// "0123456789abcdef": a file's FNV-1a-64 hash for a fingerprint (tmlab::Error naming a missing file).
std::string file_hash(const std::filesystem::path& path);

/// The text of a unit's non-numeric part (names, reasons, flags, counts) as one checkpoint text
/// entry: JSON, invalid UTF-8 replaced rather than refused. Numbers go in double entries.
std::string unit_text(const nlohmann::json& j);
/// The JSON of text entry `name`; tmlab::Error naming the file and the entry when it does not parse.
nlohmann::json read_unit_text(const CheckpointData& d, const std::string& name);
/// tmlab::Error "FILE: inconsistent entry 'NAME'; run without --resume" unless `ok`: a checkpoint
/// whose parts do not fit together.
void require_consistent(bool ok, const CheckpointData& d, const std::string& name);
/// tmlab::Error "FILE: unreadable entry 'NAME' (WHY); run without --resume".
Error unreadable_entry(const CheckpointData& d, const std::string& name, const std::string& why);
/// Runs `read`, which takes the fields out of the JSON of text entry `name`: a missing or mistyped
/// field is reported as that entry being unreadable (unreadable_entry).
template <typename F>
void read_unit_fields(const CheckpointData& d, const std::string& name, F&& read) {
  try {
    read();
  } catch (const nlohmann::json::exception& e) {
    throw unreadable_entry(d, name, e.what());
  }
}

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

/// The checkpoint of a command whose units are a list of T (the fits of a discovery, the sets of a
/// benchmark): writes the finished units through `put`, and with --resume reads them back through
/// `get` before the result directory is touched. Not copyable or movable (its writer refers to
/// the list).
template <class T>
class UnitListCheckpoint {
 public:
  using Put = void (*)(CheckpointData&, const std::vector<T>&);
  using Get = std::vector<T> (*)(const CheckpointData&);
  /// The file <dir>/.incomplete/checkpoint.h5; `noun` names the units in messages ("fit(s)").
  UnitListCheckpoint(const std::filesystem::path& dir, const std::string& kind,
                     const nlohmann::json& fingerprint, const CheckpointSchedule& schedule, Put put,
                     std::string noun)
      : noun_(std::move(noun)),
        ck_(dir / result_dir::kStaging / "checkpoint.h5", kind, fingerprint, schedule, [this, put] {
          CheckpointData d;
          put(d, done_);
          return d;
        }) {}
  UnitListCheckpoint(const UnitListCheckpoint&) = delete;
  UnitListCheckpoint& operator=(const UnitListCheckpoint&) = delete;

  /// The units of the interrupted run (--resume), said on `log` after `who` ("tmlab discover").
  std::vector<T> restore(Get get, std::ostream& log, const std::string& who) {
    done_ = get(ck_.read());
    ck_.resumed_from(count());
    log << who << ": resuming from " << ck_.path().string() << ": " << count()
        << " taken from it, the rest runs\n";
    return done_;
  }
  /// Records a finished unit (a checkpoint when one is due).
  void finished(const T& unit) {
    done_.push_back(unit);
    ck_.unit_finished(count());
  }
  UnitCheckpoint& file() { return ck_; }

 private:
  std::string count() const { return std::to_string(done_.size()) + " finished " + noun_; }
  std::vector<T> done_;
  std::string noun_;
  UnitCheckpoint ck_;
};

}  // namespace tmlab
