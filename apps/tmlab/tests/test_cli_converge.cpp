// `tmlab converge` (issue 28; docs/convergence.md): a tiny indentation rig and a tiny case file on
// three levels give a complete result folder with converge.json's fields and finite values; bad
// options exit 2 naming the option and leave no folder behind; a folder holding files tmlab did
// not write is refused and kept.
#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace {

namespace fs = std::filesystem;
using tmlab::cli_test::Result;
using tmlab::cli_test::run_argv;

using CliConverge = tmlab::testing::TempDirTest;

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

/// The common checks of a complete study folder with `levels` levels.
void expect_complete(const fs::path& out, std::size_t levels) {
  for (const char* f : {"summary.json", "manifest.json", "converge.json", "converge.md"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_FALSE(fs::exists(out / "FAILED"));
  const nlohmann::json j = read_json(out / "converge.json");
  ASSERT_EQ(j["levels"].size(), levels);
  for (std::size_t k = 0; k < levels; ++k) {
    const nlohmann::json& l = j["levels"][k];
    EXPECT_EQ(l["level"], k + 1);
    for (const char* key : {"tets", "points", "dofs", "h_m", "wall_seconds", "dir"})
      EXPECT_TRUE(l.contains(key)) << key;
    EXPECT_TRUE(fs::exists(out / l["dir"].get<std::string>() / "summary.json")) << l["dir"];
    if (k > 0) {
      EXPECT_NEAR(j["levels"][k - 1]["h_m"].get<double>() / l["h_m"].get<double>(), 2.0, 1e-12);
    }
  }
  ASSERT_FALSE(j["quantities"].empty());
  for (const nlohmann::json& q : j["quantities"]) {
    ASSERT_EQ(q["values"].size(), levels);
    for (const auto& v : q["values"]) EXPECT_TRUE(std::isfinite(v.get<double>())) << q["name"];
    ASSERT_EQ(q["observed_orders"].size(), levels - 2);
    const std::string verdict = q["verdict"];
    EXPECT_TRUE(verdict == "asymptotic" || verdict == "not asymptotic") << verdict;
    if (verdict == "asymptotic") {
      EXPECT_TRUE(q["extrapolated"].is_number()) << q["name"];
      EXPECT_TRUE(q["order"].is_number());
      EXPECT_TRUE(q["levels"][levels - 1]["gci"].is_number());
      EXPECT_TRUE(q["levels"][levels - 1]["relative_error"].is_number());
    } else {
      EXPECT_TRUE(q["extrapolated"].is_null()) << q["name"];
      EXPECT_TRUE(q["reason"].is_string());
    }
    EXPECT_TRUE(q["levels"][0]["gci"].is_null());
  }
  const nlohmann::json s = read_json(out / "summary.json");
  EXPECT_EQ(s["levels"], levels);
}

TEST_F(CliConverge, IndentationRigOnThreeLevels) {
  const fs::path out = dir_ / "study";
  const Result r = run_argv(
      {"converge", "indentation", "--cells", "2", "--layers", "1", "--depth", "0.0005", "--steps-per-segment",
       "2", "--levels", "3", "--time", "0.5", "--time", "1", "--out", out.string(), "--no-plots"},
      dir_ / "converge.log");
  ASSERT_EQ(r.status, 0) << r.output;
  expect_complete(out, 3);
  const nlohmann::json j = read_json(out / "converge.json");
  // The default quantities of an indentation: the indenter's force and contact radius, per time.
  ASSERT_EQ(j["quantities"].size(), 4u);
  EXPECT_EQ(j["quantities"][0]["name"], "contact_indenter_force_z");
  EXPECT_EQ(j["quantities"][0]["unit"], "N");
  EXPECT_EQ(j["quantities"][0]["time_s"], 0.5);
  EXPECT_EQ(j["quantities"][1]["time_s"], 1.0);
  EXPECT_EQ(j["quantities"][2]["name"], "contact_indenter_radius");
  for (const auto& f : j["quantities"][1]["values"]) EXPECT_GT(f.get<double>(), 0.0);  // the sample pushes up
  EXPECT_EQ(j["levels"][0]["cells"], 2);
  EXPECT_EQ(j["levels"][2]["cells"], 8);
  EXPECT_EQ(j["levels"][2]["layers"], 4);
  EXPECT_EQ(j["options"]["rig"]["test"], "indentation");
  // Progress: one line per level as it starts and ends.
  for (const char* line : {"level 1/3:", "level 2/3:", "level 3/3: done"})
    EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
  EXPECT_NE(r.output.find("contact_indenter_force_z at t = 1 s (N)"), std::string::npos) << r.output;
}

TEST_F(CliConverge, CaseFileIsRefinedUniformly) {
  // A 40 x 10 x 10 mm cantilever under its own weight, with a tip probe, as a user brings it.
  // One 40 x 10 x 10 mm cell split into 6 tets around its diagonal 1-8, the x = 0 face named.
  std::ofstream msh(dir_ / "beam.msh");
  msh << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 1 "
         "\"xmin\"\n$EndPhysicalNames\n$Nodes\n8\n"
         "1 0 0 0\n2 0.04 0 0\n3 0 0.01 0\n4 0.04 0.01 0\n5 0 0 0.01\n6 0.04 0 0.01\n7 0 0.01 0.01\n"
         "8 0.04 0.01 0.01\n$EndNodes\n$Elements\n8\n"
         "1 2 2 1 1 1 3 7\n2 2 2 1 1 1 7 5\n"  // the x = 0 face
         "3 4 2 2 2 1 2 4 8\n4 4 2 2 2 1 4 3 8\n5 4 2 2 2 1 3 7 8\n6 4 2 2 2 1 7 5 8\n7 4 2 2 2 1 5 6 8\n"
         "8 4 2 2 2 1 6 2 8\n$EndElements\n";
  msh.close();
  std::ofstream(dir_ / "beam.json") << R"({
    "name": "beam",
    "mesh": {"file": "beam.msh", "repair_orientation": true},
    "material": {"E": 100000, "nu": 0.3, "density": 1000},
    "boundary": [{"name": "clamp", "nodes": {"group": "xmin"}}],
    "loads": [{"type": "gravity", "acceleration": [0, 0, -9.81], "function": {"type": "ramp", "t0": 0, "t1": 1}}],
    "solver": {"type": "static", "steps": 2},
    "output": {"probes": [{"name": "tip", "point": [0.04, 0.01, 0.01]}]}
  })";
  const fs::path out = dir_ / "study";
  const Result r = run_argv(
      {"converge", (dir_ / "beam.json").string(), "--levels", "3", "--out", out.string(), "--no-plots"},
      dir_ / "converge.log");
  ASSERT_EQ(r.status, 0) << r.output;
  expect_complete(out, 3);
  const nlohmann::json j = read_json(out / "converge.json");
  EXPECT_EQ(j["levels"][0]["tets"], 6);
  EXPECT_EQ(j["levels"][2]["tets"], 6 * 64);
  EXPECT_EQ(j["levels"][2]["refinements"], 2);
  EXPECT_EQ(j["quantities"][0]["name"], "probe_tip_norm");
  EXPECT_TRUE(fs::exists(out / "meshes" / "level-3.msh"));
}

