// The tmlab command line as a user meets it: exit codes, messages naming the file/key/element,
// no result that looks complete after a failure, and the embedded demo equal to cases/liver-probe.json.
#include "../demo_case.hpp"

#include "core/config/config_reader.hpp"
#include "core/mesh/mesh_generator.hpp"

#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace {

namespace fs = std::filesystem;

using tmlab::cli_test::Result;
using tmlab::cli_test::run;

class Cli : public tmlab::testing::TempDirTest {
 protected:
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
};

TEST_F(Cli, HelpAndUsageErrors) {
  EXPECT_EQ(run("help").status, 0);
  const Result none = run("");
  EXPECT_EQ(none.status, 2);
  const Result bad = run("frobnicate");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("unknown command 'frobnicate'"), std::string::npos) << bad.output;
  // A mistyped command gets one short message with the nearest command, not the whole help.
  const Result typo = run("fti");
  EXPECT_EQ(typo.status, 2);
  EXPECT_NE(typo.output.find("unknown command 'fti' (did you mean 'fit'?)"), std::string::npos)
      << typo.output;
  EXPECT_EQ(typo.output.find("commands:"), std::string::npos) << typo.output;
  const Result old_name = run("help inversion");
  EXPECT_EQ(old_name.status, 2);
  EXPECT_NE(old_name.output.find("tmlab inversion is now tmlab depth-limit"), std::string::npos)
      << old_name.output;
  EXPECT_EQ(run("run").status, 2);
  EXPECT_EQ(run("run liver-probe --bogus").status, 2);
  const auto fig9 = run("paper fig9");
  EXPECT_EQ(fig9.status, 2) << fig9.output;
  EXPECT_NE(fig9.output.find("expected fig2, fig3, table1, table2, fig5, fig6 or fig7"), std::string::npos)
      << fig9.output;
}

// The help is generated from the option tables: every option is listed (the three the hand-written
// help had lost among them), one command's block by `help COMMAND` or `COMMAND --help`.
TEST_F(Cli, HelpFromTheOptionTables) {
  const Result all = run("help");
  ASSERT_EQ(all.status, 0) << all.output;
  for (const char* o :
       {"--meshes", "--fe-iterations", "--fe-max-samples", "--relaxation-bands", "--no-test-control"})
    EXPECT_NE(all.output.find(o), std::string::npos) << o;
  const Result fit = run("help fit");
  EXPECT_EQ(fit.status, 0) << fit.output;
  EXPECT_EQ(fit.output.rfind("  fit DATA.csv --model SPEC", 0), 0u) << fit.output;
  EXPECT_NE(fit.output.find("--starts N"), std::string::npos) << fit.output;
  EXPECT_EQ(fit.output.find("  discover"), std::string::npos) << fit.output;
  EXPECT_EQ(run("fit --help").output, fit.output);
  const Result data = run("data show --help");
  EXPECT_EQ(data.status, 0) << data.output;
  EXPECT_NE(data.output.find("  data show"), std::string::npos) << data.output;
  EXPECT_EQ(data.output.find("  data convert"), std::string::npos) << data.output;
  EXPECT_EQ(run("help frobnicate").status, 2);
  // Refusals name the option and the table's range or choices.
  const Result range = run("bench --threads 65");
  EXPECT_EQ(range.status, 2) << range.output;
  EXPECT_NE(range.output.find("--threads needs a whole number"), std::string::npos) << range.output;
  const Result twice = run("verify --full --full");
  EXPECT_EQ(twice.status, 2) << twice.output;
  EXPECT_NE(twice.output.find("option --full is given 2 times"), std::string::npos) << twice.output;
  const Result outside = run("realtime liver-poke --duration 0");
  EXPECT_EQ(outside.status, 2) << outside.output;
  EXPECT_NE(outside.output.find("--duration must be in (0, 3600]"), std::string::npos) << outside.output;
}

TEST_F(Cli, CasesListsTheShippedCases) {
  const Result r = run("cases");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("liver-probe"), std::string::npos) << r.output;
}

TEST_F(Cli, EmbeddedDemoEqualsTheShippedCaseFile) {
  const auto shipped =
      tmlab::ConfigReader::parse_file(std::string(TMLAB_SOURCE_DIR) + "/cases/liver-probe.json");
  EXPECT_EQ(nlohmann::json::parse(tmlab::cli::kDemoCase), shipped);
}

