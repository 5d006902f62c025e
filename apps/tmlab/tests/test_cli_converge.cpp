// `tmlab converge` (issue 28; docs/convergence.md): a tiny indentation rig and a tiny case file on
// three levels give a complete result folder with converge.json's fields and finite values; bad
// options exit 2 naming the option and leave no folder behind; a folder holding files tmlab did
// not write is refused and kept. --refine-in time refines a viscoelastic case's steps (dt halves,
// the mesh stays; a rig's --steps-per-segment doubles); --resume continues an interrupted study,
// reusing its complete levels (the same numbers as an uninterrupted study), refuses one planned
// otherwise, leaving it as it was, and continues a study that FAILED at a level (here: a level folder
// holding a file tmlab did not write, which is kept).
#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace {

namespace fs = std::filesystem;
using tmlab::cli_test::Result;
using tmlab::cli_test::run_argv;

class CliConverge : public tmlab::testing::TempDirTest {
 protected:
  /// A 1 cm cube (meshes/cube_n2.msh) with symmetry planes stretched 5 % by a C1 ramp over 1 s and
  /// held to 2 s, a standard linear solid with the midpoint Prony recursion, 4 load steps.
  fs::path visco_case() const {
    std::ofstream(dir_ / "visco.json") << R"({
      "name": "visco",
      "mesh": {"file": "meshes/cube_n2.msh", "scale": 0.01},
      "material": {"E": 10000, "nu": 0.3, "density": 1000,
                   "viscoelastic": {"scheme": "xu2011", "prony": {"convention": "long_term",
                                                                  "terms": [{"weight": 1.5, "tau": 0.5}]}}},
      "boundary": [
        {"name": "x0", "nodes": {"group": "xmin"}, "components": "x"},
        {"name": "y0", "nodes": {"group": "ymin"}, "components": "y"},
        {"name": "z0", "nodes": {"group": "zmin"}, "components": "z"},
        {"name": "pull", "nodes": {"group": "xmax"}, "components": "x", "value": [0.0005, 0, 0],
         "function": {"type": "smooth_ramp", "t0": 0, "t1": 1}}],
      "solver": {"type": "static", "t_end": 2.0, "steps": 4, "newton": {"rtol": 1e-13}}
    })";
    return dir_ / "visco.json";
  }
};

/// Sets the deterministic stop point (core/base/interrupt.hpp) for the drivers started while it lives.
class StopAfterLevels {
 public:
  explicit StopAfterLevels(int levels) {
    ::setenv("TMLAB_TEST_STOP_AFTER_PROGRESS", (std::to_string(levels) + ":SIGINT").c_str(), 1);
  }
  ~StopAfterLevels() { ::unsetenv("TMLAB_TEST_STOP_AFTER_PROGRESS"); }
  StopAfterLevels(const StopAfterLevels&) = delete;
  StopAfterLevels& operator=(const StopAfterLevels&) = delete;
};

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

