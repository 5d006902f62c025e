// The result-directory protocol for results/<case>/, and the run manifest.
//
// Which folder: the path is resolved first (core/results/result_dir.hpp): a symbolic link is followed
// and the result written into its target; "" and a path that is the current directory, one of its
// parents, the home directory or "/" are refused before anything is computed.
//
// Whose folder: tmlab writes into a folder only when it does not exist, is empty, or holds the
// ownership marker `.tmlab-result` that tmlab wrote there; replacing a previous result removes exactly
// the files that marker lists, and a folder holding anything else is refused with the names of what
// tmlab did not write. Nothing tmlab did not write is ever removed or overwritten.
//
// One writer: a RunOutput holds an exclusive lock (flock on the result directory itself) for its
// whole life; a second RunOutput on the same directory, in this or any other process, is refused
// with a message naming the process that holds it (from its RUNNING marker). A RUNNING marker
// left by a process that is gone (its lock died with it) is reported as stale and cleared.
//
// A run writes every result file into the staging directory <dir>/.incomplete/ while a RUNNING
// marker sits in <dir>. finalize() lists the staged files in the marker, moves them into <dir> (renames
// inside one folder, so one file system even behind a link) and writes summary.json last: a directory
// holding summary.json is a complete run, and nothing else is.
// A run that ends any other way (an exception unwinding past the RunOutput, or an explicit fail())
// leaves a FAILED marker with the reason, keeps .incomplete/ for inspection, and has no
// summary.json; a run stopped by SIGINT/SIGTERM (interrupt()) leaves INTERRUPTED instead. RUNNING
// reserves room on disk, so that even a full disk ends in FAILED with the reason.
// Typical use:
//
//   tmlab::RunOutput out("results/" + case_name);
//   try {
//     out.write_json("manifest.json", tmlab::make_manifest({args, config, {mesh_file}}));
//     tmlab::VtuWriter(mesh).write(out.file("rest.vtu"));
//     ...
//     out.finalize({{"steps", n}});
//   } catch (const std::exception& e) {
//     out.fail(e.what());  // records the reason; without this the destructor records a generic one
//     throw;
//   }
#pragma once

#include "core/results/result_dir.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace tmlab {

/// 64-bit FNV-1a hash of a file's bytes. Throws tmlab::Error naming the file when it can't be read.
std::uint64_t fnv1a64_file(const std::filesystem::path& path);
/// 64-bit FNV-1a hash of a byte string.
std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t seed = 0xcbf29ce484222325ULL);
/// "2026-11-22T03:10:50Z" (UTC, ISO-8601, whole seconds).
std::string utc_iso8601(std::chrono::system_clock::time_point t);
/// This machine's host name ("unknown" when it can't be found).
std::string host_name();
/// argv as strings.
std::vector<std::string> command_line(int argc, const char* const* argv);

/// What a manifest records beyond the build identity, which comes from tmlab/build_info.hpp.
struct ManifestInput {
  std::vector<std::string> command_line;             ///< argv of the run
  nlohmann::json config = nlohmann::json::object();  ///< the effective (defaults-filled) config
  std::vector<std::filesystem::path> input_files;    ///< mesh, config and other inputs
  std::chrono::system_clock::time_point started = std::chrono::system_clock::now();
};

/// The manifest: tmlab version, git SHA and dirty flag, build type, compiler and flags, command
/// line, effective config, start and write times (UTC ISO-8601), host name, and each input file's
/// absolute path, size and FNV-1a-64 hash (16 hex digits). Throws tmlab::Error for a missing input.
nlohmann::json make_manifest(const ManifestInput& input);

/// Empty when `name` may name a result directory, else why not. Names are 1 to 100 characters
/// from A-Z a-z 0-9 and . _ - +, and do not start with '.' or '-': they become directory names
/// and appear in plots and command lines, so nothing else is allowed.
std::string result_name_problem(const std::string& name);

