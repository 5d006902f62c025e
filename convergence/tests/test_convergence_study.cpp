// Tests of the convergence study (convergence/convergence_study.hpp, convergence_report.hpp): the
// plan refuses bad options naming them before anything is written; the value at a time
// interpolates the recorded series; a tiny cantilever case on three uniformly refined levels runs
// through the runner and gives h halving exactly, finite values and a complete converge.json.
// In time (--refine-in time): the steps multiply and dt divides per level, a problem that does not
// depend on its steps is refused, and a viscoelastic cube shows its schemes' orders in time (2 for
// the midpoint Prony recursion, 1 for backward Euler). Resuming: complete levels of the same plan
// are reused (the same numbers), a level without its completion mark runs again, a level of another
// plan is refused naming the difference.
#include "convergence/convergence_report.hpp"
#include "convergence/convergence_study.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
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
  /// A 1 cm cube of 2 x 2 x 2 cells with symmetry planes, stretched 5 % along x by a C1 ramp over
  /// 1 s and held to 2 s, a standard linear solid (one Prony term, alpha = 1.5, tau = 0.5 s) with
  /// the given integration of its recursion, `steps` static load steps: the case file's path.
  fs::path visco_cube(const std::string& integration, int steps = 8) const {
    write_gmsh22(make_box_mesh(Vec3(0, 0, 0), Vec3(0.01, 0.01, 0.01), 2, 2, 2), (dir_ / "cube.msh").string());
    testing::write_file(dir_ / ("visco-" + integration + ".json"), R"({
      "name": "visco",
      "mesh": {"file": "cube.msh"},
      "material": {"E": 10000, "nu": 0.3, "density": 1000,
                   "viscoelastic": {"history": "pk2", "integration": ")" +
                                                                       integration + R"(",
                                    "relaxation": "full",
                                    "prony": {"convention": "long_term", "terms": [{"weight": 1.5, "tau": 0.5}]}}},
      "boundary": [
        {"name": "x0", "nodes": {"group": "xmin"}, "components": "x"},
        {"name": "y0", "nodes": {"group": "ymin"}, "components": "y"},
        {"name": "z0", "nodes": {"group": "zmin"}, "components": "z"},
        {"name": "pull", "nodes": {"group": "xmax"}, "components": "x", "value": [0.0005, 0, 0],
         "function": {"type": "smooth_ramp", "t0": 0, "t1": 1}}],
      "solver": {"type": "static", "t_end": 2.0, "steps": )" + std::to_string(steps) +
                                                                       R"(,
                 "newton": {"rtol": 1e-13}}
    })");
    return dir_ / ("visco-" + integration + ".json");
  }

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

TEST(ConvergencePlan, RigInTimeMultipliesTheStepsAndNeedsATimeDependence) {
  StudyOptions o;
  o.rig = small_rig();
  o.refine = Refine::Time;
  // Elastic, frictionless: the state at a time does not depend on the load steps.
  const std::string elastic = error_of([&] { plan_study(o); });
  EXPECT_NE(elastic.find("--refine-in time"), std::string::npos) << elastic;
  EXPECT_NE(elastic.find("does not depend on its load steps"), std::string::npos) << elastic;
  o.rig->material["viscoelastic"] = nlohmann::json::parse(
      R"({"scheme": "objective", "prony": {"convention": "long_term", "terms": [{"weight": 1.0, "tau": 0.5}]}})");
  o.rig->steps_per_sample = 3;
  const StudyPlan p = plan_study(o);
  EXPECT_EQ(p.refine, Refine::Time);
  EXPECT_EQ(p.time_dependence, "a viscoelastic material");
  ASSERT_EQ(p.levels.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(p.levels[k].cells, 4);  // the mesh is fixed
    EXPECT_EQ(p.levels[k].rig.steps_per_sample, 3 << k);
    EXPECT_EQ(p.levels[k].steps, 3 << k);  // a ramp of one segment
    EXPECT_DOUBLE_EQ(p.levels[k].dt, 1.0 / (3 << k));
  }
  // Bonded contact is history dependent too.
  o.rig->material.erase("viscoelastic");
  o.rig->indenter_contact = rigs::Support::Bonded;
  EXPECT_EQ(plan_study(o).time_dependence, "bonded contact (body indenter)");
  // Rounding that does not refine: 1 step per segment times 1.2 is 1 step again.
  o.rig->steps_per_sample = 1;
  o.ratio = 1.2;
  EXPECT_NE(error_of([&] { plan_study(o); }).find("--ratio 1.2: level 2 (1 load steps) does not refine"),
            std::string::npos);
}

