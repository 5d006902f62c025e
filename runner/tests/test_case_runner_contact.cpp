// Contact in the case runner (docs/contact.md): a frictionless platen compressing a cube on rollers
// gives the homogeneous uniaxial St VK force in the static, viscoelastic (relaxed), implicit and
// explicit runs; the per-body series and the contact pressure field are written; bad contact input
// (penetration or a gap at t = 0, a rig larger than its mesh, an outer loop that cannot converge)
// stops the run with an error naming the case key and leaves no complete-looking result.
#include "core/base/error.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/results/result_compare.hpp"
#include "core/results/run_output.hpp"
#include "runner/case_runner.hpp"
#include "runner/tests/runner_test_case.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace tmlab::tm {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr double kL = 0.01, kE = 10000.0, kNu = 0.3;

/// A cube on rollers (x = 0, y = 0, z = 0) pressed by a frictionless plane moving down by d: the
/// platen case of runner_test_case.hpp with the solver each test chooses.
class ContactRunnerTest : public runner::RunnerTestCase {
 protected:
  json platen(double d, const json& solver) const {
    json j = RunnerTestCase::platen(d);
    j["solver"] = solver;
    return j;
  }
  RunResult run(const json& j) const {
    RunOptions o;
    o.results_root = (dir_ / "results").string();
    o.plots = false;
    return run_case(config(j), o);
  }
  /// The error of a run that must fail; also checks that no summary.json was written.
  std::string failure(const json& j) const {
    try {
      run(j);
    } catch (const Error& e) {
      EXPECT_FALSE(fs::exists(dir_ / "results" / j["name"].get<std::string>() / "summary.json"));
      return e.what();
    }
    ADD_FAILURE() << "the run succeeded";
    return "";
  }
};

/// The homogeneous uniaxial St VK compression force of the cube (N, > 0) at compression d.
double uniaxial_force(double d) {
  const double l = 1.0 - d / kL, E33 = 0.5 * (l * l - 1.0);
  return -l * kE * E33 * kL * kL;
}

