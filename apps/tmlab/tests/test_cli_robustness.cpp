// The command line under hostile input and concurrent use (issue 12): no case name or path ever
// reaches a shell, one writer per result directory, SIGINT/SIGTERM leave INTERRUPTED (not RUNNING),
// and a run killed outright leaves a RUNNING marker that the next run reports as stale.
#include "core/mesh/mesh_generator.hpp"

#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <fstream>
#include <thread>

namespace {

namespace fs = std::filesystem;
using namespace tmlab::cli_test;  // run_argv, spawn, wait_for, wait_exit, Result
using tmlab::testing::read_file;
using tmlab::testing::write_file;

class CliRobustness : public tmlab::testing::TempDirTest {
 protected:
  /// A 2 x 2 x 2 box clamped at z = 0 and pulled at z = 1: a valid case in dir_.
  fs::path write_case(const std::string& name, const std::string& solver, bool plots = false) const {
    tmlab::write_gmsh22(tmlab::make_box_mesh(tmlab::Vec3(0, 0, 0), tmlab::Vec3(1, 1, 1), 2, 2, 2),
                        (dir_ / "box.msh").string());
    nlohmann::json c = {
        {"name", name},
        {"mesh", {{"file", (dir_ / "box.msh").string()}}},
        {"material", {{"E", 1000.0}, {"nu", 0.3}, {"density", 1000.0}}},
        {"boundary", {{{"name", "clamp"}, {"nodes", {{"plane", {{"axis", "z"}, {"value", 0.0}}}}}}}},
        {"loads",
         {{{"type", "nodal_force"},
           {"name", "pull"},
           {"nodes", {{"plane", {{"axis", "z"}, {"value", 1.0}}}}},
           {"force", {0.0, 0.0, 1.0}}}}},
        {"solver", nlohmann::json::parse(solver)},
        {"output", {{"vtu", false}, {"xdmf", false}, {"plots", plots}}}};
    const fs::path p = dir_ / "case.json";
    std::ofstream(p) << c.dump(2);
    return p;
  }

  /// A run long enough to be caught while it runs (millions of explicit steps on 48 tets).
  fs::path write_long_case() const {
    return write_case("long", R"({"type": "explicit", "dt": 1e-6, "t_end": 100.0})");
  }
};

TEST_F(CliRobustness, HostileCaseNameIsRefusedBeforeAnythingRuns) {
  const fs::path c = write_case("a';touch${IFS}X;'", R"({"type": "static", "steps": 1})");
  const Result r = run_argv({"run", c.string(), "--results", (dir_ / "res").string()}, dir_ / "log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("key 'name'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("contains '''"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists("X"));
  EXPECT_FALSE(fs::exists(dir_ / "X"));
  EXPECT_FALSE(fs::exists(dir_ / "res"));
}

TEST_F(CliRobustness, HostileResultsPathNeverReachesAShell) {
  // The results path is the user's to choose; with quotes and command substitutions in it, the
  // plotter (python3, when installed) gets it as one argument and nothing is executed.
  const fs::path res = dir_ / "r'$(touch X)';touch${IFS}Y;'";
  const fs::path c = write_case("hostile-path", R"({"type": "static", "steps": 1})", /*plots=*/true);
  const Result r = run_argv({"run", c.string(), "--results", res.string()}, dir_ / "log");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(res / "hostile-path" / "summary.json"));
  for (const fs::path& p : {fs::path("X"), fs::path("Y"), dir_ / "X", dir_ / "Y"})
    EXPECT_FALSE(fs::exists(p)) << p;
}

TEST_F(CliRobustness, SecondRunIntoTheSameDirectoryIsRefusedAndSigintInterruptsTheFirst) {
  const fs::path c = write_long_case();
  const fs::path res = dir_ / "res", dir = res / "long";
  const pid_t first = spawn({"run", c.string(), "--no-plots", "--results", res.string()}, dir_ / "first.log");
  ASSERT_TRUE(wait_for(dir / "RUNNING")) << read_file(dir_ / "first.log");

  const Result second =
      run_argv({"run", c.string(), "--no-plots", "--results", res.string()}, dir_ / "second.log");
  EXPECT_EQ(second.status, 1) << second.output;
  EXPECT_NE(second.output.find("another tmlab run is writing"), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("pid " + std::to_string(first)), std::string::npos) << second.output;
  EXPECT_FALSE(fs::exists(dir / "FAILED")) << "the refused run must not touch the first's directory";

  ASSERT_EQ(::kill(first, SIGINT), 0);
  EXPECT_EQ(wait_exit(first), 128 + SIGINT) << read_file(dir_ / "first.log");
  ASSERT_TRUE(fs::exists(dir / "INTERRUPTED")) << read_file(dir_ / "first.log");
  EXPECT_NE(read_file(dir / "INTERRUPTED").find("SIGINT received at t = "), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "RUNNING"));
  EXPECT_FALSE(fs::exists(dir / "FAILED"));
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
}

