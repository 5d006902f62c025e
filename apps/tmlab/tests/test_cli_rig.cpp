// `tmlab rig`: a platen test written as a case file that `tmlab run` accepts, and clear refusals of
// impossible rigs (exit 1 naming the field) and unknown tests (usage error, exit 2).
#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace {

namespace fs = std::filesystem;
using tmlab::cli_test::Result;
using tmlab::cli_test::run_argv;

using CliRig = tmlab::testing::TempDirTest;

TEST_F(CliRig, UnconfinedRigRunsAndReportsThePlatenForce) {
  const Result w =
      run_argv({"rig", "unconfined", "--out", (dir_ / "rig").string(), "--name", "phantom", "--depth",
                "0.003", "--cells", "4", "--layers", "3", "--E", "10000", "--nu", "0.3"},
               dir_ / "rig.log");
  ASSERT_EQ(w.status, 0) << w.output;
  ASSERT_TRUE(fs::exists(dir_ / "rig" / "phantom.json"));
  ASSERT_TRUE(fs::exists(dir_ / "rig" / "phantom.msh"));
  const Result r = run_argv({"run", (dir_ / "rig" / "phantom.json").string(), "--results",
                             (dir_ / "results").string(), "--no-plots"},
                            dir_ / "run.log");
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(dir_ / "results" / "phantom" / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  EXPECT_GT(std::abs(s["final_reactions_N"]["top_platen"][2].get<double>()), 0.0);
}

TEST_F(CliRig, IndentationRigRunsWithItsContactBody) {
  const Result w =
      run_argv({"rig", "indentation", "--out", (dir_ / "rig").string(), "--name", "ind", "--depth", "0.0005",
                "--cells", "6", "--layers", "4", "--steps-per-segment", "4"},
               dir_ / "rig.log");
  ASSERT_EQ(w.status, 0) << w.output;
  const Result r = run_argv(
      {"run", (dir_ / "rig" / "ind.json").string(), "--results", (dir_ / "results").string(), "--no-plots"},
      dir_ / "run.log");
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(dir_ / "results" / "ind" / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  const nlohmann::json& body = s["contact"]["bodies"][0];
  EXPECT_EQ(body["name"], "indenter");
  EXPECT_EQ(body["type"], "sphere");
  const double fz = body["final_force_N"][2].get<double>();
  EXPECT_GT(fz, 0.0);
  EXPECT_GE(body["final_active_nodes"].get<int>(), 1);
  // The indenter's force is carried by the bonded bottom.
  EXPECT_NEAR(fz, s["final_reactions_N"]["bottom"][2].get<double>(), 1e-6 * fz);
}

TEST_F(CliRig, RefusesImpossibleRigsAndUnknownTests) {
  const Result deep =
      run_argv({"rig", "indentation", "--out", (dir_ / "x").string(), "--depth", "0.05"}, dir_ / "a.log");
  EXPECT_EQ(deep.status, 1) << deep.output;
  EXPECT_NE(deep.output.find("history"), std::string::npos) << deep.output;
  EXPECT_FALSE(fs::exists(dir_ / "x" / "indentation.json"));
  const Result unknown = run_argv({"rig", "shear", "--out", (dir_ / "x").string()}, dir_ / "b.log");
  EXPECT_EQ(unknown.status, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("uniaxial_tension"), std::string::npos) << unknown.output;
  const Result no_out = run_argv({"rig", "tension"}, dir_ / "c.log");
  EXPECT_EQ(no_out.status, 2) << no_out.output;
}

}  // namespace
