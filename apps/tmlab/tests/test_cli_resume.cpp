// Interrupted verification suites resume (issue 12): SIGINT at random moments during
// `tmlab verify`, then `--resume`, must give the same verification.json as an uninterrupted run,
// bit for bit except the wall-clock times; finished cases are not run again.
#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <fstream>
#include <random>

namespace {

namespace fs = std::filesystem;
using namespace tmlab::cli_test;  // run_argv, spawn, wait_for, wait_exit, Result
using tmlab::testing::read_file;

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

  // Deterministic case: stop right after the first case is checkpointed; the resumed run must take
  // that case from the checkpoint.
  {
    const fs::path res = dir_ / "after-first";
    const pid_t pid = spawn(suite(res), dir_ / "a.log");
    ASSERT_TRUE(wait_for(res / "verification.checkpoint" / "analytic-uniaxial-stvk.json"))
        << read_file(dir_ / "a.log");
    ASSERT_EQ(::kill(pid, SIGINT), 0);
    const int rc = wait_exit(pid);
    if (rc == 128 + SIGINT) {
      ASSERT_TRUE(fs::exists(res / "verification" / "INTERRUPTED")) << read_file(dir_ / "a.log");
      EXPECT_NE(read_file(res / "verification" / "INTERRUPTED").find("--resume"), std::string::npos);
      EXPECT_FALSE(fs::exists(res / "verification" / "summary.json"));
      std::vector<std::string> args = suite(res);
      args.push_back("--resume");
      const auto resumed = run_argv(args, dir_ / "a2.log");
      ASSERT_EQ(resumed.status, 0) << resumed.output;
      EXPECT_NE(resumed.output.find("analytic-uniaxial-stvk ... PASS (from the checkpoint"),
                std::string::npos)
          << resumed.output;
    } else {
      ASSERT_EQ(rc, 0) << "the suite finished before the signal arrived: " << read_file(dir_ / "a.log");
    }
    EXPECT_EQ(without_times(res), expected);
    EXPECT_FALSE(fs::exists(res / "verification.checkpoint")) << "a complete report leaves no checkpoint";
  }

  // Random moments (the seed is printed so that a failure can be replayed).
  const unsigned seed = std::random_device{}();
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> delay_ms(0, 4000);
  for (int trial = 0; trial < 3; ++trial) {
    const int ms = delay_ms(rng);
    SCOPED_TRACE("seed " + std::to_string(seed) + ", trial " + std::to_string(trial) + ", SIGINT after " +
                 std::to_string(ms) + " ms");
    const fs::path res = dir_ / ("random-" + std::to_string(trial));
    const pid_t pid = spawn(suite(res), dir_ / "r.log");
    std::this_thread::sleep_for(std::chrono::milliseconds(ms));
    ::kill(pid, SIGINT);
    const int rc = wait_exit(pid);
    ASSERT_TRUE(rc == 0 || rc == 128 + SIGINT || rc == -SIGINT) << rc << "\n" << read_file(dir_ / "r.log");
    if (rc != 0) {
      std::vector<std::string> args = suite(res);
      args.push_back("--resume");
      const auto resumed = run_argv(args, dir_ / "r2.log");
      // A signal before the suite had started its checkpoint leaves nothing to resume: say so.
      if (resumed.status != 0) {
        ASSERT_NE(resumed.output.find("no checkpoint"), std::string::npos) << resumed.output;
        ASSERT_EQ(run_argv(suite(res), dir_ / "r3.log").status, 0);
      }
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
  const pid_t pid = spawn(suite(res), dir_ / "2.log");
  ASSERT_TRUE(wait_for(res / "verification.checkpoint" / "suite.json"));
  ::kill(pid, SIGINT);
  const int rc = wait_exit(pid);
  if (rc != 128 + SIGINT) GTEST_SKIP() << "finished before the signal";
  r = run_argv({"verify", "--case", "kernel-patch-test", "--no-plots", "--results", res.string(), "--resume"},
               dir_ / "3.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("is of a different suite"), std::string::npos) << r.output;
}

TEST_F(CliResume, InterruptedPaperFigureReusesItsFinishedRuns) {
  // fig7 reduced to two short runs (two schemes, one cycle of 40 steps).
  auto params =
      nlohmann::json::parse(read_file(fs::path(TMLAB_SOURCE_DIR) / "cases" / "paper" / "xu2011_liver.json"),
                            nullptr, true, /*ignore_comments=*/true);
  params["schemes"] = {"objective", "seed"};
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

  const fs::path res = dir_ / "cut", fig = res / "paper" / "fig7";
  const pid_t pid = spawn(cmd(res), dir_ / "cut.log");
  // Wait for the first run to finish inside the figure's staging area, then interrupt the second.
  bool first_done = false;
  for (int i = 0; i < 3000 && !first_done; ++i) {
    if (fs::exists(fig / ".incomplete"))
      for (const auto& e : fs::directory_iterator(fig / ".incomplete"))
        if (e.is_directory() && fs::exists(e.path() / "summary.json")) first_done = true;
    if (!first_done) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(first_done) << read_file(dir_ / "cut.log");
  ::kill(pid, SIGINT);
  const int rc = wait_exit(pid);
  if (rc == 0) GTEST_SKIP() << "the figure finished before the signal";
  ASSERT_EQ(rc, 128 + SIGINT) << read_file(dir_ / "cut.log");
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

}  // namespace