TEST_F(CliConverge, BadOptionsExitTwoAndLeaveNothing) {
  const fs::path out = dir_ / "study";
  const std::vector<std::string> rig = {"converge", "indentation", "--cells", "2",
                                        "--layers", "1",           "--out",   out.string()};
  const auto with = [&rig](std::vector<std::string> extra) {
    std::vector<std::string> a = rig;
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {with({"--levels", "2"}), "--levels"},
      {with({"--ratio", "1"}), "--ratio"},
      {with({"--ratio", "1.2"}), "--ratio 1.2: level 2"},  // 2 cells -> 2 cells: no refinement
      {with({"--quantity", "contact_indenter_force"}), "--quantity contact_indenter_force"},
      {with({"--quantity", "reaction_top_platen_z"}), "--quantity reaction_top_platen_z"},  // no platen here
      {with({"--time", "2"}), "--time 2"},
      {with({"--levels", "8"}), "--levels"},  // the finest rig is beyond the mesh limit
      {{"converge", "cube-uniaxial", "--cells", "4", "--out", out.string()}, "--cells is a rig option"},
      {{"converge", "cube-uniaxial", "--ratio", "3", "--out", out.string()}, "--ratio 3"},
      {{"converge", "cube-uniaxial", "--quantity", "contact_indenter_force_z", "--out", out.string()},
       "--quantity contact_indenter_force_z"},
      {{"converge", "--out", out.string()}, "converge needs one rig test"},
  };
  int k = 0;
  for (const auto& [args, message] : cases) {
    const Result r = run_argv(args, dir_ / ("bad" + std::to_string(k++) + ".log"));
    EXPECT_EQ(r.status, 2) << message << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << message << "\n" << r.output;
    EXPECT_FALSE(fs::exists(out)) << message;
  }
}

TEST_F(CliConverge, ForeignFolderIsRefusedAndKept) {
  const fs::path out = dir_ / "mine";
  fs::create_directories(out);
  std::ofstream(out / "notes.txt") << "my notes\n";
  const Result r = run_argv({"converge", "indentation", "--cells", "2", "--layers", "1", "--depth", "0.0005",
                             "--steps-per-segment", "1", "--out", out.string(), "--no-plots"},
                            dir_ / "converge.log");
  EXPECT_NE(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("notes.txt"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "notes.txt"));
  EXPECT_FALSE(fs::exists(out / "summary.json"));
}

}  // namespace
