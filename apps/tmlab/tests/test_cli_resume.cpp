// Interrupted commands resume (issue 12): `tmlab verify`, `run`, `paper`, `hereditary`,
// `workprecision`, `depth-limit`, `fit`, `discover` and `discover --benchmark` stopped by SIGINT /
// SIGTERM, then `--resume`, must give the same results as an uninterrupted run, bit for bit except the
// wall-clock times; finished work is not done again.
//
// Where a run stops is deterministic: TMLAB_TEST_STOP_AFTER_PROGRESS=N[:SIGTERM] makes the driver
// raise the signal in itself right after its N-th checkpoint (core/base/interrupt.hpp), through the
// same handler a `kill` reaches. One test also sends a real signal from outside, with assertions that
// hold wherever it lands. Nothing here depends on how fast the machine is.
#include "cli_test_support.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/io/hdf5_file.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <csignal>
#include <cstring>
#include <fstream>
#include <map>
#include <random>

namespace {

namespace fs = std::filesystem;
using namespace tmlab::cli_test;  // run_argv, spawn, wait_for, wait_exit, Result
using tmlab::testing::read_file;

/// Sets the deterministic stop point for the drivers started while it lives.
class StopAfter {
 public:
  StopAfter(int checkpoints, int signal) {
    ::setenv("TMLAB_TEST_STOP_AFTER_PROGRESS",
             (std::to_string(checkpoints) + ":" + tmlab::signal_name(signal)).c_str(), 1);
  }
  ~StopAfter() { ::unsetenv("TMLAB_TEST_STOP_AFTER_PROGRESS"); }
  StopAfter(const StopAfter&) = delete;
  StopAfter& operator=(const StopAfter&) = delete;
};

class CliResume : public tmlab::testing::TempDirTest {
 protected:
  /// Four cases of the fast suite, a few seconds in all (one of them ~3 s, so signals land inside
  /// a case as well as between cases).
  std::vector<std::string> suite(const fs::path& results) const {
    return {"verify",
            "--case",
            "analytic-uniaxial-stvk",
            "--case",
            "analytic-hertz-traction",
            "--case",
            "sundials-dynamic-order",
            "--case",
            "kernel-patch-test",
            "--no-plots",
            "--results",
            results.string()};
  }

