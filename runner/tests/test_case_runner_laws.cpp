// The case runner with every hyperelastic law on the F-based kernel (model hyperelastic_tl): the
// uniaxial stretch of a cube against the homogeneous closed form of each law, St VK equal to the
// tensor-mass model, explicit and implicit dynamics settling on the static answer, the objective
// viscoelastic scheme relaxing to the long-term law (on p1 and on the locking-free p1_anp element, in
// static, implicit and explicit runs), and the refusal of another law on tensor_mass.
#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/results/result_compare.hpp"
#include "runner/case_runner.hpp"
#include "tensormass/materials/law_factory.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

namespace tmlab::tm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kSide = 0.01;  // m, the cube
constexpr double kArea = kSide * kSide;

/// The material sections of the tests: one per law, moduli of order 10 kPa.
json material_of(const std::string& law) {
  if (law == "stvk" || law == "neo_hookean") return {{"law", law}, {"E", 10000.0}, {"nu", 0.3}};
  if (law == "mooney_rivlin") return {{"law", law}, {"c10", 1500.0}, {"c01", 500.0}, {"kappa", 2e4}};
  if (law == "yeoh") return {{"law", law}, {"c10", 2000.0}, {"c20", 500.0}, {"c30", 100.0}, {"kappa", 2e4}};
  if (law == "ogden") return {{"law", law}, {"mu", {3000.0, -200.0}}, {"alpha", {2.0, -2.0}}, {"kappa", 2e4}};
  return {{"law", law}, {"c1", 1000.0}, {"c2", 2.0}, {"kappa", 2e4}};
}

/// Homogeneous uniaxial stretch l along x with free lateral faces: F = diag(l, lt, lt), lt from
/// S_yy = 0 (bisection to round-off), nominal force l S_xx A0.
double uniaxial_force(const Law& law, double l) {
  auto state = [&](double lt) {
    Mat3 E = Mat3::Zero();
    E(0, 0) = 0.5 * (l * l - 1.0);
    E(1, 1) = E(2, 2) = 0.5 * (lt * lt - 1.0);
    return law.pk2_stress(E);
  };
  double lo = 0.3, hi = 1.0;  // tension: S_yy(1) > 0 > S_yy(0.3)
  for (int it = 0; it < 200 && hi - lo > 1e-16; ++it) {
    const double mid = 0.5 * (lo + hi);
    (state(mid)(1, 1) > 0.0 ? hi : lo) = mid;
  }
  return l * state(0.5 * (lo + hi))(0, 0) * kArea;
}

class CaseRunnerLawsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tmlab_runner_laws_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    write_gmsh22(make_box_mesh(Vec3(0, 0, 0), Vec3(kSide, kSide, kSide), 3, 3, 3),
                 (dir_ / "cube.msh").string());
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Uniaxial stretch by `d` of the cube with symmetry planes x=0, y=0, z=0, ramped over [0, ramp].
  json uniaxial(const std::string& law, double d, double ramp = 1.0) const {
    json m = material_of(law);
    m["density"] = 1000.0;
    return {{"name", "uniaxial_" + law},
            {"model", "hyperelastic_tl"},
            {"mesh", {{"file", "cube.msh"}}},
            {"material", m},
            {"boundary",
             {{{"name", "x0"}, {"nodes", {{"plane", {{"axis", "x"}, {"value", 0}}}}}, {"components", "x"}},
              {{"name", "y0"}, {"nodes", {{"plane", {{"axis", "y"}, {"value", 0}}}}}, {"components", "y"}},
              {{"name", "z0"}, {"nodes", {{"plane", {{"axis", "z"}, {"value", 0}}}}}, {"components", "z"}},
              {{"name", "pull"},
               {"nodes", {{"plane", {{"axis", "x"}, {"value", kSide}}}}},
               {"components", "x"},
               {"value", {d, 0, 0}},
               {"function", {{"type", "ramp"}, {"t0", 0}, {"t1", ramp}}}}}},
            {"solver", {{"type", "static"}, {"steps", 4}}},
            {"output", {{"vtu", false}, {"xdmf", false}}}};
  }
  CaseConfig config(const json& j) const {
    return parse_case(j, (dir_ / "case.json").string(), {dir_.string()});
  }
  RunResult run(const json& j) const {
    RunOptions o;
    o.results_root = (dir_ / "results").string();
    o.plots = false;
    return run_case(config(j), o);
  }
  double pull_force(const RunResult& r) const {
    return r.summary["final_reactions_N"]["pull"][0].get<double>();
  }
  Law law(const json& j) const {
    const CaseConfig c = config(j);
    return make_law(c.material.law, c.material.parameters, "case.json: material");
  }
  fs::path dir_;
};