TEST_F(ContactRunnerTest, StaticPlatenGivesTheUniaxialForceAndWritesTheContactOutputs) {
  const double d = 0.001;
  const RunResult r = run(platen(d, {{"type", "static"}, {"steps", 4}}));
  const json& body = r.summary["contact"]["bodies"][0];
  // The force the sample exerts on the platen pushes it up (+z).
  EXPECT_NEAR(body["final_force_N"][2].get<double>(), uniaxial_force(d), 1e-8 * uniaxial_force(d));
  // ... and the support carries the same force (the recorder's sign convention is that of f_int).
  EXPECT_NEAR(body["final_force_N"][2].get<double>(), r.summary["final_reactions_N"]["z0"][2].get<double>(),
              1e-8 * uniaxial_force(d));
  EXPECT_EQ(body["final_active_nodes"].get<int>(), 16);  // the whole top face
  EXPECT_NEAR(body["final_area_m2"].get<double>(), kL * kL, 1e-15);
  EXPECT_EQ(r.summary["contact"]["method"], "augmented_lagrangian");
  EXPECT_GT(r.summary["contact"]["stiffness_N_per_m"].get<double>(), 0.0);
  // Frictionless: the work of the platen is stored (energy balance with contact forces).
  EXPECT_NEAR(r.summary["energy"]["balance_residual_J"].get<double>(), 0.0,
              0.02 * r.summary["energy"]["stored_J"].get<double>());

  H5File h5 = H5File::open_read((fs::path(r.dir) / "timeseries.h5").string());
  const auto fz = h5.read_double("/series/contact_top_force_z");
  ASSERT_EQ(fz.size(), 5u);  // t = 0 and 4 steps
  EXPECT_EQ(fz[0], 0.0);
  EXPECT_NEAR(fz[2], uniaxial_force(d / 2), 1e-8 * uniaxial_force(d));
  EXPECT_EQ(h5.string_attribute("/series/contact_top_force_z", "unit"), "N");
  for (const char* s :
       {"contact_top_moment_x", "contact_top_area", "contact_top_radius", "contact_top_active_nodes",
        "contact_top_max_pressure", "contact_top_position_z", "contact_top_max_penetration"})
    EXPECT_EQ(h5.read_double(std::string("/series/") + s).size(), 5u) << s;
  const auto pmax = h5.read_double("/series/contact_top_max_pressure");
  EXPECT_NEAR(pmax.back(), uniaxial_force(d) / (kL * kL), 1e-6 * uniaxial_force(d) / (kL * kL));
  std::ifstream vtu(fs::path(r.dir) / "vtu" / "step_00004.vtu");
  const std::string text((std::istreambuf_iterator<char>(vtu)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("contact_pressure"), std::string::npos);

  // tmlab compare reports the contact force agreement per body: nil against itself, the relative
  // difference of a 10 % deeper platen otherwise.
  json again = platen(d, {{"type", "static"}, {"steps", 4}});
  again["name"] = "again";
  EXPECT_EQ(compare_results(r.dir, run(again).dir)["rel_diff_contact_force"].get<double>(), 0.0);
  json deeper = platen(1.1 * d, {{"type", "static"}, {"steps", 4}});
  deeper["name"] = "deeper";
  const json c = compare_results(run(deeper).dir, r.dir);
  EXPECT_NEAR(c["contact"]["top"]["rel_diff_force"].get<double>(),
              (uniaxial_force(1.1 * d) - uniaxial_force(d)) / uniaxial_force(d), 1e-6);
}

/// A small sphere indentation of a bonded block, neo-Hookean, 2 load steps (the seed-like rig in
/// miniature): run with solver.linear "auto" (the default) and "ldlt".
TEST_F(ContactRunnerTest, SphereIndentationCountsItsLinearSolvesAndAutoGivesTheLdltAnswer) {
  write_gmsh22(make_box_mesh(Vec3(-0.01, -0.01, 0), Vec3(0.01, 0.01, 0.01), 4, 4, 2),
               (dir_ / "block.msh").string());
  json j = json::parse(R"({
    "name": "indent", "model": "hyperelastic_tl", "mesh": {"file": "block.msh"},
    "material": {"law": "neo_hookean", "E": 3000, "nu": 0.45, "density": 1000},
    "boundary": [{"name": "bottom", "nodes": {"plane": {"axis": "z", "value": 0}}}],
    "contact": {"bodies": [{"name": "indenter", "type": "sphere", "center": [0, 0, 0.015], "radius": 0.005,
                            "displacement": [0, 0, -0.001], "function": {"type": "ramp", "t0": 0, "t1": 1}}]},
    "solver": {"type": "static", "steps": 2, "newton": {"rtol": 1e-12}}
  })");
  const RunResult a = run(j);
  j["name"] = "indent-ldlt";
  j["solver"]["linear"] = "ldlt";
  const RunResult b = run(j);
  // The same answer to the solver tolerance.
  const double fa = a.summary["contact"]["bodies"][0]["final_force_N"][2].get<double>();
  const double fb = b.summary["contact"]["bodies"][0]["final_force_N"][2].get<double>();
  ASSERT_GT(fb, 0.0);
  EXPECT_NEAR(fa, fb, 1e-8 * fb);
  // summary.json counts every solve: one per Newton iteration (no cut-back here), CHOLMOD's or a
  // fallback's, each fallback under its reason, one CHOLMOD analysis for the whole run (the contact
  // terms stay on the mesh graph's pattern).
  for (const RunResult* r : {&a, &b}) {
    const json& s = r->summary["solver"];
    ASSERT_EQ(s["cutbacks"], 0);
    const json& ls = s["linear_solver"];
    const long n = s["newton_iterations"].get<long>();
    EXPECT_EQ(ls["solves"], n);
    EXPECT_EQ(ls["solves_by"]["cholmod"].get<long>() + ls["solves_by"]["ldlt"].get<long>(), n);
    const long fallbacks = ls["fallbacks_to_ldlt"].get<long>();
    EXPECT_EQ(ls["fallbacks"]["indefinite"].get<long>() + ls["fallbacks"]["round_off"].get<long>(),
              fallbacks);
    long by_iteration = 0;
    for (const auto& k : ls["fallbacks_by_newton_iteration"]) by_iteration += k.get<long>();
    EXPECT_EQ(by_iteration, fallbacks);
    EXPECT_EQ(ls.contains("note"), fallbacks > 0);
  }
  const json& auto_ls = a.summary["solver"]["linear_solver"];
  EXPECT_EQ(auto_ls["kind"], "auto");
  // The first iterate of a load step has the contact nodes penetrated by the sphere's whole
  // increment: its trial forces make the curvature term -p H outweigh the tangential stiffness, an
  // indefinite tangent that falls back (docs/theory/newton.md, "Linear solves"; measured: both steps).
  EXPECT_GE(auto_ls["fallbacks_by_newton_iteration"][0].get<long>(), 1) << auto_ls.dump();
  EXPECT_EQ(auto_ls["fallbacks"]["indefinite"], auto_ls["fallbacks_to_ldlt"]);
  EXPECT_EQ(auto_ls["fallbacks"]["round_off"], 0);
  EXPECT_GE(auto_ls["max_negative_pivots"].get<long>(), 1);
  EXPECT_EQ(auto_ls["symbolic_analyses"]["cholmod"], 1);
  EXPECT_EQ(auto_ls["solves_by"]["ldlt"], auto_ls["fallbacks_to_ldlt"]);
  const json& ldlt_ls = b.summary["solver"]["linear_solver"];
  EXPECT_EQ(ldlt_ls["kind"], "ldlt");
  EXPECT_EQ(ldlt_ls["solves_by"]["cholmod"], 0);
  EXPECT_EQ(ldlt_ls["fallbacks_to_ldlt"], 0);
  EXPECT_EQ(ldlt_ls["symbolic_analyses"]["ldlt"], 1);
}