TEST_F(Cli, UnknownKeyInCaseFileIsNamed) {
  tmlab::write_gmsh22(tmlab::make_box_mesh(tmlab::Vec3(0, 0, 0), tmlab::Vec3(1, 1, 1), 1, 1, 1),
                      (dir_ / "m.msh").string());
  const fs::path c = write("c.json", R"({"name": "c", "mesh": {"file": "m.msh"},
    "material": {"E": 1000, "nu": 0.3, "density": 1000, "colour": "red"},
    "solver": {"type": "static"}})");
  const Result r = run("run '" + c.string() + "' --results '" + (dir_ / "res").string() + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("c.json: unknown key 'material.colour'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "res" / "c" / "summary.json"));
}

TEST_F(Cli, MalformedMeshNamesFileAndLine) {
  const fs::path m =
      write("bad.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 0 zero 0\n$EndNodes\n");
  const Result r = run("mesh info '" + m.string() + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("bad.msh:7"), std::string::npos) << r.output;
}

TEST_F(Cli, MeshCheckFailsOnInvertedTetAndRepairFixesIt) {
  const fs::path m =
      write("inv.msh",
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
            "$Elements\n1\n17 4 2 0 1 1 3 2 4\n$EndElements\n");
  const Result r = run("mesh check '" + m.string() + "'");
  EXPECT_EQ(r.status, 1);
  // Named by tmlab's index and by the element id of the file (issue 12).
  EXPECT_NE(r.output.find("first inverted: tetrahedron 0 (Gmsh element 17)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Gmsh element 17"), std::string::npos) << r.output;
  const fs::path fixed = dir_ / "fixed.msh";
  EXPECT_EQ(run("mesh check '" + m.string() + "' --repair '" + fixed.string() + "'").status, 0);
  EXPECT_EQ(run("mesh check '" + fixed.string() + "'").status, 0);
}

TEST_F(Cli, MeshCheckRefusesAMeshWithoutTetsOrNodes) {
  const fs::path no_tets =
      write("surface.msh",
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n"
            "$EndNodes\n$Elements\n1\n1 2 2 0 1 1 2 3\n$EndElements\n");
  Result r = run("mesh check '" + no_tets.string() + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("3 nodes and 0 tetrahedra: nothing to simulate"), std::string::npos) << r.output;
  const fs::path empty = write("empty.msh",
                               "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n0\n$EndNodes\n"
                               "$Elements\n0\n$EndElements\n");
  r = run("mesh check '" + empty.string() + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("0 nodes and 0 tetrahedra"), std::string::npos) << r.output;
}

TEST_F(Cli, DegreeIsRefusedForTheFastModel) {
  const Result r =
      run("run cantilever-static --degree 2 --no-plots --results '" + (dir_ / "res").string() + "'");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--degree applies to the deal.II reference only"), std::string::npos) << r.output;
  const Result bad =
      run("run cantilever-static --model reference --degree 3 --results '" + (dir_ / "res").string() + "'");
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.output.find("--degree must be 1 or 2"), std::string::npos) << bad.output;
}

TEST_F(Cli, ProbeFarOutsideTheMeshIsRefused) {
  const fs::path c =
      write("far.json", R"({
    "name": "far", "mesh": {"file": ")" +
                            (fs::path(TMLAB_SOURCE_DIR) / "meshes" / "beam_40x10x10mm.msh").string() + R"("},
    "material": {"E": 1000, "nu": 0.3, "density": 1000},
    "boundary": [{"name": "fixed", "nodes": {"plane": {"axis": "x", "value": 0}}}],
    "solver": {"type": "static", "steps": 1},
    "output": {"probes": [{"name": "tip", "point": [40, 0, 0]}]}})");
  const Result r = run("run '" + c.string() + "' --no-plots --results '" + (dir_ / "res").string() + "'");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("output.probes 'tip' at (40, 0, 0)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("check the point and its units"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "res" / "far" / "summary.json"));
}

