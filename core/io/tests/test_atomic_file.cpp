// write_file_atomically: the content arrives whole under the final name, a previous file is replaced
// whole, and a failure throws tmlab::Error naming the file and leaves no temporary behind.
#include "core/base/error.hpp"
#include "core/io/atomic_file.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace tmlab {
namespace {

namespace fs = std::filesystem;
using testing::read_file;
using testing::write_file;

class AtomicFile : public testing::TempDirTest {};

TEST_F(AtomicFile, WritesTheContentAndLeavesNoTemporary) {
  const fs::path path = dir_ / "summary.json";
  write_file_atomically(path, "{\"ok\": true}\n");
  EXPECT_EQ(read_file(path), "{\"ok\": true}\n");
  EXPECT_FALSE(fs::exists(dir_ / "summary.json.tmp"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(AtomicFile, ReplacesALongerFileWhole) {
  const fs::path path = dir_ / "a.txt";
  write_file(path, std::string(1000, 'x'));
  write_file_atomically(path, "short");
  EXPECT_EQ(read_file(path), "short");  // no tail of the old content
}

TEST_F(AtomicFile, KeepsBinaryBytesAndWritesEmptyFiles) {
  const std::string bytes("a\0b\r\n\xff\x00", 7);
  write_file_atomically(dir_ / "bin", bytes);
  EXPECT_EQ(read_file(dir_ / "bin"), bytes);
  write_file_atomically(dir_ / "empty", "");
  ASSERT_TRUE(fs::exists(dir_ / "empty"));
  EXPECT_EQ(fs::file_size(dir_ / "empty"), 0u);
}

TEST_F(AtomicFile, NeverWritesIntoAFileThatWasThere) {
  // The temporary is a fresh file (mkstemp): a file named like a temporary, the user's or a crashed
  // run's, is left exactly as it was.
  const fs::path path = dir_ / "r.vtu";
  write_file(dir_ / "r.vtu.tmp", "somebody's file");
  write_file_atomically(path, "new");
  EXPECT_EQ(read_file(path), "new");
  EXPECT_EQ(read_file(dir_ / "r.vtu.tmp"), "somebody's file");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 2);
}

TEST_F(AtomicFile, ResultFilesAreReadable) {
  write_file_atomically(dir_ / "a.json", "{}");
  const auto perms = fs::status(dir_ / "a.json").permissions();
  EXPECT_NE(perms & fs::perms::others_read, fs::perms::none);
}

TEST_F(AtomicFile, MissingDirectoryThrowsNamingTheFile) {
  const fs::path path = dir_ / "no_such_dir" / "x.txt";
  try {
    write_file_atomically(path, "x");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path.string() + ": cannot write (", 0), 0u) << msg;
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(dir_ / "no_such_dir"));
}

TEST_F(AtomicFile, FailedRenameRemovesTheTemporaryAndKeepsWhatWasThere) {
  // The final name is a non-empty directory: the content is written to "<path>.tmp", but the rename
  // fails; the error names the file and nothing is left that looks like output.
  const fs::path path = dir_ / "out";
  fs::create_directories(path);
  write_file(path / "keep", "kept");
  try {
    write_file_atomically(path, "x");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path.string() + ": cannot move finished file into place (", 0), 0u) << msg;
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);  // no temporary
  EXPECT_TRUE(fs::is_directory(path));
  EXPECT_EQ(read_file(path / "keep"), "kept");
}

}  // namespace
}  // namespace tmlab