TEST_F(ContactRunnerTest, ViscoelasticPlatenMatchesThePrescribedDisplacementHistory) {
  // The frictionless platen on the homogeneous cube is the same problem as a prescribed u_z of the
  // top face: the Prony model's force history (ramp, then relaxation in the hold) must agree, which
  // checks that contact advances the history once per accepted increment.
  const double d = 0.0005;
  const json prony = json::parse(R"({"prony": {"terms": [{"weight": 1.0, "tau": 0.1}]}})");
  json j = platen(d, {{"type", "static"}, {"t_end", 3.0}, {"steps", 30}});
  j["material"]["viscoelastic"] = prony;
  const RunResult r = run(j);
  json k = j;
  k.erase("contact");
  k["name"] = "prescribed";
  k["boundary"].push_back({{"name", "top"},
                           {"nodes", {{"plane", {{"axis", "z"}, {"value", kL}}}}},
                           {"components", "z"},
                           {"value", {0.0, 0.0, -d}},
                           {"function", {{"type", "ramp"}, {"t0", 0.0}, {"t1", 1.0}}}});
  const RunResult q = run(k);
  H5File h5 = H5File::open_read((fs::path(r.dir) / "timeseries.h5").string());
  H5File h5q = H5File::open_read((fs::path(q.dir) / "timeseries.h5").string());
  const auto fz = h5.read_double("/series/contact_top_force_z");
  const auto fq = h5q.read_double("/series/reaction_top_z");
  ASSERT_EQ(fz.size(), 31u);
  ASSERT_EQ(fq.size(), 31u);
  // The contact gap is met to gap_tol = 1e-8 mean edge (3.3e-11 m), 7e-8 of d: the force agrees to
  // that relative order.
  for (std::size_t n = 0; n < fz.size(); ++n) EXPECT_NEAR(fz[n], -fq[n], 2e-7 * fz[10]) << n;
  for (std::size_t n = 11; n < fz.size(); ++n) EXPECT_LT(fz[n], fz[n - 1]) << n;  // relaxing
  EXPECT_LT(fz.back(), 0.95 * fz[10]);
}