  /// verification.json without what depends on the clock (case and suite times).
  static nlohmann::json without_times(const fs::path& dir) {
    nlohmann::json j = nlohmann::json::parse(read_file(dir / "verification" / "verification.json"));
    strip(j);
    return j;
  }
  static void strip(nlohmann::json& j) {
    if (j.is_object()) {
      for (const char* k : {"seconds", "wall_seconds", "generated_utc", "command_line"}) j.erase(k);
      for (auto& v : j) strip(v);
    } else if (j.is_array()) {
      for (auto& v : j) strip(v);
    }
  }
};

TEST_F(CliResume, InterruptedSuiteResumesToTheSameResult) {
  const fs::path ref = dir_ / "uninterrupted";
  const auto full = run_argv(suite(ref), dir_ / "full.log");
  ASSERT_EQ(full.status, 0) << full.output;
  const nlohmann::json expected = without_times(ref);

  // Stopped after the first and the third case; the first also stopped a second time on
  // resuming (after one more case). The resumed runs take the finished cases from the checkpoint.
  for (const auto& [first, second] : std::vector<std::pair<int, int>>{{1, 0}, {1, 1}, {3, 0}}) {
    SCOPED_TRACE("stopped after case " + std::to_string(first) + (second ? " and again after one more" : ""));
    const fs::path res = dir_ / ("after-" + std::to_string(first) + "-" + std::to_string(second));
    {
      const StopAfter stop(first, SIGINT);
      const auto cut = run_argv(suite(res), dir_ / "a.log");
      ASSERT_EQ(cut.status, 128 + SIGINT) << cut.output;
    }
    ASSERT_TRUE(fs::exists(res / "verification" / "INTERRUPTED")) << read_file(dir_ / "a.log");
    EXPECT_NE(read_file(res / "verification" / "INTERRUPTED").find("--resume"), std::string::npos);
    EXPECT_FALSE(fs::exists(res / "verification" / "summary.json"));
    std::vector<std::string> args = suite(res);
    args.push_back("--resume");
    if (second) {
      const StopAfter stop(second, SIGTERM);
      const auto again = run_argv(args, dir_ / "a2.log");
      ASSERT_EQ(again.status, 128 + SIGTERM) << again.output;
    }
    const auto resumed = run_argv(args, dir_ / "a3.log");
    ASSERT_EQ(resumed.status, 0) << resumed.output;
    EXPECT_NE(resumed.output.find("... PASS (from the checkpoint"), std::string::npos) << resumed.output;
    EXPECT_EQ(without_times(res), expected);
    EXPECT_FALSE(fs::exists(res / "verification.checkpoint.h5")) << "a complete report leaves no checkpoint";
  }

  // A real SIGINT from outside once the first checkpoint exists. Where it lands depends on the
  // machine, so the assertions hold for every outcome: finished, or interrupted and resumable.
  {
    const fs::path res = dir_ / "killed";
    const pid_t pid = spawn(suite(res), dir_ / "k.log");
    ASSERT_TRUE(wait_for(res / "verification.checkpoint.h5")) << read_file(dir_ / "k.log");
    ::kill(pid, SIGINT);
    const int rc = wait_exit(pid);
    ASSERT_TRUE(rc == 0 || rc == 128 + SIGINT) << rc << "\n" << read_file(dir_ / "k.log");
    if (rc != 0) {
      std::vector<std::string> args = suite(res);
      args.push_back("--resume");
      const auto resumed = run_argv(args, dir_ / "k2.log");
      ASSERT_EQ(resumed.status, 0) << resumed.output;
    }
    EXPECT_EQ(without_times(res), expected);
  }
}

TEST_F(CliResume, ResumeWithoutCheckpointOrWithAnotherSuiteIsRefused) {
  std::vector<std::string> args = suite(dir_ / "res");
  args.push_back("--resume");
  auto r = run_argv(args, dir_ / "1.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("--resume: no checkpoint"), std::string::npos) << r.output;

  // A checkpoint of another selection.
  const fs::path res = dir_ / "res2";
  {
    const StopAfter stop(1, SIGINT);
    const auto cut = run_argv(suite(res), dir_ / "2.log");
    ASSERT_EQ(cut.status, 128 + SIGINT) << cut.output;
  }
  r = run_argv({"verify", "--case", "kernel-patch-test", "--no-plots", "--results", res.string(), "--resume"},
               dir_ / "3.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("of a different suite"), std::string::npos) << r.output;
}

TEST_F(CliResume, InterruptedPaperFigureReusesItsFinishedRuns) {
  // fig7 reduced to two short runs (two schemes, one cycle of 40 steps).
  auto params =
      nlohmann::json::parse(read_file(fs::path(TMLAB_SOURCE_DIR) / "cases" / "paper" / "xu2011_liver.json"),
                            nullptr, true, /*ignore_comments=*/true);
  params["schemes"] = {"objective", "xu2011"};
  params["fig7"]["periods"] = {1.0};
  params["fig7"]["steps_per_cycle"] = 40;
  const fs::path pf = dir_ / "params.json";
  std::ofstream(pf) << params.dump();
  auto cmd = [&](const fs::path& res) {
    return std::vector<std::string>{"paper", "fig7", "--params", pf.string(), "--results", res.string()};
  };
  const auto full = run_argv(cmd(dir_ / "full"), dir_ / "full.log");
  ASSERT_EQ(full.status, 0) << full.output;
  const auto expected =
      nlohmann::json::parse(read_file(dir_ / "full" / "paper" / "fig7" / "fig7_energy.json"));
  ASSERT_EQ(expected.size(), 2u);

  // Stopped right after the first of the two runs finished.
  const fs::path res = dir_ / "cut", fig = res / "paper" / "fig7";
  {
    const StopAfter stop(1, SIGINT);
    const auto cut = run_argv(cmd(res), dir_ / "cut.log");
    ASSERT_EQ(cut.status, 128 + SIGINT) << cut.output;
  }
  EXPECT_NE(read_file(fig / "INTERRUPTED").find("--resume"), std::string::npos)
      << read_file(fig / "INTERRUPTED");
  EXPECT_FALSE(fs::exists(fig / "fig7.png"));

  std::vector<std::string> args = cmd(res);
  args.push_back("--resume");
  const auto resumed = run_argv(args, dir_ / "resumed.log");
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("finished before the interruption: reused"), std::string::npos)
      << resumed.output;
  EXPECT_EQ(nlohmann::json::parse(read_file(fig / "fig7_energy.json")), expected);
  EXPECT_TRUE(fs::exists(fig / "summary.json"));

  // Nothing to resume now: refused.
  EXPECT_EQ(run_argv(args, dir_ / "again.log").status, 1);
}

// ---- tmlab run --resume -----------------------------------------------------------------------

/// Every dataset of an HDF5 file, by path, as raw float64 (int datasets converted exactly).
void collect_datasets(const tmlab::H5File& f, const std::string& group,
                      std::map<std::string, std::vector<double>>& out) {
  for (const std::string& name : f.list(group)) {
    const std::string path = (group == "/" ? "" : group) + "/" + name;
    bool is_group = true;
    try {
      (void)f.list(path);
    } catch (const tmlab::Error&) {
      is_group = false;
    }
    if (is_group)
      collect_datasets(f, path, out);
    else
      out[path] = f.read_double(path);
  }
}

/// Differences between two HDF5 files, dataset by dataset, bit for bit ("" when identical).
std::string h5_differences(const fs::path& a, const fs::path& b) {
  std::map<std::string, std::vector<double>> da, db;
  collect_datasets(tmlab::H5File::open_read(a.string()), "/", da);
  collect_datasets(tmlab::H5File::open_read(b.string()), "/", db);
  std::string out;
  for (const auto& [name, v] : da) {
    const auto it = db.find(name);
    if (it == db.end())
      out += name + " missing; ";
    else if (v.size() != it->second.size() ||
             (!v.empty() && std::memcmp(v.data(), it->second.data(), 8 * v.size())))
      out += name + " differs; ";
  }
  for (const auto& [name, v] : db)
    if (!da.count(name)) out += name + " extra; ";
  if (da.empty()) out += "no datasets at all; ";
  return out;
}

/// summary.json without what depends on the clock.
nlohmann::json summary_without_times(const fs::path& dir) {
  nlohmann::json j = nlohmann::json::parse(read_file(dir / "summary.json"));
  for (const char* k : {"run_seconds", "wall_seconds", "started_utc", "finished_utc"}) j.erase(k);
  return j;
}

/// Compares two complete run directories: every HDF5 dataset, summary.json except times, and every
/// other file byte for byte except manifest.json (times and the command line) and the ownership
/// marker (its run id and time; its file list must agree).
void expect_same_run(const fs::path& ref, const fs::path& got) {
  ASSERT_TRUE(fs::exists(got / "summary.json")) << got;
  EXPECT_FALSE(fs::exists(got / "checkpoint.h5")) << "a complete result holds no checkpoint";
  EXPECT_EQ(summary_without_times(ref), summary_without_times(got));
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(ref)) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), ref);
    if (rel == "summary.json" || rel == "manifest.json") continue;
    if (rel == ".tmlab-result") {  // the ownership marker: its run id and time differ, its file list not
      const auto listed = [](const fs::path& m) { return nlohmann::json::parse(read_file(m))["files"]; };
      EXPECT_EQ(listed(e.path()), listed(got / rel));
      continue;
    }
    ASSERT_TRUE(fs::exists(got / rel)) << rel;
    ++files;
    if (rel.extension() == ".h5")
      EXPECT_EQ(h5_differences(e.path(), got / rel), "") << rel;
    else
      EXPECT_TRUE(read_file(e.path()) == read_file(got / rel)) << rel;
  }
  EXPECT_GE(files, 5);
}

