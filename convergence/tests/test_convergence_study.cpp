// Tests of the convergence study (convergence/convergence_study.hpp, convergence_report.hpp): the
// plan refuses bad options naming them before anything is written; the value at a time
// interpolates the recorded series; a tiny cantilever case on three uniformly refined levels runs
// through the runner and gives h halving exactly, finite values and a complete converge.json.
#include "convergence/convergence_report.hpp"
#include "convergence/convergence_study.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace tmlab::convergence {
namespace {

namespace fs = std::filesystem;

template <class Fn>
std::string error_of(Fn fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

/// A rig small enough to plan: the indentation block with 4 cells and 2 layers.
rigs::RigSpec small_rig() {
  rigs::RigSpec s;
  s.name = "indentation";
  s.cells = 4;
  s.layers = 2;
  return s;
}

class ConvergenceStudy : public testing::TempDirTest {
 protected:
  /// A 40 x 10 x 10 mm cantilever of 4 x 1 x 1 cells (24 tets) under its own weight, with a tip
  /// probe: the case file's path.
  fs::path cantilever() const {
    write_gmsh22(make_box_mesh(Vec3(0, 0, 0), Vec3(0.04, 0.01, 0.01), 4, 1, 1), (dir_ / "beam.msh").string());
    testing::write_file(dir_ / "beam.json", R"({
      "name": "beam",
      "mesh": {"file": "beam.msh"},
      "material": {"E": 100000, "nu": 0.3, "density": 1000},
      "boundary": [{"name": "clamp", "nodes": {"group": "xmin"}}],
      "loads": [{"type": "gravity", "acceleration": [0, 0, -9.81],
                 "function": {"type": "ramp", "t0": 0, "t1": 1}}],
      "solver": {"type": "static", "steps": 4},
      "output": {"probes": [{"name": "tip", "point": [0.04, 0.01, 0.01]}]}
    })");
    return dir_ / "beam.json";
  }
};

TEST(ConvergenceSeries, ValueAtInterpolatesLinearlyBetweenSteps) {
  const std::vector<double> t{0.0, 0.25, 0.5, 1.0}, v{0.0, 1.0, 3.0, 4.0};
  EXPECT_EQ(value_at(t, v, 0.0, "x"), 0.0);
  EXPECT_EQ(value_at(t, v, 0.5, "x"), 3.0);
  EXPECT_DOUBLE_EQ(value_at(t, v, 0.375, "x"), 2.0);
  EXPECT_DOUBLE_EQ(value_at(t, v, 0.75, "x"), 3.5);
  EXPECT_EQ(value_at(t, v, 1.0, "x"), 4.0);
  EXPECT_EQ(value_at(t, v, 1.0 + 1e-12, "x"), 4.0);  // round-off beyond the end
  EXPECT_NE(error_of([&] { value_at(t, v, 1.1, "run/timeseries.h5: q"); }).find("--time 1.1"),
            std::string::npos);
  EXPECT_NE(error_of([&] { value_at(t, {1.0}, 0.5, "q"); }).find("1 values for 4"), std::string::npos);
}

TEST(ConvergenceSeries, RecordedAndDefaultQuantitiesFollowTheSeriesNames) {
  const auto s = recorded_series({"bottom"}, {"tip"}, {"indenter"});
  for (const char* name :
       {"reaction_bottom_z", "probe_tip_norm", "contact_indenter_force_z", "contact_indenter_radius",
        "contact_indenter_max_pressure", "elastic_energy", "max_displacement"})
    EXPECT_NE(std::find(s.begin(), s.end(), name), s.end()) << name;
  EXPECT_EQ(default_quantities({}, {}, {"indenter"}),
            std::vector<std::string>({"contact_indenter_force_z", "contact_indenter_radius"}));
  EXPECT_EQ(default_quantities({"top_platen"}, {"tip"}, {}),
            std::vector<std::string>({"reaction_top_platen_norm", "probe_tip_norm"}));
  EXPECT_EQ(default_quantities({}, {}, {}), std::vector<std::string>({"max_displacement"}));
}

TEST(ConvergencePlan, RigLevelsMultiplyCellsAndLayers) {
  StudyOptions o;
  o.rig = small_rig();
  o.levels = 4;
  const StudyPlan p = plan_study(o);
  ASSERT_EQ(p.levels.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(p.levels[static_cast<std::size_t>(k)].cells, 4 << k);
    EXPECT_EQ(p.levels[static_cast<std::size_t>(k)].layers, 2 << k);
    EXPECT_EQ(p.levels[static_cast<std::size_t>(k)].rig.name, "level-" + std::to_string(k + 1));
  }
  EXPECT_EQ(p.quantities, std::vector<std::string>({"contact_indenter_force_z", "contact_indenter_radius"}));
  EXPECT_EQ(p.times, std::vector<double>({1.0}));  // ramp of 1 s, no hold: the end of loading is the end
  // A ratio of 1.5 rounds: 4, 6, 9 cells; 2, 3, 5 layers (4.5 rounds away from zero).
  o.ratio = 1.5;
  o.levels = 3;
  const StudyPlan q = plan_study(o);
  EXPECT_EQ(q.levels[2].cells, 9);
  EXPECT_EQ(q.levels[2].layers, 5);
  // With a hold, the end of loading and the last time are two default times.
  o.rig->history = rigs::DisplacementHistory::ramp_hold(0.002, 1.0, 2.0);
  EXPECT_EQ(plan_study(o).times, std::vector<double>({1.0, 3.0}));
}

TEST(ConvergencePlan, BadOptionsAreRefusedNamingTheOption) {
  StudyOptions o;
  o.rig = small_rig();
  o.levels = 2;
  EXPECT_NE(error_of([&] { plan_study(o); }).find("--levels 2"), std::string::npos);
  o.levels = 3;
  o.ratio = 1.0;
  EXPECT_NE(error_of([&] { plan_study(o); }).find("--ratio 1"), std::string::npos);
  o.ratio = 1.1;  // 4 -> 4 cells: no refinement
  EXPECT_NE(error_of([&] { plan_study(o); }).find("does not refine level 1"), std::string::npos);
  o.ratio = 2.0;
  o.quantities = {"contact_indenter_force_q"};
  const std::string unknown = error_of([&] { plan_study(o); });
  EXPECT_NE(unknown.find("--quantity contact_indenter_force_q"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("contact_indenter_force_z"), std::string::npos) << unknown;  // lists what exists
  o.quantities = {"elastic_energy", "elastic_energy"};
  EXPECT_NE(error_of([&] { plan_study(o); }).find("given twice"), std::string::npos);
  o.quantities = {};
  o.times = {2.0};
  EXPECT_NE(error_of([&] { plan_study(o); }).find("--time 2"), std::string::npos);
  o.times = {};
  o.levels = 8;  // 4 * 2^7 = 512 cells: far beyond the rigs' mesh limit
  const std::string big = error_of([&] { plan_study(o); });
  EXPECT_NE(big.find("level "), std::string::npos) << big;
  EXPECT_NE(big.find("--levels"), std::string::npos) << big;
  o.levels = 9;
  EXPECT_NE(error_of([&] { plan_study(o); }).find("3 to 8"), std::string::npos);
  StudyOptions neither;
  EXPECT_NE(error_of([&] { plan_study(neither); }).find("neither"), std::string::npos);
}

TEST_F(ConvergenceStudy, CaseFileRatioMustBeTwoAndLevelsMustFit) {
  StudyOptions o;
  o.case_config = load_case(cantilever().string(), dir_.string());
  o.ratio = 1.5;
  EXPECT_NE(error_of([&] { plan_study(o); }).find("--ratio 1.5"), std::string::npos);
  o.ratio = 2.0;
  o.levels = 8;  // 24 x 8^7 tets
  EXPECT_NE(error_of([&] { plan_study(o); }).find("--levels 8"), std::string::npos);
  o.levels = 3;
  o.quantities = {"contact_indenter_force_z"};  // the case has no contact
  EXPECT_NE(error_of([&] { plan_study(o); }).find("--quantity contact_indenter_force_z"), std::string::npos);
}

TEST_F(ConvergenceStudy, CantileverOnThreeRefinedLevels) {
  StudyOptions o;
  o.case_config = load_case(cantilever().string(), dir_.string());
  o.levels = 3;
  o.times = {0.5, 1.0};
  const StudyPlan plan = plan_study(o);
  EXPECT_EQ(plan.kind, "case");
  EXPECT_EQ(plan.quantities, std::vector<std::string>({"probe_tip_norm"}));
  const fs::path out = dir_ / "study";
  fs::create_directories(out);
  const StudyResult r = run_study(plan, o, out);
  ASSERT_EQ(r.levels.size(), 3u);
  EXPECT_EQ(r.levels[0].tets, 24);
  EXPECT_EQ(r.levels[1].tets, 192);
  EXPECT_EQ(r.levels[2].tets, 1536);
  for (std::size_t k = 1; k < 3; ++k) EXPECT_NEAR(r.levels[k - 1].h / r.levels[k].h, 2.0, 1e-12);
  EXPECT_NEAR(r.levels[0].volume, 4e-6, 1e-18);
  for (const LevelResult& l : r.levels) {
    EXPECT_TRUE(fs::exists(out / l.dir / "summary.json")) << l.dir;
    EXPECT_EQ(l.dofs, 3 * l.points);
  }
  ASSERT_EQ(r.quantities.size(), 2u);
  for (const QuantityResult& q : r.quantities) {
    EXPECT_EQ(q.unit, "m");
    for (const double v : q.analysis.value) EXPECT_TRUE(std::isfinite(v) && v > 0.0);
    // A stiffer coarse mesh (P1 bending locks): the tip deflection grows with refinement.
    EXPECT_LT(q.analysis.value[0], q.analysis.value[1]);
    EXPECT_LT(q.analysis.value[1], q.analysis.value[2]);
    EXPECT_TRUE(q.analysis.constant_ratio);
  }
  // Gravity ramps linearly and the response is nearly linear: the deflection at t = 0.5 is about
  // half that at t = 1 on every level.
  EXPECT_NEAR(r.quantities[0].analysis.value[2] / r.quantities[1].analysis.value[2], 0.5, 0.02);
  const nlohmann::json j = study_json(plan, r);
  ASSERT_EQ(j["quantities"].size(), 2u);
  for (const auto& q : j["quantities"]) {
    for (const char* key : {"name", "unit", "time_s", "values", "h_m", "ratios", "observed_orders", "verdict",
                            "reason", "order", "extrapolated", "levels"})
      EXPECT_TRUE(q.contains(key)) << key;
    EXPECT_EQ(q["levels"].size(), 3u);
    EXPECT_TRUE(q["levels"][0]["gci"].is_null());  // no coarser level
    if (q["verdict"] == "asymptotic") {
      EXPECT_TRUE(q["extrapolated"].is_number());
      EXPECT_TRUE(q["levels"][2]["gci"].is_number());
    } else {
      EXPECT_TRUE(q["extrapolated"].is_null());
      EXPECT_TRUE(q["reason"].is_string());
    }
  }
  EXPECT_EQ(j["levels"][2]["refinements"], 2);
  const std::string md = study_markdown(plan, r, "tmlab converge beam.json");
  EXPECT_NE(md.find("probe_tip_norm at t = 1 s (m)"), std::string::npos) << md;
}

TEST_F(ConvergenceStudy, LinearSolverChoiceGivesTheSameLevels) {
  // --linear sets every level's solver.linear: CHOLMOD and LDL^T solve the same Newton steps, so the
  // levels agree to round-off (the cantilever's tangent is positive definite: no fallback).
  StudyOptions o;
  o.case_config = load_case(cantilever().string(), dir_.string());
  o.levels = 3;
  std::vector<std::vector<double>> values;
  for (const char* linear : {"ldlt", "cholmod"}) {
    o.linear = linear;
    const StudyPlan plan = plan_study(o);
    const fs::path out = dir_ / (std::string("study-") + linear);
    fs::create_directories(out);
    const StudyResult r = run_study(plan, o, out);
    values.push_back(r.quantities[0].analysis.value);
    const std::string summary = testing::read_file(out / r.levels[2].dir / "summary.json");
    EXPECT_EQ(nlohmann::json::parse(summary)["solver"]["newton"]["linear"], linear) << summary;
  }
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(values[1][k], values[0][k], 1e-9 * std::abs(values[0][k]));
}

TEST_F(ConvergenceStudy, LinearSolverIsCheckedBeforeAnythingRuns) {
  StudyOptions o;
  o.rig = small_rig();
  o.linear = "lu";
  EXPECT_NE(error_of([&] { plan_study(o); }).find("--linear lu"), std::string::npos);
  // An explicit case makes no linear solves: refused, naming the option and the case.
  CaseConfig c = load_case(cantilever().string(), dir_.string());
  c.solver.type = SolverSpec::Type::Explicit;
  StudyOptions e;
  e.case_config = c;
  e.linear = "cholmod";
  const std::string msg = error_of([&] { plan_study(e); });
  EXPECT_NE(msg.find("--linear cholmod"), std::string::npos) << msg;
  EXPECT_NE(msg.find("explicit"), std::string::npos) << msg;
}

}  // namespace
}  // namespace tmlab::convergence