TEST_F(CliRobustness, SigtermInterruptsToo) {
  const fs::path c = write_long_case();
  const fs::path res = dir_ / "res", dir = res / "long";
  const pid_t pid = spawn({"run", c.string(), "--no-plots", "--results", res.string()}, dir_ / "run.log");
  ASSERT_TRUE(wait_for(dir / "RUNNING")) << read_file(dir_ / "run.log");
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  EXPECT_EQ(wait_exit(pid), 128 + SIGTERM) << read_file(dir_ / "run.log");
  EXPECT_NE(read_file(dir / "INTERRUPTED").find("SIGTERM"), std::string::npos);
}

TEST_F(CliRobustness, KilledRunLeavesAStaleMarkerThatTheNextRunReports) {
  const fs::path c = write_long_case();
  const fs::path res = dir_ / "res", dir = res / "long";
  const pid_t pid = spawn({"run", c.string(), "--no-plots", "--results", res.string()}, dir_ / "run.log");
  ASSERT_TRUE(wait_for(dir / "RUNNING")) << read_file(dir_ / "run.log");
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  EXPECT_EQ(wait_exit(pid), -SIGKILL);
  EXPECT_TRUE(fs::exists(dir / "RUNNING"));  // nothing could clean up after SIGKILL

  const fs::path quick = write_case("long", R"({"type": "static", "steps": 1})");
  const Result r =
      run_argv({"run", quick.string(), "--no-plots", "--results", res.string()}, dir_ / "next.log");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("stale RUNNING marker (pid " + std::to_string(pid)), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "summary.json"));
  EXPECT_FALSE(fs::exists(dir / "RUNNING"));
}

TEST_F(CliRobustness, MeshRepairNeverWritesOverItsInputOrAnExistingFile) {
  // Issue 26: an output file may not be the input (even through a link) nor replace a file silently.
  const fs::path mesh = fs::path(TMLAB_SOURCE_DIR) / "meshes" / "cube_n2.msh";
  const fs::path in = dir_ / "in.msh";
  fs::copy_file(mesh, in);
  const std::string original = read_file(in);
  fs::create_directory_symlink(dir_, dir_ / "same");
  for (const fs::path& out : {in, dir_ / "same" / "in.msh"}) {
    const Result r =
        run_argv({"mesh", "check", in.string(), "--repair", out.string(), "--overwrite"}, dir_ / "a.log");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find("is the input"), std::string::npos) << r.output;
  }
  EXPECT_EQ(read_file(in), original);
  write_file(dir_ / "out.msh", "mine");
  const Result r =
      run_argv({"mesh", "check", in.string(), "--repair", (dir_ / "out.msh").string()}, dir_ / "b.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("exists already"), std::string::npos) << r.output;
  EXPECT_EQ(read_file(dir_ / "out.msh"), "mine");
  const Result ok = run_argv(
      {"mesh", "check", in.string(), "--repair", (dir_ / "out.msh").string(), "--overwrite"}, dir_ / "c.log");
  EXPECT_EQ(ok.status, 0) << ok.output;
  EXPECT_NE(read_file(dir_ / "out.msh"), "mine");
}

}  // namespace
