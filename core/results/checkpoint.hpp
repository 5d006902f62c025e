// Checkpoints of long commands (issue 12): the state a command needs to continue with --resume and
// end with results identical bit for bit to an uninterrupted run (same build, same thread count).
//
// A checkpoint is one HDF5 file (tmlab-checkpoint/1):
//   root attributes  format = "tmlab-checkpoint/1", kind (which command wrote it), written_utc
//   /fingerprint     the effective configuration as JSON text (what --resume must match)
//   /double/<name>   1-D float64 datasets (doubles are stored as they are: exact round trip)
//   /int/<name>      1-D int64 datasets
//   /text/<name>     text, its bytes packed 8 to an int64 word (attribute "bytes": the length)
// It is written atomically: to "<path>.tmp", flushed, fsync'ed, renamed over <path>, and the
// directory fsync'ed, so a crash at any moment leaves the previous checkpoint or the new one.
//
// --resume refuses a checkpoint of another kind or of another configuration, naming the first
// keys that differ ("solver.dt: the checkpoint has 0.001, this run 0.002").
//
// When to write one: CheckpointSchedule (every N steps and/or T seconds of wall time, the CLI's
// --checkpoint-every) and always at a stop request (SIGINT/SIGTERM, core/base/interrupt.hpp).
#pragma once

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace tmlab {

/// The named contents of one checkpoint. Names are 1-64 characters of A-Z a-z 0-9 _ . - (they
/// become HDF5 dataset names); a bad name throws tmlab::Error.
class CheckpointData {
 public:
  void put(const std::string& name, std::vector<double> values);
  void put(const std::string& name, std::vector<std::int64_t> values);
  void put_scalar(const std::string& name, double value) { put(name, std::vector<double>{value}); }
  void put_int(const std::string& name, std::int64_t value) { put(name, std::vector<std::int64_t>{value}); }
  void put_text(const std::string& name, const std::string& text);

  bool has(const std::string& name) const;
  /// The stored entry; tmlab::Error naming the checkpoint file and the entry when it is missing
  /// (or, for scalar()/integer(), not of length 1).
  const std::vector<double>& doubles(const std::string& name) const;
  const std::vector<std::int64_t>& ints(const std::string& name) const;
  double scalar(const std::string& name) const;
  std::int64_t integer(const std::string& name) const;
  const std::string& text(const std::string& name) const;

  const std::map<std::string, std::vector<double>>& all_doubles() const { return doubles_; }
  const std::map<std::string, std::vector<std::int64_t>>& all_ints() const { return ints_; }
  const std::map<std::string, std::string>& all_texts() const { return texts_; }
  /// Where the data came from, for error messages ("" for data built in memory).
  const std::string& source() const { return source_; }
  void set_source(std::string s) { source_ = std::move(s); }

 private:
  [[noreturn]] void missing(const std::string& name, const char* what) const;
  std::map<std::string, std::vector<double>> doubles_;
  std::map<std::string, std::vector<std::int64_t>> ints_;
  std::map<std::string, std::string> texts_;
  std::string source_;
};

/// Writes the checkpoint atomically (see the file comment). Throws tmlab::Error naming the file.
void write_checkpoint(const std::filesystem::path& path, const std::string& kind,
                      const nlohmann::json& fingerprint, const CheckpointData& data);

/// Reads a checkpoint back exactly. Throws tmlab::Error naming the file when it is missing,
/// unreadable, not a tmlab checkpoint, of another `kind`, or of another configuration (the
/// message names the differing keys and says to run without --resume).
CheckpointData read_checkpoint(const std::filesystem::path& path, const std::string& kind,
                               const nlohmann::json& fingerprint);

/// Removes the checkpoint and a temporary left by a write that was killed half-way (never throws).
void remove_checkpoint(const std::filesystem::path& path) noexcept;

/// "" when `stored` and `current` are equal, else the differing keys (dotted paths, at most 5)
/// with both values: "solver.dt: the checkpoint has 0.001, this run 0.002".
std::string fingerprint_mismatch(const nlohmann::json& stored, const nlohmann::json& current);

/// When to write checkpoints besides at a stop request.
struct CheckpointSchedule {
  long every_steps = 0;         ///< every N steps (or sub-runs); 0: not by count
  double every_seconds = 60.0;  ///< when this much wall time passed since the last one; 0: not by time

  /// The --checkpoint-every value: "N" (steps), "Ts" or "Tmin" (wall time), "off" (only at a stop
  /// request). Throws tmlab::Error naming the accepted forms.
  static CheckpointSchedule parse(const std::string& text);
  /// "every 100 steps", "every 60 s", "only on a stop request".
  std::string describe() const;
};

/// Decides, at each safe point, whether a checkpoint is due.
class CheckpointClock {
 public:
  explicit CheckpointClock(CheckpointSchedule schedule);
  /// True when `step` is a multiple of every_steps or every_seconds passed since the last mark.
  bool due(long step) const;
  /// Call after writing a checkpoint: restarts the wall-time interval.
  void mark();

 private:
  CheckpointSchedule schedule_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace tmlab