class CliRunResume : public tmlab::testing::TempDirTest {
 protected:
  /// A viscoelastic cantilever case of `solver` with field frames, written to dir_.
  fs::path write_case(const std::string& name, const nlohmann::json& solver, int every) const {
    nlohmann::json c = {
        {"name", name},
        {"mesh", {{"file", (fs::path(TMLAB_SOURCE_DIR) / "meshes" / "beam_40x10x10mm.msh").string()}}},
        {"material",
         {{"E", 100000},
          {"nu", 0.3},
          {"density", 1000},
          {"viscoelastic",
           {{"scheme", "objective"},
            {"prony",
             {{"convention", "instantaneous"},
              {"terms", {{{"weight", 0.3}, {"tau", 0.05}}, {{"weight", 0.2}, {"tau", 0.5}}}}}}}}}},
        {"boundary", {{{"name", "clamp"}, {"nodes", {{"group", "xmin"}}}}}},
        {"loads",
         {{{"type", "gravity"},
           {"acceleration", {0, 0, -9.81}},
           {"function", {{"type", "ramp"}, {"t0", 0}, {"t1", 0.2}}}}}},
        {"solver", solver},
        {"output", {{"every", every}, {"probes", {{{"name", "tip"}, {"point", {0.04, 0.005, 0.005}}}}}}}};
    const fs::path f = dir_ / (name + ".json");
    std::ofstream(f) << c.dump(2);
    return f;
  }
  std::vector<std::string> cmd(const fs::path& c, const fs::path& res, const std::string& every = "1") const {
    return {"run", c.string(), "--no-plots", "--results", res.string(), "--checkpoint-every", every};
  }
  /// Runs the case uninterrupted, then `trials` times: start, stop after a fixed-seed random number
  /// (1-4) of checkpoints (SIGINT or SIGTERM), resume and stop again the same way, resume to the end;
  /// every result must equal the uninterrupted one.
  void check(const fs::path& c, const std::string& name, int trials, std::mt19937& rng,
             const std::string& every) {
    const fs::path ref = dir_ / ("ref-" + name);
    const auto full =
        run_argv({"run", c.string(), "--no-plots", "--results", ref.string()}, dir_ / "full.log");
    ASSERT_EQ(full.status, 0) << full.output;
    std::uniform_int_distribution<int> checkpoints(1, 4);
    for (int trial = 0; trial < trials; ++trial) {
      const fs::path res = dir_ / (name + "-" + std::to_string(trial));
      const fs::path result = res / name;
      std::vector<std::string> args = cmd(c, res, every);
      for (int leg = 0; leg < 2; ++leg) {
        const int sig = (trial + leg) % 2 ? SIGTERM : SIGINT;
        const int n = checkpoints(rng);
        SCOPED_TRACE(name + " trial " + std::to_string(trial) + " leg " + std::to_string(leg) + ": " +
                     tmlab::signal_name(sig) + " after checkpoint " + std::to_string(n));
        const fs::path log = dir_ / (name + "-leg" + std::to_string(leg) + ".log");
        {
          const StopAfter stop(n, sig);
          const auto r = run_argv(args, log);
          ASSERT_EQ(r.status, 128 + sig) << r.output;
          if (leg == 1) {
            EXPECT_NE(r.output.find("tmlab: resuming"), std::string::npos) << r.output;
          }
        }
        const std::string marker = read_file(result / "INTERRUPTED");
        EXPECT_NE(marker.find(tmlab::signal_name(sig)), std::string::npos) << marker;
        EXPECT_NE(marker.find("checkpoint after step"), std::string::npos) << marker;
        EXPECT_NE(marker.find("--resume"), std::string::npos) << marker;
        EXPECT_FALSE(fs::exists(result / "summary.json"));
        EXPECT_FALSE(fs::exists(result / "RUNNING"));
        if (leg == 0) args.push_back("--resume");
      }
      const auto r = run_argv(args, dir_ / (name + "-last.log"));  // the last leg runs to the end
      ASSERT_EQ(r.status, 0) << r.output;
      expect_same_run(ref / name, result);
    }
  }
};