TEST_F(Cli, DemoRunsAndWritesACompleteResult) {
  const Result r = run("demo --no-plots --results '" + (dir_ / "res").string() + "'");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("reaction    probe"), std::string::npos) << r.output;
  // The solver line is brief (the per-step Newton history is in summary.json only), and with
  // --no-plots no PNG is announced.
  EXPECT_NE(r.output.find("\"newton_line_search\":\"energy\""), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("per_step"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(".png"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("t = 0 included"), std::string::npos) << r.output;
  const fs::path out = dir_ / "res" / "liver-probe";
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  std::ifstream in(out / "summary.json");
  const auto s = nlohmann::json::parse(in);
  EXPECT_EQ(s["mesh"]["tets"], 2704);
  EXPECT_GT(s["min_volume_ratio"].get<double>(), 0.0);
  // The probe is pushed down 15 mm: the support pushes the body down (negative z reaction).
  EXPECT_LT(s["final_reactions_N"]["probe"][2].get<double>(), 0.0);
  EXPECT_EQ(s["solver"]["newton"]["per_step"]["iterations"].size(),
            s["solver"]["load_steps"].get<std::size_t>());
}

/// "seed" was the name of the xu2011 Prony scheme: a case file that still says so runs, as the same case.
TEST_F(Cli, FormerSchemeNameSeedStillRuns) {
  tmlab::write_gmsh22(tmlab::make_box_mesh(tmlab::Vec3(0, 0, 0), tmlab::Vec3(1, 1, 1), 2, 2, 2),
                      (dir_ / "m.msh").string());
  std::vector<nlohmann::json> reactions;
  for (const std::string scheme : {"seed", "xu2011"}) {
    const nlohmann::json doc = nlohmann::json::parse(R"({"mesh": {"file": "m.msh"},
      "material": {"E": 1000, "nu": 0.3, "density": 1000,
                   "viscoelastic": {"prony": {"terms": [{"weight": 0.3, "tau": 0.5}]}}},
      "boundary": [{"name": "base", "nodes": {"plane": {"axis": "z", "value": 0}}},
                   {"name": "top", "nodes": {"plane": {"axis": "z", "value": 1}}, "components": "z",
                    "value": [0, 0, -0.02]}],
      "solver": {"type": "static", "steps": 4, "t_end": 1.0}, "output": {"plots": false, "vtu": false}})");
    nlohmann::json j = doc;
    j["name"] = scheme;
    j["material"]["viscoelastic"]["scheme"] = scheme;
    const fs::path c = write(scheme + ".json", j.dump());
    const Result r = run("run '" + c.string() + "' --results '" + (dir_ / "res").string() + "'");
    ASSERT_EQ(r.status, 0) << r.output;
    std::ifstream in(dir_ / "res" / scheme / "summary.json");
    reactions.push_back(nlohmann::json::parse(in).at("final_reactions_N"));
  }
  EXPECT_NE(reactions[0]["top"][2].get<double>(), 0.0);
  EXPECT_EQ(reactions[0], reactions[1]);
}

