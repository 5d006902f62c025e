// The result-directory property (issue 26): every command that writes a result directory, with its
// output in each of the conditions a user meets (an empty folder; a folder holding someone's files,
// a foreign manifest.json among them; a symlink to a folder, also on another file system; `.`; ""; a
// previous complete result, one with a file added, an interrupted one; a crafted ownership marker; a
// full disk (a 128 KiB tmpfs filled by someone's file) and a small one (an empty 64 KiB tmpfs that
// fills while HDF5 writes); for the commands whose --out names the result itself also $HOME, `/` and
// an ancestor of the working directory) must
//   1. never remove or change a file tmlab did not write (names and content hashes of the whole
//      scratch world, the result's siblings and the symlink targets included, before and after), and
//   2. end in exactly one of: a complete result (exit 0, summary.json and a .tmlab-result marker
//      listing every file, no RUNNING / FAILED / INTERRUPTED / .incomplete, no .NAME.final /
//      .NAME.old beside it); a refusal before computing (exit 1, the rule named, nothing created or
//      changed); or, on a full disk, FAILED with the reason (exit 1, no summary.json, no HDF5-DIAG
//      noise; a result that fits may also be complete). Never a RUNNING marker after the process ended.
// The tmpfs are mounted in a private mount namespace of the test process (cli_test_support.hpp);
// where that is impossible the disk conditions are skipped with the reason.
// The table of commands x conditions below is the property; each pair is one test. Commands run
// with their quickest options; those that cannot be made quick (bench, paper, workprecision) get
// fewer conditions (see fewer()).
#include "cli_test_support.hpp"

#include "core/base/interrupt.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/statvfs.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace tmlab::cli_test;
using tmlab::testing::read_file;
using tmlab::testing::write_file;

/// Where the output goes.
enum class Condition {
  Empty,                ///< an empty folder
  Foreign,              ///< a folder of someone's files: manifest.json ({}), thesis.tex, data/raw.csv
  Symlink,              ///< the result directory is a symlink to an empty folder
  SymlinkOtherFs,       ///< ... to a folder on another file system (tmpfs)
  Dot,                  ///< `.`, the working directory (holding someone's files)
  EmptyString,          ///< ""
  PreviousComplete,     ///< a complete result of the same command
  PreviousWithForeign,  ///< a complete result to which the user added a file
  PreviousInterrupted,  ///< a result stopped by SIGINT after its first checkpoint
  CraftedMarker,        ///< a .tmlab-result listing ../victim.txt and an absolute path
  FullDisk,             ///< a 128 KiB tmpfs filled by someone's file to two free pages
  SmallDisk,            ///< an empty 64 KiB tmpfs: the disk fills in the middle of the writes (HDF5)
  Home,                 ///< $HOME (a scratch one)            [--out commands only]
  Root,                 ///< `/`                              [--out commands only]
  Ancestor,             ///< `..` of the working directory    [--out commands only]
};

std::string name_of(Condition c) {
  switch (c) {
    case Condition::Empty:
      return "Empty";
    case Condition::Foreign:
      return "ForeignFiles";
    case Condition::Symlink:
      return "Symlink";
    case Condition::SymlinkOtherFs:
      return "SymlinkOtherFs";
    case Condition::Dot:
      return "Dot";
    case Condition::EmptyString:
      return "EmptyString";
    case Condition::PreviousComplete:
      return "PreviousComplete";
    case Condition::PreviousWithForeign:
      return "PreviousWithForeignFile";
    case Condition::PreviousInterrupted:
      return "PreviousInterrupted";
    case Condition::CraftedMarker:
      return "CraftedMarker";
    case Condition::FullDisk:
      return "FullDisk";
    case Condition::SmallDisk:
      return "SmallDisk";
    case Condition::Home:
      return "Home";
    case Condition::Root:
      return "Root";
    case Condition::Ancestor:
      return "Ancestor";
  }
  return "?";
}

/// One command that writes a result directory.
struct Command {
  std::string id;
  /// "": `--out DIR` names the result directory itself; else the result directory under the
  /// `--results ROOT` (e.g. "verification", "paper/fig2").
  std::string sub;
  /// The argument vector, given the data directory (tiny data set) and the output argument.
  std::function<std::vector<std::string>(const fs::path& data, const std::string& out)> args;
  /// Extra arguments that make it checkpoint (so TMLAB_TEST_STOP_AFTER_PROGRESS can stop it);
  /// nullopt: it has no checkpoints, so no deterministic interrupted result can be made.
  std::optional<std::vector<std::string>> checkpointing;
  /// Slow even with its quickest options: only the conditions in kFewer.
  bool slow = false;
};

