// Test helpers: a fresh temporary directory per test (TempDirTest) and whole-file text reads and
// writes. Shared by the tests that write files, so each names its directory the same way and
// cleans up the same way.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

namespace tmlab::testing {

/// The whole content of a file ("" when it cannot be read: the caller's EXPECT shows that).
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Writes `text` to `path`, replacing the file.
inline void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

/// Fixture: `dir_` is an empty directory of its own for each test, named after the test and the
/// process (ctest runs test executables in parallel), removed after the test.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    std::replace(name.begin(), name.end(), '/', '_');  // parameterised tests: "Suite/Name/0"
    dir_ = std::filesystem::temp_directory_path() / ("tmlab_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;  // a test that made a file read-only must not turn into a failure here
    std::filesystem::remove_all(dir_, ignored);
  }

  std::filesystem::path dir_;
};

}  // namespace tmlab::testing