/// `tmlab compare`: the shipped uniaxial case with the tensor-mass model and the deal.II P1 reference
/// (same mesh, same discretisation: same answer to solver tolerance), and against the oracle.
TEST_F(Cli, CompareWritesTheDifferences) {
  for (const std::string against : {"tl_oracle", "reference"}) {
#ifndef TMLAB_HAVE_REFERENCE
    if (against == "reference") {
      const Result r = run("compare cube-uniaxial --results '" + (dir_ / "res").string() + "'");
      EXPECT_EQ(r.status, 1);
      EXPECT_NE(r.output.find("without the deal.II reference"), std::string::npos) << r.output;
      continue;
    }
#endif
    const Result r =
        run("compare cube-uniaxial --against " + against + " --results '" + (dir_ / "res").string() + "'");
    ASSERT_EQ(r.status, 0) << r.output;
    // A result directory of its own (issue 12): staged, summary.json listing compare.json; the
    // tensor-mass run's own directory is left as its summary describes it.
    // Each comparison its own directory (issue 26): the oracle's does not replace the reference's.
    const fs::path cdir =
        dir_ / "res" / (against == "reference" ? "cube-uniaxial-compare" : "cube-uniaxial-compare-tl_oracle");
    std::ifstream in(cdir / "compare.json");
    const auto c = nlohmann::json::parse(in);
    std::ifstream sin(cdir / "summary.json");
    const auto summary = nlohmann::json::parse(sin);
    const auto& files = summary.at("files");
    EXPECT_NE(std::find(files.begin(), files.end(), "compare.json"), files.end()) << summary.dump();
    EXPECT_FALSE(fs::exists(cdir / ".incomplete"));
    EXPECT_FALSE(fs::exists(dir_ / "res" / "cube-uniaxial" / "compare.json"));
    EXPECT_EQ(c["against"], against);
    EXPECT_EQ(c["element"], "p1");
    if (against == "reference") EXPECT_EQ(c["reference_element"], "P1");
    EXPECT_LT(c["rel_diff_displacement"].get<double>(), 1e-8) << c.dump();
    EXPECT_LT(c["rel_diff_reaction"].get<double>(), 1e-8) << c.dump();
    EXPECT_LT(c["rel_diff_energy"].get<double>(), 1e-8) << c.dump();
  }
#ifdef TMLAB_HAVE_REFERENCE
  // The oracle's comparison, made first, is still there beside the reference's.
  std::ifstream oracle(dir_ / "res" / "cube-uniaxial-compare-tl_oracle" / "compare.json");
  ASSERT_TRUE(oracle.good());
  EXPECT_EQ(nlohmann::json::parse(oracle)["against"], "tl_oracle");
#endif
  // --degree is a whole number 1 or 2 of the reference's elements, and only for the reference.
  for (const std::string bad :
       {"--degree 1.5", "--degree 0x2", "--degree 3", "--against tl_oracle --degree 2"}) {
    const Result r = run("compare cube-uniaxial " + bad + " --results '" + (dir_ / "res").string() + "'");
    EXPECT_EQ(r.status, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--degree"), std::string::npos) << r.output;
  }
}

/// `tmlab compare` on a p2_mean_dilatation case: the reference runs the same F-bar P2 element
/// (docs/elements.md), so the two agree to the solvers' tolerance; compare.json names both elements.
TEST_F(Cli, CompareGivesTheReferenceTheMeanDilatationElement) {
#ifndef TMLAB_HAVE_REFERENCE
  GTEST_SKIP() << "built without the deal.II reference";
#endif
  const fs::path c = write("md.json", R"({"name": "md", "model": "hyperelastic_tl",
    "mesh": {"file": "meshes/cube_n2.msh", "scale": 0.01, "element": "p2_mean_dilatation"},
    "material": {"law": "neo_hookean", "E": 10000, "nu": 0.49, "density": 1000},
    "boundary": [{"name": "base", "nodes": {"group": "zmin"}}],
    "loads": [{"type": "pressure", "faces": {"group": "zmax"}, "pressure": 800,
               "function": {"type": "ramp", "t0": 0, "t1": 1}},
              {"type": "traction", "faces": {"group": "xmax"}, "traction": [0, 500, 0],
               "function": {"type": "ramp", "t0": 0, "t1": 1}}],
    "solver": {"type": "static", "steps": 2, "newton": {"rtol": 1e-12}}})");
  const Result r = run("compare '" + c.string() + "' --no-plots --results '" + (dir_ / "res").string() + "'");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("deal.II reference run (P2 mean dilatation"), std::string::npos) << r.output;
  std::ifstream in(dir_ / "res" / "md-compare" / "compare.json");
  const auto cmp = nlohmann::json::parse(in);
  EXPECT_EQ(cmp["element"], "p2_mean_dilatation");
  EXPECT_EQ(cmp["reference_element"], "P2 mean dilatation (F-bar per cell)");
  EXPECT_EQ(fs::path(cmp["b"].get<std::string>()).filename(), "md-reference-p2-mean_dilatation");
  // The reference's Newton tolerance stays its default (1e-10), so the agreement is the solvers'.
  EXPECT_LT(cmp["rel_diff_displacement"].get<double>(), 1e-8) << cmp.dump();
  EXPECT_LT(cmp["rel_diff_energy"].get<double>(), 1e-8) << cmp.dump();
  std::printf(
      "[ measured ] tmlab compare, p2_mean_dilatation cube (nu = 0.49): displacement %.2e, energy %.2e\n",
      cmp["rel_diff_displacement"].get<double>(), cmp["rel_diff_energy"].get<double>());
}

