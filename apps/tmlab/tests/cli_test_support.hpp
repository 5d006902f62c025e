// Shared by the command-line tests: run the built `tmlab` driver in a shell and capture its exit
// status and combined output, and a fixture that gives each test its own temporary directory.
#pragma once

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

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