std::vector<Command> commands() {
  auto tiny = [](const fs::path& data) { return (data / "tiny.csv").string(); };
  const std::vector<std::string> none;
  return {
      {"run", "cube-uniaxial",
       [](const fs::path&, const std::string& o) -> std::vector<std::string> {
         return {"run", "cube-uniaxial", "--no-plots", "--results", o};
       },
       std::vector<std::string>{"--checkpoint-every", "1"}},
      // compare has no checkpoints: no interrupted result.
      {"compare", "cube-uniaxial-compare-tl_oracle",
       [](const fs::path&, const std::string& o) -> std::vector<std::string> {
         return {"compare", "cube-uniaxial", "--against", "tl_oracle", "--results", o};
       },
       std::nullopt},
      {"verify", "verification",
       [](const fs::path&, const std::string& o) -> std::vector<std::string> {
         return {"verify",    "--case", "kernel-patch-test", "--case", "analytic-uniaxial-stvk", "--no-plots",
                 "--results", o};
       },
       none},
      {"hereditary", "hereditary",
       [](const fs::path&, const std::string& o) -> std::vector<std::string> {
         return {"hereditary", "--quick",    "--no-liver", "--histories",
                 "ramp_hold",  "--no-plots", "--results",  o};
       },
       none},
      {"depth_limit", "depth-limit",
       [](const fs::path&, const std::string& o) -> std::vector<std::string> {
         return {"depth-limit", "--laws",      "neo_hookean,stvk", "--cells",    "3",         "--max-depth",
                 "0.001",       "--increment", "0.0005",           "--no-plots", "--results", o};
       },
       none},
      {"fit", "",
       [tiny](const fs::path& d, const std::string& o) -> std::vector<std::string> {
         return {"fit", tiny(d),        "--model",    "neo_hookean", "--starts", "2", "--local-runs",
                 "1",   "--no-profile", "--no-plots", "--quiet",     "--out",    o};
       },
       std::vector<std::string>{"--checkpoint-every", "1"}},
      {"discover", "",
       [tiny](const fs::path& d, const std::string& o) -> std::vector<std::string> {
         return {"discover", tiny(d), "--rounds", "1", "--starts", "2", "--no-plots", "--quiet", "--out", o};
       },
       std::vector<std::string>{"--checkpoint-every", "1"}},
      // realtime --record has no checkpoints: no interrupted result. Real time: 0.2 s of the poke.
      {"realtime", "realtime",
       [](const fs::path&, const std::string& o) -> std::vector<std::string> {
         return {"realtime", "liver-poke", "--record", "--duration", "0.2", "--no-frames", "--results", o};
       },
       std::nullopt},
      {"workprecision", "workprecision",
       [](const fs::path&, const std::string& o) -> std::vector<std::string> {
         return {"workprecision", "--quick", "--problem", "liver", "--no-plots", "--results", o};
       },
       none, /*slow=*/true},
      {"paper", "paper/fig2",
       [](const fs::path&, const std::string& o) -> std::vector<std::string> {
         return {"paper", "fig2", "--quick", "--no-plots", "--results", o};
       },
       none, /*slow=*/true},
      {"discover_benchmark", "",
       [](const fs::path&, const std::string& o) -> std::vector<std::string> {
         return {"discover", "--benchmark", "--quick",  "--only", "noise_only,contact_offset",
                 "--rounds", "1",           "--starts", "2",      "--max-samples",
                 "200",      "--quiet",     "--out",    o};
       },
       std::vector<std::string>{"--checkpoint-every", "1"}},
      // bench has no checkpoints: no interrupted result.
      {"bench", "bench",
       [](const fs::path&, const std::string& o) -> std::vector<std::string> {
         return {"bench", "--quick", "--no-plots", "--results", o};
       },
       std::nullopt, /*slow=*/true},
  };
}