/// The common checks of a complete study folder with `levels` levels; `size` is the level size's
/// key (h_m in space, dt_s in time), halving from level to level.
void expect_complete(const fs::path& out, std::size_t levels, const std::string& size = "h_m") {
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
      EXPECT_NEAR(j["levels"][k - 1][size].get<double>() / l[size].get<double>(), 2.0, 1e-12);
    }
  }
  ASSERT_FALSE(j["quantities"].empty());
  for (const nlohmann::json& q : j["quantities"]) {
    ASSERT_EQ(q["values"].size(), levels);
    ASSERT_EQ(q[size].size(), levels);
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
      // Nothing to refine in time: static, elastic, frictionless.
      {{"converge", "cube-uniaxial", "--refine-in", "time", "--out", out.string()},
       "--refine-in time: the case 'cube-uniaxial' does not depend on its load steps"},
      {with({"--refine-in", "time"}), "--refine-in time: the rig 'indentation' does not depend"},
      {with({"--refine-in", "steps"}), "--refine-in"},
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

TEST_F(CliConverge, TimeStepsOfAViscoelasticCase) {
  const fs::path out = dir_ / "study";
  const Result r = run_argv({"converge", visco_case().string(), "--refine-in", "time", "--levels", "3",
                             "--out", out.string(), "--no-plots"},
                            dir_ / "converge.log");
  ASSERT_EQ(r.status, 0) << r.output;
  expect_complete(out, 3, "dt_s");
  const nlohmann::json j = read_json(out / "converge.json");
  EXPECT_EQ(j["options"]["refine"], "time");
  EXPECT_EQ(j["options"]["time_dependence"], "a viscoelastic material");
  EXPECT_EQ(j["options"]["steps"], nlohmann::json({4, 8, 16}));
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(j["levels"][k]["steps"], 4 << k);
    EXPECT_EQ(j["levels"][k]["tets"], j["levels"][0]["tets"]);  // the mesh is fixed
    EXPECT_EQ(j["levels"][k]["run"], "new");
  }
  EXPECT_EQ(j["quantities"][0]["name"], "reaction_pull_norm");
  EXPECT_NE(r.output.find("level 3/3: 16 steps, dt = 0.125 s: running"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("| level | steps | dt (s) |"), std::string::npos) << r.output;
}

TEST_F(CliConverge, TimeStepsOfAViscoelasticRig) {
  // The indentation rig with a standard linear solid: --steps-per-segment doubles per level, one
  // mesh (meshes/mesh.msh) for every level.
  const fs::path out = dir_ / "study";
  const Result r =
      run_argv({"converge",
                "indentation",
                "--cells",
                "2",
                "--layers",
                "1",
                "--depth",
                "0.0005",
                "--hold",
                "1",
                "--steps-per-segment",
                "2",
                "--material",
                R"({"E": 3000, "nu": 0.45, "density": 1000, "viscoelastic": {"scheme": "objective",
           "prony": {"convention": "long_term", "terms": [{"weight": 1.0, "tau": 0.5}]}}})",
                "--refine-in",
                "time",
                "--levels",
                "3",
                "--out",
                out.string(),
                "--no-plots"},
               dir_ / "converge.log");
  ASSERT_EQ(r.status, 0) << r.output;
  expect_complete(out, 3, "dt_s");
  const nlohmann::json j = read_json(out / "converge.json");
  EXPECT_EQ(j["options"]["steps"], nlohmann::json({4, 8, 16}));  // 2 segments (ramp, hold) of 1 s
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(j["levels"][k]["tets"], 24);
    EXPECT_DOUBLE_EQ(j["levels"][k]["dt_s"].get<double>(), 0.5 / (1 << k));
  }
  EXPECT_TRUE(fs::exists(out / "meshes" / "mesh.msh"));
  EXPECT_FALSE(fs::exists(out / "meshes" / "level-2.msh"));
  // The force relaxes during the hold, and the levels differ (the steps changed).
  const nlohmann::json& f1 = j["quantities"][0]["values"];
  EXPECT_EQ(j["quantities"][0]["name"], "contact_indenter_force_z");
  EXPECT_NE(f1[0], f1[1]);
  EXPECT_GT(f1[2].get<double>(), j["quantities"][1]["values"][2].get<double>());
}

