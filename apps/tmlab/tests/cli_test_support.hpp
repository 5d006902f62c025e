// Shared by the command-line tests: run the built `tmlab` driver (through a shell for readable
// tests, or with an argument vector when the arguments themselves are hostile) and capture its
// exit status and combined output. Each test gets its own temporary directory from
// tmlab::testing::TempDirTest (core/testing/temp_dir.hpp).
#pragma once

#include "core/base/process.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace tmlab::cli_test {

struct Result {
  int status = -1;     ///< exit status of the driver (-1 if it did not exit normally)
  std::string output;  ///< stdout and stderr together
};

/// Runs `tmlab <args>` (TMLAB_CLI, set by CMake) with TMLAB_ROOT pointing at the source tree.
inline Result run(const std::string& args) {
  const std::string cmd =
      std::string("TMLAB_ROOT='") + TMLAB_SOURCE_DIR + "' '" + TMLAB_CLI + "' " + args + " 2>&1";
  Result r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), buf.size(), p)) r.output += buf.data();
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

/// Runs `tmlab argv...` with an argument vector (no shell): every argument arrives verbatim.
/// `log` receives stdout and stderr.
inline Result run_argv(const std::vector<std::string>& args, const std::filesystem::path& log) {
  ::setenv("TMLAB_ROOT", TMLAB_SOURCE_DIR, 1);
  std::vector<std::string> argv{TMLAB_CLI};
  argv.insert(argv.end(), args.begin(), args.end());
  const tmlab::ProcessStatus st = tmlab::run_process(argv, tmlab::ProcessOutput::to_file(log));
  Result r;
  r.status = st.started && st.signal == 0 ? st.exit_code : -1;
  FILE* f = std::fopen(log.c_str(), "r");
  if (f) {
    std::array<char, 4096> buf{};
    while (std::fgets(buf.data(), buf.size(), f)) r.output += buf.data();
    std::fclose(f);
  }
  return r;
}

/// Starts `tmlab args...` in the background (argument vector, no shell); output to `log`.
inline pid_t spawn(const std::vector<std::string>& args, const std::filesystem::path& log) {
  ::setenv("TMLAB_ROOT", TMLAB_SOURCE_DIR, 1);
  std::vector<std::string> argv{TMLAB_CLI};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> c;
  for (auto& a : argv) c.push_back(a.data());
  c.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  pid_t pid = -1;
  EXPECT_EQ(::posix_spawn(&pid, c[0], &fa, nullptr, c.data(), environ), 0);
  posix_spawn_file_actions_destroy(&fa);
  return pid;
}

/// Waits (up to 5 minutes: the machine may be busy) until `p` exists.
inline bool wait_for(const std::filesystem::path& p) {
  for (int i = 0; i < 3000; ++i) {
    if (std::filesystem::exists(p)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

/// The exit status of a spawned process (-signal when a signal ended it).
inline int wait_exit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) return -WTERMSIG(status);
  return WEXITSTATUS(status);
}

/// One of the silicone phantom files in the repository (calibration/data/phantom/).
inline std::filesystem::path phantom_a1() {
  return std::filesystem::path(TMLAB_SOURCE_DIR) / "calibration" / "data" / "phantom" / "EF10_0T" /
         "EF10_0T_A1.csv";
}

/// Fixture: a temporary directory per test and `tmlab(args)`, the driver run with an argument vector
/// whose output is kept in dir_/log.txt.
class CliTest : public tmlab::testing::TempDirTest {
 protected:
  Result tmlab(const std::vector<std::string>& args) const { return run_argv(args, dir_ / "log.txt"); }
};

}  // namespace tmlab::cli_test