TEST_F(ConvergenceStudy, CaseInTimeMultipliesTheStepsOrDividesDt) {
  StudyOptions o;
  o.refine = Refine::Time;
  // A static elastic case is refused, naming the option.
  o.case_config = load_case(cantilever().string(), dir_.string());
  const std::string elastic = error_of([&] { plan_study(o); });
  EXPECT_NE(elastic.find("--refine-in time: the case 'beam' does not depend on its load steps"),
            std::string::npos)
      << elastic;
  // A static viscoelastic case: solver.steps times the ratio, dt = t_end / steps.
  o.case_config = load_case(visco_cube("midpoint", 10).string(), dir_.string());
  o.ratio = 1.5;
  o.levels = 4;
  const StudyPlan p = plan_study(o);
  EXPECT_EQ(p.kind, "case");
  EXPECT_EQ(p.time_dependence, "a viscoelastic material");
  const std::vector<long> steps{10, 15, 23, 34};  // round(10 x 1.5^k)
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(p.levels[k].steps, steps[k]);
    EXPECT_DOUBLE_EQ(p.levels[k].dt, 2.0 / static_cast<double>(steps[k]));
    EXPECT_EQ(p.levels[k].refinements, 0);
  }
  EXPECT_EQ(p.quantities, std::vector<std::string>({"reaction_pull_norm"}));
  EXPECT_EQ(p.times, std::vector<double>({2.0}));
  // Any ratio > 1 (no mesh to split), but the levels must refine and fit.
  o.ratio = 1.04;
  EXPECT_NE(error_of([&] { plan_study(o); }).find("--ratio 1.04: level 2 (10 steps) does not refine"),
            std::string::npos);
  o.ratio = 10.0;
  o.levels = 8;
  EXPECT_NE(error_of([&] { plan_study(o); }).find("--levels 8: level 7"), std::string::npos);
  // Dynamics: solver.dt divided by the ratio.
  CaseConfig dynamic = load_case(cantilever().string(), dir_.string());
  dynamic.solver.type = SolverSpec::Type::Implicit;
  dynamic.solver.dt = 0.1;
  dynamic.solver.steps = 10;
  o.case_config = dynamic;
  o.ratio = 2.0;
  o.levels = 3;
  const StudyPlan d = plan_study(o);
  EXPECT_EQ(d.time_dependence, "dynamics (solver implicit)");
  EXPECT_DOUBLE_EQ(d.levels[2].dt, 0.025);
  EXPECT_EQ(d.levels[2].steps, 40);
}

TEST_F(ConvergenceStudy, ViscoelasticCubeShowsItsSchemesOrdersInTime) {
  // The Prony recursion's error in time: O(dt^2) for the midpoint factor, O(dt) for backward Euler
  // (docs/theory/viscoelasticity.md; verification/cases/analytic-prony-relaxation). Were dt not
  // refined, the levels would agree exactly and there would be no order at all.
  // From dt = 0.125 s (dt / tau = 0.25) down: the next term of the error expansion is O(dt / tau)
  // relative, so the orders of the two triples are within 0.1 of 2 (midpoint: measured 1.955 and
  // 1.989) and 0.15 of 1 (backward Euler, whose second term is larger: 0.889 and 0.936 at t = 1 s).
  struct Scheme {
    std::string integration;
    double order, tolerance;
  };
  for (const auto& [integration, order, tolerance] :
       std::vector<Scheme>{{"midpoint", 2.0, 0.1}, {"backward_euler", 1.0, 0.15}}) {
    StudyOptions o;
    o.case_config = load_case(visco_cube(integration, 16).string(), dir_.string());
    o.refine = Refine::Time;
    o.levels = 4;
    o.times = {1.0, 2.0};
    const StudyPlan plan = plan_study(o);
    const fs::path out = dir_ / ("study-" + integration);
    fs::create_directories(out);
    const StudyResult r = run_study(plan, o, out);
    ASSERT_EQ(r.levels.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) {
      EXPECT_EQ(r.levels[k].steps, 16 << k);
      EXPECT_DOUBLE_EQ(r.levels[k].size, 0.125 / (1 << k));
      EXPECT_EQ(r.levels[k].tets, r.levels[0].tets);  // one mesh
    }
    ASSERT_EQ(r.quantities.size(), 2u);
    for (const QuantityResult& q : r.quantities) {
      const ConvergenceAnalysis& a = q.analysis;
      EXPECT_EQ(a.verdict, "asymptotic") << integration << " t = " << q.time << ": " << a.reason;
      ASSERT_EQ(a.triples.size(), 2u);
      for (const TripleOrder& t : a.triples)
        EXPECT_NEAR(t.order, order, tolerance)
            << integration << " t = " << q.time << " levels " << t.first + 1;
      std::cerr << integration << " reaction at t = " << q.time << ": orders " << a.triples[0].order << ", "
                << a.triples[1].order << ", extrapolated " << a.extrapolated << " N, finest GCI " << a.gci[3]
                << "\n";
    }
    const nlohmann::json j = study_json(plan, r);
    EXPECT_EQ(j["options"]["refine"], "time");
    EXPECT_TRUE(j.contains("dt_definition"));
    EXPECT_FALSE(j.contains("h_definition"));
    EXPECT_EQ(j["quantities"][0]["dt_s"].size(), 4u);
    EXPECT_FALSE(j["quantities"][0].contains("h_m"));
    EXPECT_EQ(j["levels"][3]["steps"], 128);
    const std::string md = study_markdown(plan, r, "tmlab converge visco.json --refine-in time");
    EXPECT_NE(md.find("| level | steps | dt (s) |"), std::string::npos) << md;
  }
}

