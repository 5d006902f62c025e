// The case runner end to end: a uniaxial StVK stretch of a cube whose reaction force has a closed
// form, the result-directory protocol, and clear failures (inverted element, unstable explicit step).
#include "core/base/error.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/results/result_compare.hpp"
#include "core/results/run_output.hpp"
#include "runner/case_runner.hpp"
#include "runner/tests/runner_test_case.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace tmlab::tm {
namespace {

namespace fs = std::filesystem;

/// The cube and its uniaxial case from runner_test_case.hpp, run through run_case.
class CaseRunnerTest : public runner::RunnerTestCase {
 protected:
  RunResult run(const nlohmann::json& j) const {
    RunOptions o;
    o.results_root = (dir_ / "results").string();
    o.plots = false;
    return run_case(config(j), o);
  }
};

TEST_F(CaseRunnerTest, UniaxialStretchReactionMatchesClosedForm) {
  const double d = 0.002;  // 20 % stretch: well into the nonlinear range
  const RunResult r = run(uniaxial(d));
  // Homogeneous state: E11 = (l^2 - 1)/2, S11 = E * E11, force = l * S11 * A0 (nominal).
  const double l = 1.0 + d / 0.01, E11 = 0.5 * (l * l - 1.0);
  const double force = l * 10000.0 * E11 * 1e-4;
  const auto reac = r.summary["final_reactions_N"]["pull"];
  EXPECT_NEAR(reac[0].get<double>(), force, 1e-9 * force);
  // Lateral contraction: E22 = -nu E11 -> lateral stretch sqrt(1 - 2 nu E11).
  const double lat = std::sqrt(1.0 - 2.0 * 0.3 * E11) - 1.0;
  const auto corner = r.summary["probes"]["corner"]["displacement_m"];
  EXPECT_NEAR(corner[1].get<double>(), 0.01 * lat, 1e-12);
  EXPECT_NEAR(corner[2].get<double>(), 0.01 * lat, 1e-12);

  // The result directory is complete: summary last, numbers, fields, manifest.
  const fs::path out = r.dir;
  for (const char* f : {"summary.json", "manifest.json", "timeseries.h5", "displacement.h5", "fields.xdmf",
                        "result.pvd", "mesh_report.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_FALSE(fs::exists(out / RunOutput::kStaging));
  H5File h5 = H5File::open_read((out / "timeseries.h5").string());
  EXPECT_EQ(h5.read_double("/series/time").size(), 5u);  // t = 0 and 4 load steps
  EXPECT_EQ(h5.string_attribute("/series/reaction_pull_x", "unit"), "N");

  // The Newton history of every step is in the summary (issue 12), consistent with the totals.
  const auto& nw = r.summary["solver"]["newton"];
  EXPECT_EQ(nw["line_search"], "energy");
  const auto& its = nw["per_step"]["iterations"];
  ASSERT_EQ(its.size(), 4u);
  int sum = 0;
  for (const auto& i : its) sum += i.get<int>();
  EXPECT_EQ(sum, r.summary["solver"]["newton_iterations"].get<int>());
  EXPECT_EQ(nw["per_step"]["residual_history_last_solve"].size(), 4u);
  for (std::size_t k = 0; k < 4; ++k)
    EXPECT_LE(nw["per_step"]["residual_final"][k].get<double>(),
              1e3 * nw["per_step"]["residual_target"][k].get<double>());
  // The linear solves (solver.linear "auto" by default): one per Newton iteration, all CHOLMOD's on
  // one symbolic analysis (the uniaxial stretch's tangent stays positive definite), none fell back.
  const auto& ls = r.summary["solver"]["linear_solver"];
  EXPECT_EQ(ls["kind"], "auto");
  EXPECT_EQ(ls["solves"], sum);
  EXPECT_EQ(ls["solves_by"]["cholmod"], sum);
  EXPECT_EQ(ls["symbolic_analyses"]["cholmod"], 1);
  EXPECT_EQ(ls["fallbacks_to_ldlt"], 0);
  EXPECT_FALSE(ls.contains("note"));
  // The manifest holds the effective configuration, defaults included.
  std::ifstream min(out / "manifest.json");
  const auto manifest = nlohmann::json::parse(min);
  EXPECT_EQ(manifest["config"]["solver"]["newton"]["max_iterations"], 25) << manifest["config"].dump();
}

TEST_F(CaseRunnerTest, OracleAndTensorMassGiveTheSameAnswer) {
  auto j = uniaxial(0.001);
  const RunResult a = run(j);
  j["model"] = "tl_oracle";
  j["name"] = "uniaxial_oracle";
  const RunResult b = run(j);
  const double fa = a.summary["final_reactions_N"]["pull"][0].get<double>();
  const double fb = b.summary["final_reactions_N"]["pull"][0].get<double>();
  EXPECT_NEAR(fa, fb, 1e-10 * std::abs(fb));

  // The comparison tool sees the same: differences at round-off (the two kernels agree to ~1e-15;
  // Newton stops at rtol 1e-10, so displacements agree to about that).
  const nlohmann::json cmp = compare_results(a.dir, b.dir);
  EXPECT_LT(cmp["rel_diff_displacement"].get<double>(), 1e-9) << cmp.dump();
  EXPECT_LT(cmp["rel_diff_reaction"].get<double>(), 1e-9) << cmp.dump();
  EXPECT_LT(cmp["rel_diff_energy"].get<double>(), 1e-9) << cmp.dump();
  EXPECT_EQ(cmp["frames"].get<int>(), 5);

  // A different material is seen as different.
  j["material"]["E"] = 12000;
  j["name"] = "uniaxial_stiffer";
  const RunResult c = run(j);
  const nlohmann::json cmp2 = compare_results(c.dir, a.dir);
  EXPECT_NEAR(cmp2["rel_diff_reaction"].get<double>(), 0.2, 1e-6) << cmp2.dump();
  // Different output frames cannot be compared.
  j["solver"]["steps"] = 2;
  j["name"] = "uniaxial_two_steps";
  const RunResult d = run(j);
  EXPECT_THROW(compare_results(d.dir, a.dir), Error);
}

TEST_F(CaseRunnerTest, InvertedElementStopsTheRunWithoutSummary) {
  auto j = uniaxial(-0.012);  // pushed past the opposite face: every tet must invert
  j["solver"]["steps"] = 2;
  j["solver"]["newton"] = {{"max_cutbacks", 2}};
  try {
    run(j);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_TRUE(m.find("inverted") != std::string::npos || m.find("did not converge") != std::string::npos)
        << m;
  }
  EXPECT_FALSE(fs::exists(dir_ / "results" / "uniaxial" / "summary.json"));
  EXPECT_TRUE(fs::exists(dir_ / "results" / "uniaxial" / RunOutput::kFailed));
}

TEST_F(CaseRunnerTest, ExplicitStepAboveCriticalIsRefused) {
  auto j = uniaxial(0.001);
  j["solver"] = {{"type", "explicit"}, {"dt", 0.01}, {"t_end", 1.0}};
  try {
    run(j);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("critical time step"), std::string::npos) << e.what();
  }
}

TEST_F(CaseRunnerTest, SelectorThatSelectsNothingIsNamed) {
  auto j = uniaxial(0.001);
  j["boundary"][3]["nodes"] = {{"plane", {{"axis", "x"}, {"value", 0.5}}}};
  try {
    run(j);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("boundary[3] 'pull' selects no nodes"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tmlab::tm