/// The conditions of the slow commands (paper fig2 --quick and workprecision --quick take ~45 s
/// each on a busy 2-core machine, bench --quick ~10 s): only those that the protocol decides before
/// computing (so each costs nothing once it is right), and for bench also a symlink and the full
/// disk. The other conditions exercise the same RunOutput through the quick commands above.
std::set<Condition> fewer(const std::string& command) {
  std::set<Condition> c = {Condition::Foreign, Condition::CraftedMarker, Condition::EmptyString};
  if (command == "bench") c.insert({Condition::Symlink, Condition::FullDisk});
  return c;
}

struct Param {
  std::string command;
  Condition condition;
};

void PrintTo(const Param& p, std::ostream* os) { *os << p.command << " x " << name_of(p.condition); }

std::vector<Param> params() {
  std::vector<Param> out;
  for (const Command& c : commands()) {
    for (int i = 0; i <= static_cast<int>(Condition::Ancestor); ++i) {
      const auto cond = static_cast<Condition>(i);
      if (c.slow && !fewer(c.id).count(cond)) continue;
      if (!c.sub.empty() &&
          (cond == Condition::Home || cond == Condition::Root || cond == Condition::Ancestor))
        continue;  // a results ROOT there only makes <root>/<sub>, which is not the folder itself
      if (!c.checkpointing && cond == Condition::PreviousInterrupted) continue;  // see the table
      out.push_back({c.id, cond});
    }
  }
  return out;
}

/// What the outcome must be.
enum class Expect {
  Complete,           ///< a complete result
  Refused,            ///< a named refusal before computing
  CompleteOrRefused,  ///< either (`--results .` for a results root: <cwd>/<sub> is a folder of its own)
  FailedOrRefused,  ///< full disk: FAILED with the reason, refused before computing, or (if it fits) complete
};

/// Where the output of a condition goes, what must come of it, and what to watch.
struct Placement {
  fs::path result;  ///< the result directory
  std::string out;  ///< the --out / --results argument
  Expect expect = Expect::Complete;
  std::vector<fs::path> roots;  ///< the trees to snapshot
};

class ResultDirProperty : public tmlab::testing::TempDirTest, public ::testing::WithParamInterface<Param> {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    for (const Command& c : commands())
      if (c.id == GetParam().command) cmd_ = c;
    world_ = dir_ / "w";
    cwd_ = world_ / "cwd";
    fs::create_directories(cwd_);
    write_tiny_data_set(dir_ / "data", "tiny");
    // Someone's files beside everything tmlab will touch.
    write_file(world_ / "notes.txt", "beside the results\n");
    write_file(cwd_ / "thesis.tex", "\\chapter{cwd}\n");
    write_file(cwd_ / "manifest.json", "{}\n");
  }
  void TearDown() override {
    std::error_code ec;
    if (!other_fs_.empty()) fs::remove_all(other_fs_, ec);
    TempDirTest::TearDown();
  }

  static void plant_foreign(const fs::path& dir) {
    fs::create_directories(dir / "data");
    write_file(dir / "manifest.json", "{}\n");
    write_file(dir / "thesis.tex", "\\chapter{Results}\nnot tmlab's\n");
    write_file(dir / "data" / "raw.csv", "t,f\n0,1\n");
  }

  /// The output argument for a result directory `result` (the root above it for results-root commands).
  std::string out_for(const fs::path& result) const {
    if (cmd_.sub.empty()) return result.string();
    fs::path root = result;
    const fs::path sub(cmd_.sub);
    for (auto it = sub.begin(); it != sub.end(); ++it) root = root.parent_path();
    return root.string();
  }
  /// The result directory of output argument `out` (relative ones against the working directory).
  fs::path result_of(const std::string& out) const {
    const fs::path o = fs::path(out).is_absolute() ? fs::path(out) : cwd_ / out;
    return cmd_.sub.empty() ? o : o / cmd_.sub;
  }
  std::vector<std::string> args(const std::string& out) const { return cmd_.args(dir_ / "data", out); }

  Result tmlab_in(const std::vector<std::string>& a, const std::string& log) const {
    return run_in(a, dir_ / log, cwd_);
  }

  /// A complete (or interrupted) result of the command at `result`, made by tmlab itself; what it
  /// wrote (new or changed entries of the world) goes to written_: tmlab may replace those.
  void make_previous(const fs::path& result, bool interrupted) {
    std::vector<std::string> a = args(out_for(result));
    const Snapshot before = snapshot(world_);
    if (!interrupted) {
      const Result r = tmlab_in(a, "previous.log");
      ASSERT_EQ(r.status, 0) << r.output;
      ASSERT_TRUE(fs::exists(result / "summary.json")) << r.output;
    } else {
      a.insert(a.end(), cmd_.checkpointing->begin(), cmd_.checkpointing->end());
      const ScopedEnv stop("TMLAB_TEST_STOP_AFTER_PROGRESS", "1:SIGINT");
      const Result r = tmlab_in(a, "previous.log");
      ASSERT_EQ(r.status, 128 + SIGINT) << r.output;
      ASSERT_TRUE(fs::exists(result / "INTERRUPTED")) << r.output;
    }
    for (const auto& [path, what] : snapshot(world_)) {
      const auto it = before.find(path);
      if (it == before.end() || it->second != what) written_.insert(path);
    }
  }

  /// Makes the condition's folders and files; sets skip_ when it cannot be made here.
  Placement place(Condition cond, std::optional<PrivateTmpfs>& disk, std::optional<ScopedEnv>& home);

  Command cmd_;
  fs::path world_, cwd_, other_fs_;
  std::string skip_;
  std::set<std::string> written_;  ///< what tmlab wrote while making a previous result
};