/// `tmlab paper fig7` end to end on a reduced parameter file (one scheme, one short cycle): the
/// figure, its HDF5 curves and the energy table exist, and the objective scheme's energy balance
/// (loop area = dissipated + stored) closes to the time-discretisation error.
TEST_F(Cli, PaperFig7ProducesFigureAndClosesTheEnergyBalance) {
  auto params =
      tmlab::ConfigReader::parse_file(std::string(TMLAB_SOURCE_DIR) + "/cases/paper/xu2011_liver.json");
  params["schemes"] = {"objective"};
  params["fig7"]["periods"] = {1.0};
  params["fig7"]["steps_per_cycle"] = 40;
  const fs::path pf = write("params.json", params.dump());
  const Result r =
      run("paper fig7 --params '" + pf.string() + "' --results '" + (dir_ / "res").string() + "'");
  ASSERT_EQ(r.status, 0) << r.output;
  const fs::path d = dir_ / "res" / "paper" / "fig7";
  // One result directory through the run protocol: summary.json last, the runs inside it, their
  // paths in figure.json relative to it.
  EXPECT_TRUE(fs::exists(d / "summary.json"));
  EXPECT_FALSE(fs::exists(d / ".incomplete"));
  std::ifstream fin(d / "figure.json");
  const auto spec = nlohmann::json::parse(fin);
  ASSERT_EQ(spec["runs"].size(), 1u);
  EXPECT_TRUE(fs::exists(d / spec["runs"][0]["dir"].get<std::string>() / "summary.json")) << spec.dump();
  EXPECT_TRUE(fs::exists(d / "fig7.png"));
  EXPECT_TRUE(fs::exists(d / "fig7.h5"));
  std::ifstream in(d / "fig7_energy.json");
  const auto e = nlohmann::json::parse(in);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_GT(e[0]["dissipation_J"].get<double>(), 0.0);
  EXPECT_LT(e[0]["relative_residual"].get<double>(), 5e-3) << e.dump();
}

}  // namespace

namespace {

// ------------------------------------------------------------------ tmlab verify

TEST_F(Cli, VerifyListsSelectsAndRejectsUnknownCases) {
  const Result list = run("verify --list");
  EXPECT_EQ(list.status, 0) << list.output;
  EXPECT_NE(list.output.find("kernel-patch-test"), std::string::npos) << list.output;
  const Result unknown = run("verify --case no-such-case --results '" + dir_.string() + "'");
  EXPECT_EQ(unknown.status, 1) << unknown.output;
  EXPECT_NE(unknown.output.find("no-such-case"), std::string::npos) << unknown.output;
  EXPECT_NE(unknown.output.find("kernel-patch-test"), std::string::npos)
      << "lists the known cases: " << unknown.output;
  EXPECT_EQ(run("verify --bogus").status, 2);
}

TEST_F(Cli, VerifyRunsACaseAndWritesACompleteReport) {
  const Result r = run("verify --case kernel-patch-test --no-plots --results '" + dir_.string() + "'");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("[1/1] kernel-patch-test ... PASS"), std::string::npos) << r.output;
  const fs::path out = dir_ / "verification";
  for (const char* f : {"report.md", "report.html", "verification.json", "manifest.json", "summary.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto j = nlohmann::json::parse(std::ifstream(out / "verification.json"));
  ASSERT_EQ(j["cases"].size(), 1u);
  EXPECT_EQ(j["cases"][0]["name"], "kernel-patch-test");
  EXPECT_EQ(j["cases"][0]["status"], "pass");
  EXPECT_TRUE(j["cases"][0]["error"].is_number());
  EXPECT_TRUE(j["cases"][0]["tolerance"].is_number());
}

TEST_F(Cli, VerifyFailingCaseExitsNonZeroAndBadCaseFileIsNamed) {
  // A copy of a real case with an impossible tolerance must fail (the harness can fail), and a case
  // file with a misspelt key must be refused naming the file and key.
  const fs::path cases = dir_ / "cases";
  fs::create_directories(cases / "strict");
  auto spec = tmlab::ConfigReader::parse_file(std::string(TMLAB_SOURCE_DIR) +
                                              "/verification/cases/kernel-patch-test/verify.json");
  spec["checks"][1]["max"] = -1.0;  // a relative residual can never be negative: this check must fail
  std::ofstream(cases / "strict" / "verify.json") << spec.dump(1);
  std::ofstream(cases / "strict" / "README.md") << "# strict\n";
  const Result fail =
      run("verify --cases-dir '" + cases.string() + "' --no-plots --results '" + dir_.string() + "'");
  EXPECT_EQ(fail.status, 1) << fail.output;
  EXPECT_NE(fail.output.find("FAIL"), std::string::npos) << fail.output;
  const auto j = nlohmann::json::parse(std::ifstream(dir_ / "verification" / "verification.json"));
  EXPECT_EQ(j["cases"][0]["status"], "fail");

  spec["checks"][0]["tolerence"] = 1.0;
  std::ofstream(cases / "strict" / "verify.json") << spec.dump(1);
  const Result bad = run("verify --cases-dir '" + cases.string() + "' --results '" + dir_.string() + "'");
  EXPECT_EQ(bad.status, 1) << bad.output;
  EXPECT_NE(bad.output.find("verify.json"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("tolerence"), std::string::npos) << bad.output;
}

}  // namespace
