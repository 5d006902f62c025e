// Result-folder ownership (issue 26): tmlab removes only what its own marker lists, refuses folders it
// did not write, follows links to where the result goes, and refuses folders that are not a result's own.
#include "core/base/error.hpp"
#include "core/results/result_dir.hpp"
#include "core/results/run_output.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include <unistd.h>

namespace fs = std::filesystem;

namespace {

using tmlab::testing::read_file;
using tmlab::testing::write_file;
namespace rd = tmlab::result_dir;

/// Every file under `root` with its content (links by their target): what must not change.
std::map<std::string, std::string> snapshot(const fs::path& root) {
  std::map<std::string, std::string> out;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
    const std::string rel = it->path().lexically_relative(root).generic_string();
    if (it->is_symlink())
      out[rel] = "-> " + fs::read_symlink(it->path()).string();
    else if (it->is_regular_file())
      out[rel] = read_file(it->path());
    else
      out[rel + "/"] = "";
  }
  return out;
}

/// Runs `what`, expecting tmlab::Error whose message contains `needle`.
template <typename F>
void expect_refused(F&& what, const std::string& needle) {
  try {
    what();
    ADD_FAILURE() << "not refused (expected: " << needle << ")";
  } catch (const tmlab::Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

class ResultDir : public tmlab::testing::TempDirTest {
 protected:
  /// A finished result with the given files, written through RunOutput.
  void make_result(const fs::path& dir, const std::vector<std::string>& files) {
    tmlab::RunOutput out(dir);
    for (const auto& f : files) write_file(out.file(f), "result " + f);
    out.finalize();
  }
  void write_marker(const fs::path& dir, const nlohmann::json& files) {
    write_file(dir / rd::kMarker,
               nlohmann::json{{"format", rd::kFormat}, {"run_id", "0"}, {"files", files}}.dump());
  }
};

TEST_F(ResultDir, AForeignManifestDoesNotMakeAFolderTmlabs) {
  // The reproduction: `mkdir V; echo '{}' > V/manifest.json; echo x > V/thesis.tex; tmlab fit ...
  // --out V` emptied V.
  const fs::path v = dir_ / "V";
  fs::create_directories(v);
  write_file(v / "manifest.json", "{}");
  write_file(v / "thesis.tex", "x");
  write_file(v / "summary.json", "{}");
  fs::create_directories(v / ".incomplete");
  const auto before = snapshot(dir_);
  expect_refused([&] { tmlab::RunOutput out(v); }, "not a tmlab result directory");
  EXPECT_EQ(snapshot(dir_), before);
}

TEST_F(ResultDir, ReplacingAResultRemovesOnlyTheFilesItsMarkerLists) {
  const fs::path r = dir_ / "r";
  make_result(r, {"manifest.json", "vtu/step_1.vtu", "plot.png"});
  const auto marker = nlohmann::json::parse(read_file(r / rd::kMarker));
  EXPECT_EQ(marker["files"], (nlohmann::json{"manifest.json", "plot.png", "summary.json", "vtu/step_1.vtu"}));
  EXPECT_EQ(marker["format"], rd::kFormat);
  EXPECT_EQ(marker["run_id"].get<std::string>().size(), 32u);
  {
    tmlab::RunOutput again(r);
    EXPECT_FALSE(fs::exists(r / "plot.png"));
    EXPECT_FALSE(fs::exists(r / "vtu"));  // emptied by the listed files, so removed
    write_file(again.file("other.txt"), "2");
    again.finalize();
  }
  EXPECT_EQ(read_file(r / "other.txt"), "2");
  EXPECT_FALSE(fs::exists(r / "manifest.json"));
}

TEST_F(ResultDir, AResultThatAlsoHoldsSomebodysFilesIsRefusedAndKept) {
  const fs::path r = dir_ / "r";
  make_result(r, {"manifest.json", "vtu/step_1.vtu"});
  write_file(r / "notes.txt", "mine");
  write_file(r / "vtu" / "my.vtu", "mine too");
  const auto before = snapshot(dir_);
  expect_refused([&] { tmlab::RunOutput out(r); }, "notes.txt, vtu/my.vtu");
  EXPECT_EQ(snapshot(dir_), before);
}

TEST_F(ResultDir, ACraftedMarkerCannotReachOutside) {
  const fs::path outside = dir_ / "precious.txt";
  write_file(outside, "keep");
  fs::create_directories(dir_ / "elsewhere");
  write_file(dir_ / "elsewhere" / "x", "keep");
  for (const nlohmann::json& files : {nlohmann::json{"../precious.txt"}, nlohmann::json{outside.string()},
                                      nlohmann::json{"a/../../precious.txt"}, nlohmann::json{"./x"},
                                      nlohmann::json{""}, nlohmann::json{"link/x"}, nlohmann::json{1}}) {
    const fs::path r = dir_ / "crafted";
    fs::remove_all(r);
    fs::create_directories(r);
    fs::create_directory_symlink(dir_ / "elsewhere", r / "link");
    write_marker(r, files);
    const auto before = snapshot(dir_);
    expect_refused([&] { tmlab::RunOutput out(r); }, "nothing in");
    EXPECT_EQ(snapshot(dir_), before) << files.dump();
  }
  const fs::path r = dir_ / "notjson";
  fs::create_directories(r);
  write_file(r / rd::kMarker, "{\"format\": \"tmlab-result/1\", ");
  expect_refused([&] { tmlab::RunOutput out(r); }, "is not valid JSON");
}

TEST_F(ResultDir, ALinkIsFollowedAndStaysALink) {
  const fs::path target = dir_ / "target";
  fs::create_directories(target);
  const fs::path link = dir_ / "link";
  fs::create_directory_symlink(target, link);
  {
    tmlab::RunOutput out(link);
    EXPECT_EQ(out.dir(), fs::canonical(target));
    write_file(out.file("a.txt"), "a");
    out.finalize();
  }
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read_file(target / "a.txt"), "a");
  EXPECT_TRUE(fs::exists(target / "summary.json"));
  EXPECT_FALSE(fs::exists(target / "RUNNING"));
  // A link to nothing is refused, naming where it points.
  fs::create_directory_symlink(dir_ / "nowhere", dir_ / "dangling");
  expect_refused([&] { tmlab::RunOutput out(dir_ / "dangling"); }, "which does not exist");
  EXPECT_FALSE(fs::exists(dir_ / "nowhere"));
}

TEST_F(ResultDir, TheCurrentDirectoryItsParentsHomeAndRootAreRefused) {
  const fs::path cwd = fs::current_path();
  const fs::path work = dir_ / "a" / "b";
  fs::create_directories(work);
  fs::current_path(work);
  const auto before = snapshot(dir_);
  expect_refused([] { tmlab::RunOutput out("."); }, "is the current directory");
  expect_refused([] { tmlab::RunOutput out(""); }, "is empty");
  expect_refused([] { tmlab::RunOutput out(".."); }, "a parent of the current directory");
  expect_refused([] { tmlab::RunOutput out("/"); }, "is /");
  const char* home = std::getenv("HOME");
  const std::string saved = home ? home : "";
  ::setenv("HOME", (dir_ / "a").c_str(), 1);
  fs::current_path(dir_);
  expect_refused([&] { tmlab::RunOutput out(dir_ / "a"); }, "is the home directory");
  if (home) ::setenv("HOME", saved.c_str(), 1);
  fs::current_path(cwd);
  EXPECT_EQ(snapshot(dir_), before);
  // A folder below the current directory is fine.
  fs::current_path(work);
  {
    tmlab::RunOutput out("sub");
    out.finalize();
  }
  fs::current_path(cwd);
  EXPECT_TRUE(fs::exists(work / "sub" / "summary.json"));
}

TEST_F(ResultDir, AnEmptyStagedFolderIsNotLeftToBlockTheNextRun) {
  // The deal.II reference stages vtu/ and leaves it empty when no fields are written.
  const fs::path r = dir_ / "r";
  for (int k = 0; k < 2; ++k) {
    tmlab::RunOutput out(r);
    fs::create_directories(out.staging_dir() / "vtu" / "deeper");
    write_file(out.file("a.txt"), "a");
    out.finalize();
  }
  EXPECT_FALSE(fs::exists(r / "vtu"));
  EXPECT_TRUE(fs::exists(r / "summary.json"));
}

TEST_F(ResultDir, InspectTellsMarkedFromForeign) {
  EXPECT_FALSE(rd::inspect(dir_ / "none").exists);
  const fs::path e = dir_ / "empty";
  fs::create_directories(e);
  const auto empty = rd::inspect(e);
  EXPECT_TRUE(empty.exists);
  EXPECT_TRUE(empty.foreign.empty());
  EXPECT_NO_THROW(rd::check_may_take(e, empty));
  const fs::path r = dir_ / "r";
  make_result(r, {"x.txt"});
  const auto mine = rd::inspect(r);
  EXPECT_TRUE(mine.has_marker);
  EXPECT_TRUE(mine.foreign.empty());
  EXPECT_EQ(mine.listed, (std::vector<std::string>{"summary.json", "x.txt"}));
  // A temporary a crash left beside a listed file is tmlab's; another name is not.
  write_file(r / "x.txt.tmpAb12Cd", "half");
  write_file(r / "y.txt.tmpAb12Cd", "not ours");
  EXPECT_EQ(rd::inspect(r).foreign, (std::vector<std::string>{"y.txt.tmpAb12Cd"}));
}

}  // namespace