TEST_F(CaseRunnerLawsTest, EveryLawMatchesItsHomogeneousUniaxialClosedForm) {
  const double d = 0.002, l = 1.0 + d / kSide;  // 20 % stretch
  for (const char* name : kMaterialLawNames) {
    const json j = uniaxial(name, d);
    const RunResult r = run(j);
    const double expected = uniaxial_force(law(j), l);
    // P1 tets reproduce the homogeneous state exactly: the force is Newton's (rtol 1e-10) answer.
    EXPECT_NEAR(pull_force(r), expected, 1e-8 * expected) << name;
    EXPECT_EQ(r.summary["material"]["law"], name);
    EXPECT_EQ(r.summary["model"], "hyperelastic_tl");
    // Quasi-static: the work of the supports is the stored energy (trapezoidal rule over 4 steps).
    const json& e = r.summary["energy"];
    EXPECT_NEAR(e["external_work_J"].get<double>(), e["stored_J"].get<double>(),
                2e-2 * e["stored_J"].get<double>())
        << name << " " << e.dump();
  }
}

TEST_F(CaseRunnerLawsTest, StVKOnTheFBasedKernelIsTheTensorMassModel) {
  json j = uniaxial("stvk", 0.002);
  const RunResult a = run(j);
  j["model"] = "tensor_mass";
  j["name"] = "uniaxial_tm";
  const RunResult b = run(j);
  const json cmp = compare_results(a.dir, b.dir);
  EXPECT_LT(cmp["rel_diff_displacement"].get<double>(), 1e-9) << cmp.dump();
  EXPECT_LT(cmp["rel_diff_reaction"].get<double>(), 1e-9) << cmp.dump();
}

TEST_F(CaseRunnerLawsTest, AnotherLawOnTheStVKModelsIsRefusedNamingTheModelToUse) {
  for (const char* model : {"tensor_mass", "tl_oracle"}) {
    json j = uniaxial("ogden", 0.001);
    j["model"] = model;
    try {
      run(j);
      FAIL() << "expected an error";
    } catch (const Error& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("case.json: key 'model'"), std::string::npos) << m;
      EXPECT_NE(m.find("material.law 'ogden'"), std::string::npos) << m;
      EXPECT_NE(m.find("\"model\": \"hyperelastic_tl\""), std::string::npos) << m;
    }
  }
  // A viscoelastic scheme the general-law model does not have is refused, naming the key.
  json j = uniaxial("yeoh", 0.001);
  j["material"]["viscoelastic"] = {{"history", "nodal_force"},
                                   {"prony", {{"terms", {{{"weight", 1.0}, {"tau", 0.1}}}}}}};
  try {
    run(j);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("key 'material.viscoelastic'"), std::string::npos) << e.what();
  }
}

TEST_F(CaseRunnerLawsTest, DynamicsSettleOnTheStaticAnswer) {
  // A slow ramp (0.1 s, about 10 periods of the cube) then a hold: the explicit and implicit runs end
  // at rest on the static equilibrium of the law, up to the remaining (damped) oscillation.
  const double d = 0.001, l = 1.0 + d / kSide;
  for (const char* name : {"mooney_rivlin", "ogden"}) {
    json j = uniaxial(name, d, 0.1);
    const double expected = uniaxial_force(law(j), l);
    j["solver"] = {{"type", "explicit"}, {"dt", 1e-4}, {"t_end", 0.3}, {"damping", {{"alpha", 100.0}}}};
    const RunResult ex = run(j);
    EXPECT_NEAR(pull_force(ex), expected, 1e-5 * expected) << name;  // measured 7e-7
    j["name"] = std::string("implicit_") + name;
    j["solver"] = {{"type", "implicit"}, {"dt", 2e-3}, {"t_end", 0.3}, {"scheme", "backward_euler"}};
    const RunResult im = run(j);
    EXPECT_NEAR(pull_force(im), expected, 1e-8 * expected) << name;  // measured 4e-13
  }
}