TEST_F(ConvergenceStudy, ResumeReusesCompleteLevelsOfTheSamePlanOnly) {
  StudyOptions o;
  o.case_config = load_case(visco_cube("midpoint", 4).string(), dir_.string());
  o.refine = Refine::Time;
  const StudyPlan plan = plan_study(o);
  const fs::path out = dir_ / "study";
  fs::create_directories(out);
  // Nothing there yet: every level runs.
  EXPECT_EQ(check_resume(plan, out), std::vector<LevelAction>(3, LevelAction::Run));
  const StudyResult first = run_study(plan, o, out);
  // Every level complete and of this plan: reused, with the same numbers.
  EXPECT_EQ(check_resume(plan, out), std::vector<LevelAction>(3, LevelAction::Reuse));
  // A level without its completion mark (as an interrupted run leaves it) runs again.
  fs::remove(out / "levels" / "level-2" / "summary.json");
  const std::vector<LevelAction> actions = check_resume(plan, out);
  EXPECT_EQ(actions, std::vector<LevelAction>({LevelAction::Reuse, LevelAction::Run, LevelAction::Reuse}));
  const StudyResult second = run_study(plan, o, out, actions);
  EXPECT_EQ(second.levels[0].run, "reused");
  EXPECT_EQ(second.levels[1].run, "new");
  EXPECT_TRUE(fs::exists(out / "levels" / "level-2" / "summary.json"));
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(second.levels[k].values, first.levels[k].values) << k;
  // Another plan (other steps): refused, naming the level and the difference.
  StudyOptions other = o;
  other.ratio = 3.0;
  const std::string refused = error_of([&] { check_resume(plan_study(other), out); });
  EXPECT_NE(refused.find("--resume: levels/level-2 was run from another plan"), std::string::npos) << refused;
  EXPECT_NE(refused.find("solver.steps': 8 there, 12 here"), std::string::npos) << refused;
  EXPECT_NE(refused.find("run without --resume"), std::string::npos) << refused;
  // A level folder the plan does not have.
  fs::create_directories(out / "levels" / "level-4");
  const std::string extra = error_of([&] { check_resume(plan, out); });
  EXPECT_NE(extra.find("levels/level-4 is not a level of this study (3 levels)"), std::string::npos) << extra;
  fs::remove(out / "levels" / "level-4");
  // Another mesh in the same file, the case unchanged: refused by the mesh's hash.
  write_gmsh22(make_box_mesh(Vec3(0, 0, 0), Vec3(0.01, 0.01, 0.01), 3, 2, 2), (dir_ / "cube.msh").string());
  const std::string mesh = error_of([&] { check_resume(plan, out); });
  EXPECT_NE(mesh.find("levels/level-1 was run from another plan (its mesh"), std::string::npos) << mesh;
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