TEST_F(CliRunResume, InterruptedRunsResumeBitIdentical) {
  std::mt19937 rng(20261125);  // fixed: the same moments on every run of the test
  const fs::path st = write_case("resume-static", {{"type", "static"}, {"steps", 60}, {"t_end", 0.6}}, 7);
  const fs::path im = write_case(
      "resume-implicit", {{"type", "implicit"}, {"scheme", "newmark"}, {"dt", 0.005}, {"t_end", 0.4}}, 9);
  const fs::path ex =
      write_case("resume-explicit",
                 {{"type", "explicit"}, {"dt", 5e-5}, {"t_end", 0.1}, {"damping", {{"alpha", 50}}}}, 300);
  check(st, "resume-static", 2, rng, "1");
  check(im, "resume-implicit", 2, rng, "1");
  check(ex, "resume-explicit", 2, rng, "50");
}

TEST_F(CliRunResume, InterruptedContactRunsResumeBitIdentical) {
  // A rigid sphere pressed into the top of a viscoelastic unit cube (125 nodes): the contact state a
  // resumed run needs (augmented-Lagrangian multipliers, the candidate set the next increment's
  // search keeps, the kinematic contact's glued nodes, the outputs and the per-step contact log)
  // changes at every step, so a checkpoint that missed any of it would not resume bit for bit.
  auto write = [&](const std::string& name, const nlohmann::json& solver) {
    const nlohmann::json c = {
        {"name", name},
        {"mesh", {{"file", (fs::path(TMLAB_SOURCE_DIR) / "meshes" / "cube_n4.msh").string()}}},
        {"material",
         {{"E", 3000},
          {"nu", 0.4},
          {"density", 1000},
          {"viscoelastic",
           {{"scheme", "objective"},
            {"prony",
             {{"convention", "instantaneous"},
              {"terms", {{{"weight", 0.3}, {"tau", 0.05}}, {{"weight", 0.2}, {"tau", 0.5}}}}}}}}}},
        {"boundary", {{{"name", "bottom"}, {"nodes", {{"group", "zmin"}}}}}},
        {"contact",
         {{"bodies",
           {{{"name", "indenter"},
             {"type", "sphere"},
             {"center", {0.5, 0.5, 1.5}},
             {"radius", 0.5},
             {"displacement", {0, 0, -0.12}},
             {"function", {{"type", "ramp"}, {"t0", 0}, {"t1", 0.2}}}}}}}},
        {"solver", solver},
        {"output", {{"every", 3}, {"probes", {{{"name", "top"}, {"point", {0.5, 0.5, 1.0}}}}}}}};
    const fs::path f = dir_ / (name + ".json");
    std::ofstream(f) << c.dump(2);
    return f;
  };
  std::mt19937 rng(20261126);
  check(write("contact-static", {{"type", "static"}, {"steps", 12}, {"t_end", 0.3}}), "contact-static", 2,
        rng, "1");
  check(
      write("contact-implicit", {{"type", "implicit"}, {"scheme", "newmark"}, {"dt", 0.01}, {"t_end", 0.3}}),
      "contact-implicit", 1, rng, "1");
  check(write("contact-explicit",
              {{"type", "explicit"}, {"dt", 1e-3}, {"t_end", 0.3}, {"damping", {{"alpha", 50}}}}),
        "contact-explicit", 1, rng, "40");
}