TEST_F(CliConverge, ResumeReusesTheLevelsAnInterruptedStudyFinished) {
  const fs::path visco = visco_case();
  const auto args = [&visco](const fs::path& out, std::vector<std::string> extra) {
    std::vector<std::string> a = {"converge", visco.string(), "--refine-in", "time",      "--levels",
                                  "3",        "--no-plots",   "--out",       out.string()};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  // Uninterrupted, for the numbers.
  const fs::path whole = dir_ / "whole";
  ASSERT_EQ(run_argv(args(whole, {}), dir_ / "whole.log").status, 0);
  // Nothing to resume in a folder that never held a study.
  const fs::path out = dir_ / "study";
  const Result none = run_argv(args(out, {"--resume"}), dir_ / "none.log");
  EXPECT_NE(none.status, 0);
  EXPECT_NE(none.output.find("nothing to resume"), std::string::npos) << none.output;
  // Stopped after its first level (SIGINT through the driver's own handler).
  {
    const StopAfterLevels stop(1);
    const Result r = run_argv(args(out, {}), dir_ / "stopped.log");
    EXPECT_EQ(r.status, 130) << r.output;
    EXPECT_NE(r.output.find("continue the study with the same command and --resume"), std::string::npos)
        << r.output;
  }
  ASSERT_TRUE(fs::exists(out / "INTERRUPTED"));
  ASSERT_TRUE(fs::exists(out / ".incomplete" / "levels" / "level-1" / "summary.json"));
  EXPECT_FALSE(fs::exists(out / ".incomplete" / "levels" / "level-2"));
  // The case changed since (5 load steps): its level 1 is not the one this plan would run; refused,
  // naming the difference, and the folder is left as it was.
  const std::string original = tmlab::testing::read_file(visco);
  std::string changed = original;
  const std::string four = "\"steps\": 4";
  changed.replace(changed.find(four), four.size(), "\"steps\": 5");
  std::ofstream(visco) << changed;
  const Result other = run_argv(args(out, {"--resume"}), dir_ / "other.log");
  EXPECT_NE(other.status, 0) << other.output;
  EXPECT_NE(other.output.find("--resume: levels/level-1 was run from another plan (its case differs at key "
                              "'solver.steps': 4 there, 5 here)"),
            std::string::npos)
      << other.output;
  EXPECT_TRUE(fs::exists(out / "INTERRUPTED"));
  EXPECT_FALSE(fs::exists(out / "RUNNING"));
  EXPECT_TRUE(fs::exists(out / ".incomplete" / "levels" / "level-1" / "summary.json"));
  std::ofstream(visco) << original;
  // Resumed with the same command: level 1 reused, levels 2 and 3 run; the numbers of the whole run.
  const Result resumed = run_argv(args(out, {"--resume"}), dir_ / "resumed.log");
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("level 1/3: 4 steps, dt = 0.5 s: reused"), std::string::npos)
      << resumed.output;
  expect_complete(out, 3, "dt_s");
  const nlohmann::json a = read_json(whole / "converge.json"), b = read_json(out / "converge.json");
  EXPECT_EQ(b["levels"][0]["run"], "reused");
  EXPECT_EQ(b["levels"][1]["run"], "new");
  EXPECT_EQ(a["quantities"][0]["values"], b["quantities"][0]["values"]);  // bit for bit
  EXPECT_EQ(a["quantities"][0]["order"], b["quantities"][0]["order"]);
}

TEST_F(CliConverge, AFailedLevelResumesAndFilesTmlabDidNotWriteAreKept) {
  const fs::path visco = visco_case();
  const fs::path out = dir_ / "study";
  const std::vector<std::string> args = {"converge", visco.string(), "--refine-in", "time",      "--levels",
                                         "3",        "--no-plots",   "--out",       out.string()};
  std::vector<std::string> resume = args;
  resume.push_back("--resume");
  {
    const StopAfterLevels stop(1);
    ASSERT_EQ(run_argv(args, dir_ / "stopped.log").status, 130);
  }
  // Someone's file where level 2 will run: that level's run refuses the folder, the study FAILS,
  // and the file stays.
  const fs::path level2 = out / ".incomplete" / "levels" / "level-2";
  fs::create_directories(level2);
  std::ofstream(level2 / "notes.txt") << "mine\n";
  const Result failed = run_argv(resume, dir_ / "failed.log");
  EXPECT_EQ(failed.status, 1) << failed.output;
  EXPECT_NE(failed.output.find("notes.txt"), std::string::npos) << failed.output;
  EXPECT_TRUE(fs::exists(out / "FAILED"));
  EXPECT_EQ(tmlab::testing::read_file(level2 / "notes.txt"), "mine\n");
  EXPECT_TRUE(fs::exists(out / ".incomplete" / "levels" / "level-1" / "summary.json"));
  // The file moved away, the failed study resumes: level 1 reused, the others run.
  fs::remove(level2 / "notes.txt");
  const Result resumed = run_argv(resume, dir_ / "resumed.log");
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  expect_complete(out, 3, "dt_s");
  const nlohmann::json j = read_json(out / "converge.json");
  EXPECT_EQ(j["levels"][0]["run"], "reused");
  EXPECT_EQ(j["levels"][1]["run"], "new");
  EXPECT_EQ(j["levels"][2]["run"], "new");
}

}  // namespace