TEST_F(ContactRunnerTest, ImplicitAndExplicitPlatenApproachTheStaticForce) {
  // A slow smooth ramp (1 s against the cube's ~10 ms wave period) and mass damping: the
  // dynamic runs end near the static force.
  const double d = 0.0005;
  for (const char* type : {"implicit", "explicit"}) {
    json j = platen(d, {{"type", type},
                        {"t_end", 1.5},
                        {"dt", std::string(type) == "implicit" ? 0.01 : 1e-4},
                        {"damping", {{"alpha", 200.0}}}});
    j["contact"]["bodies"][0]["function"] = {{"type", "smooth_ramp"}, {"t0", 0.0}, {"t1", 1.0}};
    if (std::string(type) == "implicit") j["solver"]["scheme"] = "backward_euler";
    j["output"] = {{"every", 100000}, {"vtu", false}, {"xdmf", false}};  // the last step only
    j["name"] = std::string("platen_") + type;
    const RunResult r = run(j);
    const json& body = r.summary["contact"]["bodies"][0];
    EXPECT_NEAR(body["final_force_N"][2].get<double>(), uniaxial_force(d), 0.02 * uniaxial_force(d)) << type;
    EXPECT_EQ(body["final_active_nodes"].get<int>(), 16) << type;
    EXPECT_LT(body["final_max_penetration_m"].get<double>(), 1e-9) << type;
    EXPECT_EQ(r.summary["contact"]["scheme"],
              std::string(type) == "implicit" ? "augmented_lagrangian_implicit" : "kinematic_explicit");
  }
}

TEST_F(ContactRunnerTest, BadContactInputStopsTheRunNamingTheKey) {
  const json statics = {{"type", "static"}, {"steps", 2}};
  json j = platen(0.001, statics);
  j["contact"]["bodies"][0]["point"] = json::array({0, 0, 0.0099});  // 0.1 mm into the cube
  std::string e = failure(j);
  EXPECT_NE(e.find("case.json: key 'contact.bodies[0]'"), std::string::npos) << e;
  EXPECT_NE(e.find("penetrates"), std::string::npos) << e;

  j = platen(0.001, statics);
  j["contact"]["bodies"][0]["point"] = json::array({0, 0, 0.012});  // 2 mm above it
  e = failure(j);
  EXPECT_NE(e.find("contact.bodies[0]"), std::string::npos) << e;
  EXPECT_NE(e.find("does not touch"), std::string::npos) << e;
  j["contact"]["max_initial_gap"] = 0.003;  // an approach phase, allowed explicitly: it runs
  j["contact"]["bodies"][0]["displacement"] = json::array({0.0, 0.0, -0.003});
  EXPECT_NO_THROW(run(j));

  j = platen(0.001, statics);
  j["contact"]["bodies"][0] = {{"type", "punch"},
                               {"center", {0.005, 0.005, 0.01}},
                               {"axis", {0, 0, -1}},
                               {"radius", 0.02},
                               {"displacement", {0, 0, -0.001}},
                               {"function", {{"type", "ramp"}, {"t0", 0.0}, {"t1", 1.0}}}};
  e = failure(j);
  EXPECT_NE(e.find("contact.bodies[0]"), std::string::npos) << e;
  EXPECT_NE(e.find("larger than its mesh"), std::string::npos) << e;

  j = platen(0.001, {{"type", "static"}, {"steps", 1}, {"newton", {{"max_cutbacks", 0}}}});
  j["contact"]["max_outer_iterations"] = 1;
  e = failure(j);
  EXPECT_NE(e.find("did not converge"), std::string::npos) << e;
  EXPECT_NE(e.find("contact.bodies[0]"), std::string::npos) << e;
}

}  // namespace
}  // namespace tmlab::tm