TEST_F(CliRunResume, ResumeOfAnotherCaseOrWithoutCheckpointIsRefused) {
  const fs::path st = write_case("resume-refuse", {{"type", "static"}, {"steps", 200}, {"t_end", 0.6}}, 50);
  const fs::path res = dir_ / "res";
  auto r =
      run_argv({"run", st.string(), "--no-plots", "--results", res.string(), "--resume"}, dir_ / "0.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("no checkpoint"), std::string::npos) << r.output;

  {
    const StopAfter stop(1, SIGINT);
    r = run_argv(cmd(st, res), dir_ / "1.log");
    ASSERT_EQ(r.status, 128 + SIGINT) << r.output;
  }
  // The same name, another time step: refused, naming the key; the interrupted run stays resumable.
  const fs::path other =
      write_case("resume-refuse", {{"type", "static"}, {"steps", 100}, {"t_end", 0.6}}, 50);
  r = run_argv({"run", other.string(), "--no-plots", "--results", res.string(), "--resume"}, dir_ / "2.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("solver.steps: the checkpoint has 200, this run 100"), std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::exists(res / "resume-refuse" / "INTERRUPTED"));
  r = run_argv({"run", "cube-uniaxial", "--model", "reference", "--resume"}, dir_ / "3.log");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("the deal.II reference has no checkpoints"), std::string::npos) << r.output;
}

// ---- tmlab hereditary / workprecision --resume -------------------------------------------------

/// `j` without the keys that hold clock times.
void strip_times(nlohmann::json& j) {
  if (j.is_object()) {
    for (const char* k :
         {"seconds", "wall_seconds", "cpu_seconds", "run_seconds", "started_utc", "finished_utc"})
      j.erase(k);
    for (auto& v : j) strip_times(v);
  } else if (j.is_array()) {
    for (auto& v : j) strip_times(v);
  }
}

/// h5_differences without the datasets whose names end in one of `timed` (CPU and wall times).
std::string h5_differences_except(const fs::path& a, const fs::path& b,
                                  const std::vector<std::string>& timed) {
  std::map<std::string, std::vector<double>> da, db;
  collect_datasets(tmlab::H5File::open_read(a.string()), "/", da);
  collect_datasets(tmlab::H5File::open_read(b.string()), "/", db);
  auto is_timed = [&](const std::string& n) {
    for (const auto& t : timed)
      if (n.size() >= t.size() && n.compare(n.size() - t.size(), t.size(), t) == 0) return true;
    return false;
  };
  std::string out;
  int compared = 0;
  for (const auto& [name, v] : da) {
    if (is_timed(name)) continue;
    ++compared;
    const auto it = db.find(name);
    if (it == db.end())
      out += name + " missing; ";
    else if (v.size() != it->second.size() ||
             (!v.empty() && std::memcmp(v.data(), it->second.data(), 8 * v.size())))
      out += name + " differs; ";
  }
  if (da.size() != db.size()) out += "different dataset counts; ";
  if (compared == 0) out += "nothing compared; ";
  return out;
}

/// Runs a study uninterrupted, then stopped by `sig` after its `n`-th checkpoint and resumed; the
/// results must agree.
void check_study(const fs::path& tmp, const std::vector<std::string>& args, const std::string& sub,
                 const std::string& h5, int sig, int n) {
  SCOPED_TRACE(sub + " stopped by " + tmlab::signal_name(sig) + " after checkpoint " + std::to_string(n));
  auto with = [&](const fs::path& res, bool resume) {
    std::vector<std::string> a = args;
    a.insert(a.end(), {"--no-plots", "--results", res.string()});
    if (resume) a.push_back("--resume");
    return a;
  };
  const fs::path ref = tmp / (sub + "-ref"), cut = tmp / (sub + "-cut");
  fs::remove_all(ref);
  fs::remove_all(cut);
  const auto full = run_argv(with(ref, false), tmp / (sub + "-ref.log"));
  ASSERT_EQ(full.status, 0) << full.output;
  {
    const StopAfter stop(n, sig);
    const auto r = run_argv(with(cut, false), tmp / (sub + "-cut.log"));
    ASSERT_EQ(r.status, 128 + sig) << r.output;
  }
  const std::string marker = read_file(cut / sub / "INTERRUPTED");
  EXPECT_NE(marker.find("--resume"), std::string::npos) << marker;
  const auto resumed = run_argv(with(cut, true), tmp / (sub + "-resumed.log"));
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("from the checkpoint of the interrupted study"), std::string::npos)
      << resumed.output;
  EXPECT_FALSE(fs::exists(cut / sub / "checkpoint.h5"));
  EXPECT_EQ(h5_differences_except(ref / sub / h5, cut / sub / h5, {"cpu_seconds", "wall_seconds"}), "");
  nlohmann::json a = nlohmann::json::parse(read_file(ref / sub / "summary.json"));
  nlohmann::json b = nlohmann::json::parse(read_file(cut / sub / "summary.json"));
  strip_times(a);
  strip_times(b);
  EXPECT_EQ(a, b);
}

class CliStudyResume : public tmlab::testing::TempDirTest {};