/// Fills the file system of `file` with `file` (someone's data) until two 4 KiB pages are left.
void fill_but_one_page(const fs::path& file) {
  struct statvfs st {};
  ASSERT_EQ(::statvfs(file.parent_path().c_str(), &st), 0);
  const std::size_t free_bytes = static_cast<std::size_t>(st.f_bavail) * st.f_frsize;
  ASSERT_GT(free_bytes, 8192u);
  write_file(file, std::string(free_bytes - 2 * 4096, 'x'));
}

/// A complete result at `dir`: summary.json, a .tmlab-result marker (format tmlab-result/1, a
/// run_id, "files" listing every file of the result, each relative and present), no run markers,
/// no staging, no sibling .NAME.final / .NAME.old. "" when complete, else what is wrong.
std::string incomplete(const fs::path& dir) {
  std::string why;
  if (!fs::exists(dir / "summary.json")) why += "no summary.json; ";
  for (const char* m : {"RUNNING", "FAILED", "INTERRUPTED", ".incomplete"})
    if (fs::exists(dir / m)) why += std::string(m) + " left; ";
  for (const char* suffix : {".final", ".old"})
    if (fs::exists(dir.parent_path() / ("." + dir.filename().string() + suffix)))
      why += "sibling ." + dir.filename().string() + suffix + "; ";
  nlohmann::json marker;
  try {
    marker = nlohmann::json::parse(read_file(dir / ".tmlab-result"));
  } catch (const std::exception& e) {
    return why + "no valid .tmlab-result (" + e.what() + ")";
  }
  if (marker.value("format", "") != "tmlab-result/1") why += "marker format is not tmlab-result/1; ";
  if (!marker.contains("run_id") || marker["run_id"].dump().size() <= 2) why += "marker has no run_id; ";
  std::set<std::string> listed;
  for (const auto& f : marker.value("files", nlohmann::json::array())) {
    const std::string p = f.is_string() ? f.get<std::string>() : f.dump();
    listed.insert(p);
    if (fs::path(p).is_absolute() || p.find("..") != std::string::npos) why += "marker lists " + p + "; ";
    if (!fs::is_regular_file(dir / p)) why += "marker lists missing " + p + "; ";
  }
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (!it->is_regular_file()) continue;
    const std::string rel = fs::relative(it->path(), dir).string();
    if (rel != ".tmlab-result" && !listed.count(rel)) why += "marker does not list " + rel + "; ";
  }
  return why;
}

/// The message a refusal must carry for `c` (the rule named): "" when any named message does.
std::vector<std::string> refusal_words(Condition c, const fs::path& result) {
  switch (c) {
    case Condition::Foreign:
      return {"not a tmlab result directory", result.filename().string()};
    case Condition::Dot:
    case Condition::EmptyString:
    case Condition::Home:
    case Condition::Root:
    case Condition::Ancestor:
      return {"a folder of its own"};
    case Condition::PreviousWithForeign:
      return {"mine.txt"};
    case Condition::CraftedMarker:
      return {".tmlab-result"};
    default:
      return {};
  }
}

