// Shared by the command-line tests: run the built `tmlab` driver (through a shell for readable
// tests, or with an argument vector when the arguments themselves are hostile) and capture its
// exit status and combined output, and a fixture that gives each test its own temporary directory.
#pragma once

#include "core/base/process.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

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

/// A fixture whose dir_ is a fresh temporary directory named after the process and the test.
class TempDirTest : public ::testing::Test {
 protected:
  explicit TempDirTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           (prefix_ + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string prefix_;
  std::filesystem::path dir_;
};

}  // namespace tmlab::cli_test