TEST_F(CaseRunnerLawsTest, ViscoelasticLawRelaxesToTheLongTermLaw) {
  // Stretch in the first step (0.04 s), hold 50 tau: the force starts near the instantaneous response
  // (long-term weight 1: twice the long-term modulus, less the relaxation within the step) and ends
  // on the long-term law's closed form; the dissipated energy is positive.
  const double d = 0.001, l = 1.0 + d / kSide;
  json j = uniaxial("yeoh", d, 0.04);
  j["material"]["viscoelastic"] = {{"scheme", "objective"},
                                   {"prony", {{"terms", {{{"weight", 1.0}, {"tau", 0.1}}}}}}};
  j["solver"] = {{"type", "static"}, {"steps", 125}, {"t_end", 5.0}};
  const RunResult r = run(j);
  const double long_term = uniaxial_force(law(j), l);
  EXPECT_NEAR(pull_force(r), long_term, 1e-8 * long_term);
  EXPECT_GT(r.summary["energy"]["total_dissipation_J"].get<double>(), 0.0);
  EXPECT_EQ(r.summary["viscoelastic"]["history"], "pk2");
  // St VK: the general-law model is the tensor-mass model's objective scheme (pk2, full).
  json s = uniaxial("stvk", d, 0.04);
  s["material"]["viscoelastic"] = j["material"]["viscoelastic"];
  s["solver"] = {{"type", "static"}, {"steps", 10}, {"t_end", 0.4}};
  const RunResult a = run(s);
  s["model"] = "tensor_mass";
  s["name"] = "visco_tm";
  const RunResult b = run(s);
  const json cmp = compare_results(a.dir, b.dir);
  EXPECT_LT(cmp["rel_diff_reaction"].get<double>(), 1e-9) << cmp.dump();
  EXPECT_LT(cmp["rel_diff_energy"].get<double>(), 1e-9) << cmp.dump();
}

TEST_F(CaseRunnerLawsTest, ViscoelasticP1AnpRunsAsP1OnTheHomogeneousStretch) {
  // mesh.element p1_anp with material.viscoelastic (ViscoelasticAveragedPressureTet) through the
  // runner. Static: the stretch is homogeneous at every step, where the element is P1 (Jbar = J), so
  // the run equals the P1 run to round-off, relaxes to the long-term law's closed form and
  // dissipates. Implicit and explicit: inertia makes the transient non-homogeneous (the elements
  // then differ), and both settle on the same relaxed answer: the final forces agree within the
  // settle-test tolerance of DynamicsSettleOnTheStaticAnswer.
  const double d = 0.001, l = 1.0 + d / kSide;
  json j = uniaxial("neo_hookean", d, 0.04);
  j["material"]["viscoelastic"] = {{"scheme", "objective"},
                                   {"prony", {{"terms", {{{"weight", 1.0}, {"tau", 0.05}}}}}}};
  j["solver"] = {{"type", "static"}, {"steps", 50}, {"t_end", 2.0}};
  const RunResult p1 = run(j);
  j["mesh"]["element"] = "p1_anp";
  j["name"] = "visco_anp_static";
  const RunResult anp = run(j);
  EXPECT_EQ(anp.summary["mesh"]["element"], "p1_anp");
  const json cmp = compare_results(p1.dir, anp.dir);
  EXPECT_LT(cmp["rel_diff_reaction"].get<double>(), 1e-9) << cmp.dump();
  EXPECT_LT(cmp["rel_diff_energy"].get<double>(), 1e-9) << cmp.dump();
  const double long_term = uniaxial_force(law(j), l);
  EXPECT_NEAR(pull_force(anp), long_term, 1e-8 * long_term);
  EXPECT_GT(anp.summary["energy"]["total_dissipation_J"].get<double>(), 0.0);
  const json dyn[2] = {{{"type", "implicit"}, {"dt", 2e-3}, {"t_end", 0.6}, {"scheme", "backward_euler"}},
                       {{"type", "explicit"}, {"dt", 1e-4}, {"t_end", 0.6}, {"damping", {{"alpha", 100.0}}}}};
  for (const json& solver : dyn) {
    const std::string type = solver["type"];
    j["solver"] = solver;
    j["mesh"]["element"] = "p1";
    j["name"] = "visco_p1_" + type;
    const RunResult a = run(j);
    j["mesh"]["element"] = "p1_anp";
    j["name"] = "visco_anp_" + type;
    const RunResult b = run(j);
    std::printf("viscoelastic p1_anp %s: final pull force %.9e N (p1 %.9e, long-term %.9e)\n", type.c_str(),
                pull_force(b), pull_force(a), long_term);
    EXPECT_NEAR(pull_force(b), pull_force(a), 1e-5 * long_term) << type;
    EXPECT_GT(b.summary["energy"]["total_dissipation_J"].get<double>(), 0.0) << type;
  }
}

}  // namespace
}  // namespace tmlab::tm
