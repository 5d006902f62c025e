// Starting helper programs (the python plotters) safely: always with an argument vector through
// posix_spawn, never through a shell, so no file name, case name or path can be interpreted as a
// command. Standard output and error go to a log file, to /dev/null, or stay with the caller.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace tmlab {

/// Where a child's standard output and standard error go.
struct ProcessOutput {
  enum class Kind { Inherit, Discard, File };
  Kind kind = Kind::Inherit;
  std::filesystem::path file;  ///< Kind::File: both streams, truncated first

  static ProcessOutput inherit() { return {}; }
  static ProcessOutput discard() { return {Kind::Discard, {}}; }
  static ProcessOutput to_file(std::filesystem::path p) { return {Kind::File, std::move(p)}; }
};

/// How a child ended.
struct ProcessStatus {
  bool started = false;  ///< false: the program could not be started (not found, not executable)
  int exit_code = -1;    ///< when it exited normally
  int signal = 0;        ///< when a signal ended it
  std::string error;     ///< why it could not be started

  bool ok() const { return started && signal == 0 && exit_code == 0; }
  /// "exit status 1", "killed by signal 9", "could not start: No such file or directory".
  std::string describe() const;
};

/// Runs argv[0] (looked up on PATH when it has no slash) with arguments argv[1..], waits for it and
/// returns how it ended. The arguments reach the program verbatim: there is no shell. Never throws
/// for a child that fails; throws tmlab::Error for an empty argv or an unopenable output file.
ProcessStatus run_process(const std::vector<std::string>& argv, const ProcessOutput& output = {});

/// The python3 used for plots: $TMLAB_PYTHON when set, else Debian's /usr/bin/python3 (which
/// carries python3-matplotlib and python3-h5py; another python3 may come first on PATH), else
/// "python3" from PATH.
std::string python_interpreter();

/// Runs `python_interpreter() script args...` (see run_process).
ProcessStatus run_python(const std::filesystem::path& script, const std::vector<std::string>& args,
                         const ProcessOutput& output = {});

}  // namespace tmlab
