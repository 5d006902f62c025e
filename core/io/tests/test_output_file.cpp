// check_output_files: never over an input, never over an existing file unless asked.
#include "core/base/error.hpp"
#include "core/io/output_file.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace tmlab {
namespace {

namespace fs = std::filesystem;
using testing::write_file;

class OutputFile : public testing::TempDirTest {};

std::string refusal(const std::vector<fs::path>& targets, const std::vector<fs::path>& inputs,
                    bool overwrite) {
  try {
    check_output_files(targets, inputs, overwrite);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST_F(OutputFile, NewFilesAreFine) {
  EXPECT_EQ(refusal({dir_ / "a.csv", dir_ / "a.json"}, {dir_ / "raw.csv"}, false), "");
}

TEST_F(OutputFile, AnExistingFileNeedsOverwrite) {
  write_file(dir_ / "a.json", "mine");
  const std::string why = refusal({dir_ / "a.csv", dir_ / "a.json"}, {}, false);
  EXPECT_NE(why.find("a.json: exists already; nothing was written (give --overwrite"), std::string::npos)
      << why;
  EXPECT_EQ(refusal({dir_ / "a.csv", dir_ / "a.json"}, {}, true), "");
}

TEST_F(OutputFile, NeverOverAnInputEvenWithOverwriteOrThroughALink) {
  write_file(dir_ / "raw.csv", "data");
  fs::create_directories(dir_ / "sub");
  fs::create_directory_symlink(dir_, dir_ / "sub" / "up");
  for (const fs::path& target :
       {dir_ / "raw.csv", dir_ / "sub" / ".." / "raw.csv", dir_ / "sub" / "up" / "raw.csv"}) {
    const std::string why = refusal({target}, {dir_ / "raw.csv"}, true);
    EXPECT_NE(why.find("is the input"), std::string::npos) << target << ": " << why;
  }
}

TEST_F(OutputFile, ADanglingLinkIsNotAnAbsentFile) {
  fs::create_symlink(dir_ / "elsewhere" / "x.csv", dir_ / "a.csv");
  EXPECT_NE(refusal({dir_ / "a.csv"}, {}, true).find("which does not exist"), std::string::npos);
}

TEST_F(OutputFile, ADirectoryIsNotAFileToReplace) {
  fs::create_directories(dir_ / "a.msh");
  EXPECT_NE(refusal({dir_ / "a.msh"}, {}, true).find("not a regular file"), std::string::npos);
}

}  // namespace
}  // namespace tmlab