/// One run's result directory; see the file comment for the protocol.
class RunOutput {
 public:
  static constexpr const char* kStaging = result_dir::kStaging;
  static constexpr const char* kRunning = result_dir::kRunning;
  static constexpr const char* kFailed = result_dir::kFailed;
  static constexpr const char* kInterrupted = result_dir::kInterrupted;
  static constexpr const char* kSummary = result_dir::kSummary;

  /// Resolves `dir` (result_dir::resolve), takes its lock, creates it (and parents) and the staging
  /// area, and writes the ownership marker and RUNNING. A previous result's files (those its marker
  /// lists) are removed first, summary.json before anything else; a folder tmlab may not take (see
  /// the file comment) is refused (tmlab::Error) before anything is changed, and so is a directory
  /// another live RunOutput holds (the message names its process). A stale RUNNING marker (its
  /// process is gone) is reported on `log` when given.
  explicit RunOutput(std::filesystem::path dir, std::ostream* log = nullptr);
  /// What to do with the previous contents: discard them (the constructor above), or, to resume
  /// an interrupted command, keep its staged files (.incomplete/) so that the finished parts can
  /// be reused; the INTERRUPTED marker is cleared. A run whose process died (a stale RUNNING
  /// marker: SIGKILL, a crash) resumes the same way from its last scheduled checkpoint. Resuming a
  /// directory without one of these markers and staged files is refused (tmlab::Error: nothing to
  /// resume). ResumeStopped also resumes a run that FAILED (its staged files kept): for a command
  /// whose finished parts are complete result folders checked one by one before reuse (`tmlab
  /// converge --resume`: a level that failed runs again, the finished ones are reused).
  enum class Previous { Discard, ResumeInterrupted, ResumeStopped };
  RunOutput(std::filesystem::path dir, std::ostream* log, Previous previous);
  /// When neither finalize() nor fail() ran: writes FAILED (never throws). Releases the lock.
  ~RunOutput();
  RunOutput(const RunOutput&) = delete;
  RunOutput& operator=(const RunOutput&) = delete;

  /// The final result directory (resolved: absolute, links followed).
  const std::filesystem::path& dir() const { return dir_; }
  /// Where files are written until finalize().
  std::filesystem::path staging_dir() const { return dir_ / kStaging; }
  /// Path for result file `name` (relative; may contain subdirectories, which are created) in
  /// the staging area. It ends up at dir()/name after finalize().
  std::filesystem::path file(const std::string& name) const;
  /// Writes `value` as indented JSON to file(name), atomically.
  void write_json(const std::string& name, const nlohmann::json& value) const;

  /// Lists the staged files in the ownership marker, moves them into dir(), removes the staging area,
  /// writes summary.json last (`summary` plus "status", "started_utc", "finished_utc", "wall_seconds"
  /// and "files", the top-level names) and removes RUNNING. Throws tmlab::Error (and records FAILED) if
  /// anything goes wrong.
  void finalize(const nlohmann::json& summary = nlohmann::json::object());
  /// Records that the run failed: writes FAILED with `message` and removes RUNNING; staged files
  /// stay in staging_dir(). The first reason recorded wins. Never throws.
  void fail(const std::string& message) noexcept;
  /// Records that the run was stopped by a signal: writes INTERRUPTED with `message` (what was
  /// done, where a checkpoint is) and removes RUNNING; staged files stay. Never throws.
  void interrupt(const std::string& message) noexcept;
  /// fail() or interrupt(), chosen by the exception's type (tmlab::Interrupted -> interrupt()).
  void abandon(const std::exception& e) noexcept;

  bool finalized() const { return state_ == State::Finalized; }
  bool failed() const { return state_ == State::Failed; }
  bool interrupted() const { return state_ == State::Interrupted; }

 private:
  enum class State { Running, Finalized, Failed, Interrupted };
  void mark_stopped(State state, const char* marker, const std::string& message) noexcept;
  void take(std::ostream* log, Previous previous);
  void release_lock() noexcept;
  std::filesystem::path dir_;
  std::string run_id_;
  int lock_fd_ = -1;
  State state_ = State::Running;
  std::chrono::system_clock::time_point started_;
  std::chrono::steady_clock::time_point started_steady_;
  int uncaught_at_start_ = 0;
};

}  // namespace tmlab