TEST_F(CliStudyResume, InterruptedStudiesResume) {
  check_study(dir_, {"hereditary", "--quick", "--no-liver"}, "hereditary", "hereditary.h5", SIGINT, 1);
  check_study(dir_, {"workprecision", "--quick", "--problem", "incompressible"}, "workprecision",
              "workprecision.h5", SIGTERM, 1);  // after the reference solution
  check_study(dir_, {"hereditary", "--quick", "--no-liver", "--histories", "sine"}, "hereditary",
              "hereditary.h5", SIGTERM, 2);
  check_study(dir_, {"workprecision", "--quick", "--problem", "incompressible"}, "workprecision",
              "workprecision.h5", SIGINT, 4);
  // Another configuration is refused, naming the key.
  const fs::path res = dir_ / "other";
  {
    const StopAfter stop(1, SIGINT);
    const auto r = run_argv({"hereditary", "--quick", "--no-liver", "--no-plots", "--results", res.string()},
                            dir_ / "o.log");
    ASSERT_EQ(r.status, 128 + SIGINT) << r.output;
  }
  const auto r = run_argv({"hereditary", "--quick", "--no-liver", "--seed", "5", "--no-plots", "--results",
                           res.string(), "--resume"},
                          dir_ / "o2.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("seed: the checkpoint has 20111101, this run 5"), std::string::npos) << r.output;
}

// ---- tmlab fit / discover --resume ---------------------------------------------------------------

/// A JSON file without the keys that hold clock times.
nlohmann::json json_without_times(const fs::path& file) {
  nlohmann::json j = nlohmann::json::parse(read_file(file));
  strip_times(j);
  return j;
}

class CliFitResume : public tmlab::testing::TempDirTest {
 protected:
  /// The silicone phantom in the tmlab-measured/1 format.
  fs::path phantom() const {
    const fs::path csv = dir_ / "data" / "EF10_0T_A1.csv";
    if (fs::exists(csv)) return csv;
    const auto r = run_argv(
        {"data", "convert", tmlab::cli_test::phantom_a1().string(), "--out", (dir_ / "data").string()},
        dir_ / "convert.log");
    EXPECT_EQ(r.status, 0) << r.output;
    return csv;
  }

  /// Runs `args` + --out uninterrupted into dir_/<name>-ref, then for each leg of `legs` (the
  /// checkpoint after which the driver stops, and the signal) stopped there, every leg after the
  /// first with --resume, and at last resumed to the end; `files` must then equal the uninterrupted
  /// run's (JSON without the clock times, HDF5 dataset for dataset, bit for bit).
  void check(const std::string& name, const std::vector<std::string>& args,
             const std::vector<std::pair<int, int>>& legs, const std::vector<std::string>& files) {
    auto with = [&](const fs::path& out, bool resume) {
      std::vector<std::string> a = args;
      a.insert(a.end(), {"--out", out.string(), "--checkpoint-every", "1"});
      if (resume) a.push_back("--resume");
      return a;
    };
    const fs::path ref = dir_ / (name + "-ref"), cut = dir_ / name;
    std::vector<std::string> plain = args;  // the reference keeps the default schedule
    plain.insert(plain.end(), {"--out", ref.string()});
    const auto full = run_argv(plain, dir_ / (name + "-ref.log"));
    ASSERT_EQ(full.status, 0) << full.output;
    for (std::size_t leg = 0; leg < legs.size(); ++leg) {
      const auto [n, sig] = legs[leg];
      SCOPED_TRACE(name + " leg " + std::to_string(leg) + ": " + tmlab::signal_name(sig) +
                   " after checkpoint " + std::to_string(n));
      const StopAfter stop(n, sig);
      const auto r = run_argv(with(cut, leg > 0), dir_ / (name + "-leg.log"));
      ASSERT_EQ(r.status, 128 + sig) << r.output;
      if (leg > 0) {
        EXPECT_NE(r.output.find("resuming from"), std::string::npos) << r.output;
      }
      const std::string marker = read_file(cut / "INTERRUPTED");
      EXPECT_NE(marker.find(tmlab::signal_name(sig)), std::string::npos) << marker;
      EXPECT_NE(marker.find("checkpoint after"), std::string::npos) << marker;
      EXPECT_NE(marker.find("continue with the same command and --resume"), std::string::npos) << marker;
      EXPECT_FALSE(fs::exists(cut / "summary.json"));
      EXPECT_TRUE(fs::exists(cut / ".incomplete" / "checkpoint.h5"));
    }
    const auto last = run_argv(with(cut, true), dir_ / (name + "-last.log"));
    ASSERT_EQ(last.status, 0) << last.output;
    EXPECT_NE(last.output.find("taken from it"), std::string::npos) << last.output;
    ASSERT_TRUE(fs::exists(cut / "summary.json"));
    EXPECT_FALSE(fs::exists(cut / "checkpoint.h5")) << "a complete result holds no checkpoint";
    EXPECT_FALSE(fs::exists(cut / ".incomplete"));
    for (const auto& f : files) {
      SCOPED_TRACE(f);
      if (fs::path(f).extension() == ".h5")
        EXPECT_EQ(h5_differences_except(ref / f, cut / f, {}), "");
      else
        EXPECT_EQ(json_without_times(ref / f), json_without_times(cut / f));
    }
    nlohmann::json a = json_without_times(ref / "summary.json"), b = json_without_times(cut / "summary.json");
    EXPECT_EQ(a, b);
  }
};

TEST_F(CliFitResume, InterruptedFitsResumeBitIdentical) {
  // Multi-start: 14 units (the global stage, 3 local runs, 10 profile-likelihood points). Stopped
  // after the global stage; inside the local stage; and in the profile, then again on resuming.
  const std::vector<std::string> fit = {
      "fit", phantom().string(), "--model", "mooney_rivlin,poisson=0.49", "--starts", "6", "--local-runs",
      "3",   "--no-plots",       "--quiet"};
  check("fit-1", fit, {{1, SIGINT}}, {"fit.json", "fit.h5"});
  check("fit-3", fit, {{3, SIGTERM}}, {"fit.json", "fit.h5"});
  check("fit-6-2", fit, {{6, SIGINT}, {2, SIGTERM}}, {"fit.json", "fit.h5"});
  // Simulated annealing: the annealed start is restored with the global stage.
  std::vector<std::string> siman = fit;
  siman.insert(siman.end(), {"--global", "siman", "--siman-evaluations", "300", "--no-profile"});
  check("siman-2", siman, {{2, SIGTERM}}, {"fit.json", "fit.h5"});
}

TEST_F(CliFitResume, ARealSignalWithoutScheduledCheckpointsLeavesOneAtTheStop) {
  // --checkpoint-every off: the only checkpoint is the one written at the stop (the latest finished
  // unit). A real SIGINT from outside once the local stage has begun; where it lands depends on the
  // machine, so the assertions hold for every outcome: finished, or interrupted with a checkpoint
  // that resumes to the uninterrupted result.
  const std::vector<std::string> fit = {
      "fit", phantom().string(), "--model", "mooney_rivlin,poisson=0.49", "--starts", "12", "--no-plots"};
  auto with = [&](const fs::path& out, std::vector<std::string> extra) {
    std::vector<std::string> a = fit;
    a.insert(a.end(), {"--out", out.string()});
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  const fs::path ref = dir_ / "ref", cut = dir_ / "cut", log = dir_ / "cut.log";
  ASSERT_EQ(run_argv(with(ref, {}), dir_ / "ref.log").status, 0);
  const pid_t pid = spawn(with(cut, {"--checkpoint-every", "off"}), log);
  bool started = false;
  for (int i = 0; i < 15000 && !started; ++i) {  // up to 5 minutes on a busy machine
    started = fs::exists(log) && read_file(log).find("local stage from start") != std::string::npos;
    if (!started) ::usleep(20000);
  }
  ASSERT_TRUE(started) << read_file(log);
  ::kill(pid, SIGINT);
  const int rc = wait_exit(pid);
  ASSERT_TRUE(rc == 0 || rc == 128 + SIGINT) << rc << "\n" << read_file(log);
  if (rc != 0) {
    const std::string marker = read_file(cut / "INTERRUPTED");
    EXPECT_NE(marker.find("checkpoint after the global stage"), std::string::npos) << marker;
    const auto r = run_argv(with(cut, {"--resume"}), dir_ / "resumed.log");
    ASSERT_EQ(r.status, 0) << r.output;
  }
  EXPECT_EQ(json_without_times(ref / "fit.json"), json_without_times(cut / "fit.json"));
  EXPECT_EQ(h5_differences_except(ref / "fit.h5", cut / "fit.h5", {}), "");
}

TEST_F(CliFitResume, ResumeOfAnotherFitOrWithoutCheckpointIsRefused) {
  const fs::path csv = phantom(), out = dir_ / "fit";
  const std::vector<std::string> fit = {"fit",        csv.string(), "--model", "mooney_rivlin,poisson=0.49",
                                        "--no-plots", "--quiet",    "--out",   out.string()};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = fit;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  auto r = run_argv(with({"--resume"}), dir_ / "0.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("--resume: no checkpoint"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out)) << "a refused resume creates nothing";
  {
    const StopAfter stop(2, SIGINT);
    r = run_argv(with({"--checkpoint-every", "1"}), dir_ / "1.log");
    ASSERT_EQ(r.status, 128 + SIGINT) << r.output;
  }
  // Other options: refused naming the key; the interrupted fit stays resumable.
  r = run_argv(with({"--seed", "2", "--resume"}), dir_ / "2.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("seed: the checkpoint has 1, this run 2"), std::string::npos) << r.output;
  r = run_argv(with({"--threads", "1", "--resume"}), dir_ / "3.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("threads: the checkpoint has 2, this run 1"), std::string::npos) << r.output;
  // Other data (the same name, one force changed): refused.
  const fs::path other = dir_ / "other";
  fs::create_directories(other);
  fs::copy_file(csv.parent_path() / "EF10_0T_A1.json", other / "EF10_0T_A1.json");
  {
    std::string text = read_file(csv);
    const std::size_t last_digit = text.find_last_of("0123456789");
    text[last_digit] = text[last_digit] == '1' ? '2' : '1';
    std::ofstream(other / "EF10_0T_A1.csv") << text;
  }
  std::vector<std::string> a = fit;
  a[1] = (other / "EF10_0T_A1.csv").string();
  a.push_back("--resume");
  r = run_argv(a, dir_ / "4.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("data.csv: the checkpoint has"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "INTERRUPTED"));
  EXPECT_TRUE(fs::exists(out / ".incomplete" / "checkpoint.h5"));
  // Resumed to the end; then nothing is left to resume.
  r = run_argv(with({"--resume"}), dir_ / "5.log");
  ASSERT_EQ(r.status, 0) << r.output;
  r = run_argv(with({"--resume"}), dir_ / "6.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(fs::exists(out / "summary.json")) << "a refused resume leaves the complete fit";
}

TEST_F(CliFitResume, InterruptedDiscoveryResumesToTheSameReport) {
  // One round on the phantom: the baseline, then each applicable effect's fit and the held-out
  // folds of the best ones, each fit a unit. Stopped after the baseline; and later, then again.
  const std::vector<std::string> disc = {
      "discover", phantom().string(), "--max-samples", "150", "--rounds", "1", "--starts",
      "4",        "--no-plots",       "--quiet"};
  check("discover-1", disc, {{1, SIGINT}}, {"report.json", "discover.h5"});
  check("discover-5-3", disc, {{5, SIGTERM}, {3, SIGINT}}, {"report.json", "discover.h5"});
}

TEST_F(CliFitResume, InterruptedBenchmarkResumesToTheSameResult) {
  // Two quick benchmark sets, a checkpoint after each.
  const std::vector<std::string> bench = {
      "discover", "--benchmark", "--quick",  "--only", "noise_only,contact_offset",
      "--rounds", "1",           "--starts", "2",      "--max-samples",
      "200",      "--quiet"};
  check("bench-1", bench, {{1, SIGTERM}}, {"benchmark.json"});
  // Resumed with another selection of sets: refused, naming the key.
  const fs::path out = dir_ / "bench-other";
  std::vector<std::string> args = bench;
  args.insert(args.end(), {"--out", out.string(), "--checkpoint-every", "1"});
  {
    const StopAfter stop(1, SIGINT);
    const auto r = run_argv(args, dir_ / "other-cut.log");
    ASSERT_EQ(r.status, 128 + SIGINT) << r.output;
  }
  args[4] = "noise_only";
  args.push_back("--resume");
  const auto r = run_argv(args, dir_ / "other.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("(only: the checkpoint has \"noise_only,contact_offset\", this run \"noise_only\""),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::exists(out / "INTERRUPTED"));
}

/// `tmlab depth-limit`: a checkpoint after every finished (law, mesh) run. Four small runs (St VK, whose
/// solve fails on the n = 4 mesh between 2.0 and 2.5 mm, and neo-Hookean, on 3 and 4 cells per
/// axis), stopped after the first and after the third run, resumed: depth_limit.json and summary.json
/// equal the uninterrupted study's except the clock times.
TEST_F(CliStudyResume, InterruptedInversionStudyResumes) {
  const std::vector<std::string> args = {"depth-limit", "--laws",      "stvk,neo_hookean", "--cells",
                                         "3,4",         "--max-depth", "0.0025",           "--increment",
                                         "0.0005",      "--no-plots"};
  auto with = [&](const fs::path& res, bool resume) {
    std::vector<std::string> a = args;
    a.insert(a.end(), {"--results", res.string()});
    if (resume) a.push_back("--resume");
    return a;
  };
  auto result = [](const fs::path& res) {
    nlohmann::json j = {
        {"inversion", nlohmann::json::parse(read_file(res / "depth-limit" / "depth_limit.json"))},
        {"summary", nlohmann::json::parse(read_file(res / "depth-limit" / "summary.json"))}};
    strip_times(j);
    return j;
  };
  const fs::path ref = dir_ / "inversion-ref";
  const auto full = run_argv(with(ref, false), dir_ / "inv-ref.log");
  ASSERT_EQ(full.status, 0) << full.output;
  const nlohmann::json expected = result(ref);
  ASSERT_EQ(expected["inversion"]["runs"].size(), 4u);
  // The checkpoint must carry every kind of outcome: St VK fails on the n = 4 mesh.
  EXPECT_EQ(expected["inversion"]["runs"][1]["outcome"], "solver_failed") << expected.dump(1);

  for (const auto& [n, sig] : std::vector<std::pair<int, int>>{{1, SIGINT}, {3, SIGTERM}}) {
    SCOPED_TRACE("stopped by " + tmlab::signal_name(sig) + " after run " + std::to_string(n));
    const fs::path cut = dir_ / ("inversion-cut" + std::to_string(n));
    {
      const StopAfter stop(n, sig);
      const auto r = run_argv(with(cut, false), dir_ / "inv-cut.log");
      ASSERT_EQ(r.status, 128 + sig) << r.output;
    }
    EXPECT_FALSE(fs::exists(cut / "depth-limit" / "summary.json"));
    const std::string marker = read_file(cut / "depth-limit" / "INTERRUPTED");
    EXPECT_NE(marker.find("--resume"), std::string::npos) << marker;
    const auto resumed = run_argv(with(cut, true), dir_ / "inv-resumed.log");
    ASSERT_EQ(resumed.status, 0) << resumed.output;
    EXPECT_NE(resumed.output.find("stvk.n3: from the checkpoint of the interrupted study"), std::string::npos)
        << resumed.output;
    EXPECT_FALSE(fs::exists(cut / "depth-limit" / ".incomplete" / "checkpoint.h5"));
    EXPECT_EQ(result(cut), expected);
  }
  // Other options are refused, naming the key; the interrupted study stays resumable.
  const fs::path other = dir_ / "inversion-other";
  {
    const StopAfter stop(1, SIGINT);
    ASSERT_EQ(run_argv(with(other, false), dir_ / "inv-o.log").status, 128 + SIGINT);
  }
  std::vector<std::string> changed = with(other, true);
  changed[8] = "0.00025";  // --increment
  const auto refused = run_argv(changed, dir_ / "inv-o2.log");
  EXPECT_EQ(refused.status, 1) << refused.output;
  EXPECT_NE(refused.output.find("increment_m: the checkpoint has 0.0005, this run 0.00025"),
            std::string::npos)
      << refused.output;
  EXPECT_TRUE(fs::exists(other / "depth-limit" / "INTERRUPTED"));
}

}  // namespace