/// Checks the outcome `r` of a run whose snapshots were `before` / `after` against `p.expect`.
void check_outcome(const Placement& p, Condition cond, const Result& r, const Snapshot& before,
                   const Snapshot& after) {
  const bool complete = r.status == 0 && incomplete(p.result).empty();
  // A refusal is an error (exit 1) or a usage error (exit 2, e.g. an empty --out), named, before
  // anything is created or changed.
  const bool refused = (r.status == 1 || r.status == 2) && lost_or_changed(before, after).empty() &&
                       created(before, after).empty();
  const bool failed = r.status == 1 && fs::exists(p.result / "FAILED") &&
                      !read_file(p.result / "FAILED").empty() && !fs::exists(p.result / "summary.json");
  switch (p.expect) {
    case Expect::Complete:
      EXPECT_TRUE(complete) << "exit " << r.status << ": " << incomplete(p.result) << "\n" << r.output;
      break;
    case Expect::CompleteOrRefused:
      EXPECT_TRUE(complete || refused) << "exit " << r.status << ": " << incomplete(p.result) << "\n"
                                       << created(before, after) << r.output;
      if (refused) {
        EXPECT_NE(r.output.find("a folder of its own"), std::string::npos) << r.output;
      }
      break;
    case Expect::Refused:
      EXPECT_TRUE(refused) << "exit " << r.status << "; not a refusal before computing:\n"
                           << lost_or_changed(before, after) << created(before, after) << r.output;
      for (const std::string& w : refusal_words(cond, p.result))
        EXPECT_NE(r.output.find(w), std::string::npos) << "the refusal does not name '" << w << "':\n"
                                                       << r.output;
      break;
    case Expect::FailedOrRefused:
      EXPECT_TRUE(failed || refused || complete)
          << "exit " << r.status << "; neither FAILED with the reason, nor refused, nor complete ("
          << incomplete(p.result) << "):\n"
          << r.output;
      EXPECT_EQ(r.output.find("HDF5-DIAG"), std::string::npos) << r.output;
      break;
  }
}

Placement ResultDirProperty::place(Condition cond, std::optional<PrivateTmpfs>& disk,
                                   std::optional<ScopedEnv>& home) {
  const bool own_folder = cmd_.sub.empty();  // --out names the result directory itself
  Placement p;
  p.result = world_ / "res" / (own_folder ? "out" : cmd_.sub);
  p.out = out_for(p.result);
  p.roots = {world_};
  switch (cond) {
    case Condition::Empty:
      fs::create_directories(p.result);
      break;
    case Condition::Foreign:
      plant_foreign(p.result);
      p.expect = Expect::Refused;
      break;
    case Condition::Symlink:
    case Condition::SymlinkOtherFs: {
      fs::path target = world_ / "elsewhere" / "target";
      if (cond == Condition::SymlinkOtherFs) {
        other_fs_ = fs::path("/dev/shm") / ("tmlab_props_" + std::to_string(::getpid()));
        if (!fs::is_directory("/dev/shm") || !other_file_system("/dev/shm", dir_)) {
          other_fs_ = dir_ / "tmpfs";
          disk.emplace(other_fs_, 64u << 20);
          if (!disk->problem().empty()) {
            skip_ = disk->problem();
            return p;
          }
        }
        target = other_fs_ / "target";
        p.roots.push_back(other_fs_);
      }
      fs::create_directories(target);
      write_file(target.parent_path() / "beside-target.txt", "someone's\n");
      fs::create_directories(p.result.parent_path());
      fs::create_directory_symlink(target, p.result);
      break;
    }
    case Condition::Dot:
      p.out = ".";
      p.result = result_of(p.out);
      p.expect = own_folder ? Expect::Refused : Expect::CompleteOrRefused;
      break;
    case Condition::EmptyString:
      p.out = "";
      p.result = result_of(own_folder ? "." : "");
      p.expect = Expect::Refused;
      break;
    case Condition::PreviousComplete:
    case Condition::PreviousWithForeign:
    case Condition::PreviousInterrupted:
      make_previous(p.result, cond == Condition::PreviousInterrupted);
      if (cond == Condition::PreviousWithForeign) {
        write_file(p.result / "mine.txt", "added by the user after the run\n");
        p.expect = Expect::Refused;
      }
      break;
    case Condition::CraftedMarker:
      fs::create_directories(p.result);
      write_file(p.result.parent_path() / "victim.txt", "must survive\n");
      write_file(world_ / "victim2.txt", "must survive too\n");
      write_file(p.result / "summary.json", "{}\n");
      write_file(
          p.result / ".tmlab-result",
          nlohmann::json{{"format", "tmlab-result/1"},
                         {"run_id", "crafted"},
                         {"files", {"../victim.txt", (world_ / "victim2.txt").string(), "summary.json"}}}
              .dump());
      p.expect = Expect::Refused;
      break;
    case Condition::FullDisk:
    case Condition::SmallDisk: {
      const fs::path mnt = world_ / "disk";
      disk.emplace(mnt, cond == Condition::FullDisk ? 128u << 10 : 64u << 10);
      if (!disk->problem().empty()) {
        skip_ = disk->problem();
        return p;
      }
      if (cond == Condition::FullDisk)
        fill_but_one_page(mnt / "filler.bin");  // someone's file: the quick results would fit in 128 KiB
      p.result = mnt / (own_folder ? "out" : cmd_.sub);
      p.out = out_for(p.result);
      p.expect = Expect::FailedOrRefused;
      break;
    }
    case Condition::Home:
      plant_foreign(world_ / "home");
      home.emplace("HOME", (world_ / "home").string());
      p.out = p.result = world_ / "home";
      p.expect = Expect::Refused;
      break;
    case Condition::Root:
      p.out = p.result = "/";
      p.expect = Expect::Refused;
      break;
    case Condition::Ancestor:
      p.out = "..";
      p.result = world_;
      p.expect = Expect::Refused;
      break;
  }
  return p;
}

TEST_P(ResultDirProperty, NothingForeignLostOutcomeCompleteRefusedOrFailed) {
  const Condition cond = GetParam().condition;
  std::optional<PrivateTmpfs> disk;
  std::optional<ScopedEnv> home;
  const Placement p = place(cond, disk, home);
  if (!skip_.empty()) GTEST_SKIP() << skip_;
  if (HasFatalFailure()) return;

  auto take = [&p] {
    Snapshot s;
    for (const auto& r : p.roots) {
      Snapshot part = snapshot(r);
      s.insert(part.begin(), part.end());
    }
    return s;
  };
  // Every file now in the world that tmlab did not write: the whole world, less what tmlab wrote
  // for a previous result (those it may replace; the user's file added to it it may not).
  const Snapshot before = take();
  Snapshot protected_files = before;
  for (const std::string& path : written_) protected_files.erase(path);
  std::set<std::string> root_names;
  if (cond == Condition::Root)
    for (const auto& e : fs::directory_iterator("/")) root_names.insert(e.path().string());

  SCOPED_TRACE(cmd_.id + " with its output at " + name_of(cond) + " ('" + p.out + "', result " +
               p.result.string() + ")");
  const Result r = tmlab_in(args(p.out), "run.log");
  const Snapshot after = take();

  // 1. Nothing tmlab did not write is removed or changed.
  EXPECT_EQ(lost_or_changed(protected_files, after), "") << r.output;
  if (cond == Condition::Root) {
    std::set<std::string> now;
    for (const auto& e : fs::directory_iterator("/")) now.insert(e.path().string());
    EXPECT_EQ(now, root_names) << "tmlab created or removed something in /\n" << r.output;
  }
  // 2. Never a RUNNING marker after the process ended; a symlink stays a symlink.
  for (const auto& root : p.roots) EXPECT_EQ(find_named(root, "RUNNING"), "") << r.output;
  if (cond == Condition::Symlink || cond == Condition::SymlinkOtherFs) {
    EXPECT_TRUE(fs::is_symlink(p.result)) << "the symlink was replaced\n" << r.output;
  }
  // 3. The outcome is exactly one of the three, and the one this condition calls for.
  check_outcome(p, cond, r, before, after);
}

INSTANTIATE_TEST_SUITE_P(CommandsTimesConditions, ResultDirProperty, ::testing::ValuesIn(params()),
                         [](const ::testing::TestParamInfo<Param>& i) {
                           return i.param.command + "_" + name_of(i.param.condition);
                         });

}  // namespace
