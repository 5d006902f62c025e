// The element kinds in the case runner (mesh.element; docs/elements.md):
//  - p2: a cube on rollers under a uniform dead pressure gives the homogeneous uniaxial St VK
//    solution (exact for 10-node tets: the displacement is linear), with the consistent quadratic
//    load of the pressure, the VTU output on quadratic tets and displacement.h5 on the vertices;
//  - p2 contact at face quadrature points: a frictionless platen compressing the cube gives the
//    uniaxial force, and its load on the top face is the consistent quadratic one (midside nodes
//    carry it, corners nothing);
//  - a small sphere indentation runs with p2 and p1_anp (contact force = support reaction);
//  - refusals name the keys (an element other than p1 on the tensor-mass kernel).
#include "core/base/error.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/quadratic_mesh.hpp"
#include "runner/case_runner.hpp"
#include "runner/contact_stepping.hpp"
#include "runner/problem.hpp"
#include "runner/tests/runner_test_case.hpp"
#include "tensormass/contact/contact_config.hpp"
#include "tensormass/contact/contact_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tmlab::tm {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr double kL = 0.01, kE = 10000.0, kNu = 0.3;

class ElementRunnerTest : public runner::RunnerTestCase {
 protected:
  RunResult run(const json& j) const {
    RunOptions o;
    o.results_root = (dir_ / "results").string();
    o.plots = false;
    return run_case(config(j), o);
  }
  /// The cube on rollers under a dead pressure p on its top face, St VK on the F-based kernel.
  static json pressed(double p, const std::string& element) {
    json j = uniaxial(0.0);
    j["name"] = "pressed-" + element;
    j["model"] = "hyperelastic_tl";
    j["mesh"]["element"] = element;
    j["boundary"].erase(3);
    j["loads"] = json::array({{{"name", "top"},
                               {"type", "pressure"},
                               {"faces", {{"plane", {{"axis", "z"}, {"value", kL}}}}},
                               {"pressure", p},
                               {"function", {{"type", "ramp"}, {"t0", 0}, {"t1", 1}}}}});
    j["solver"]["newton"] = {{"rtol", 1e-12}};
    return j;
  }
};

/// Uniaxial St VK stress: S33 = E E33 (S11 = S22 = 0 gives E11 = E22 = -nu E33), P33 = l3 S33.
/// The stretch l3 under a dead compressive pressure p: -p = l3 E (l3^2 - 1) / 2 (Newton from 1).
double uniaxial_stretch(double p) {
  double l = 1.0;
  for (int k = 0; k < 50; ++k) {
    const double f = l * kE * 0.5 * (l * l - 1.0) + p, df = kE * (1.5 * l * l - 0.5);
    l -= f / df;
  }
  return l;
}

TEST_F(ElementRunnerTest, P2UnderUniformPressureIsTheHomogeneousSolution) {
  const double p = 500.0;  // Pa: 5 % strain
  const RunResult r = run(pressed(p, "p2"));
  const double l3 = uniaxial_stretch(p);
  const double e33 = 0.5 * (l3 * l3 - 1.0), l1 = std::sqrt(1.0 - 2.0 * kNu * e33);
  const auto corner = r.summary["probes"]["corner"]["displacement_m"];
  EXPECT_NEAR(corner[2].get<double>(), (l3 - 1.0) * kL, 1e-9 * kL);
  EXPECT_NEAR(corner[0].get<double>(), (l1 - 1.0) * kL, 1e-9 * kL);
  EXPECT_NEAR(corner[1].get<double>(), (l1 - 1.0) * kL, 1e-9 * kL);
  // The support carries the dead load p L^2 (the pressure acts on the reference face).
  EXPECT_NEAR(r.summary["final_reactions_N"]["z0"][2].get<double>(), p * kL * kL, 1e-9 * p * kL * kL);
  EXPECT_EQ(r.summary["mesh"]["element"], "p2");
  const QuadraticMesh qm = make_quadratic(read_mesh((dir_ / "cube.msh").string()));
  EXPECT_EQ(r.summary["mesh"]["nodes"].get<int>(), qm.num_points());
  // displacement.h5 holds the vertices (as the deal.II reference writes them at any degree).
  H5File h5 = H5File::open_read((fs::path(r.dir) / "displacement.h5").string());
  H5File::Dims dims;
  h5.read_double("/u", &dims);
  EXPECT_EQ(dims.at(1), 3u * static_cast<std::size_t>(qm.num_vertices));
  // The VTU files are quadratic tets over all the nodes.
  std::ifstream in(fs::path(r.dir) / "vtu" / "step_00000.vtu");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("NumberOfPoints=\"" + std::to_string(qm.num_points()) + "\""), std::string::npos);
}

TEST_F(ElementRunnerTest, P2PlatenContactIsUniaxialWithTheConsistentLoad) {
  const double d = 0.0005;
  json j = platen(d);
  j["name"] = "platen-p2";
  j["model"] = "hyperelastic_tl";
  j["mesh"]["element"] = "p2";
  const CaseConfig cfg = config(j);
  runner::Problem p(cfg);
  const ContactSettings cs = contact_settings(cfg.contact, cfg.file);
  VecX u = VecX::Zero(p.system.num_dofs());
  NewtonOptions newton;
  newton.rtol = 1e-12;
  ContactStaticSolver solver(p.system, p.mesh, p.quadratic.get(), cs.bodies, cs.options, newton, 0.0, u);
  solver.advance(0.0, 1.0, u);
  const ContactBodyState& b = solver.state()[0];
  const double l3 = 1.0 - d / kL, total = -l3 * kE * 0.5 * (l3 * l3 - 1.0) * kL * kL;
  EXPECT_NEAR(b.force.z(), total, 1e-6 * total);
  EXPECT_NEAR(b.area, kL * kL, 1e-15);
  double corners = 0.0, midside = 0.0;
  for (std::size_t i = 0; i < b.nodes.size(); ++i) {
    if (p.quadratic->is_midside(b.nodes[i]))
      midside -= b.nodal_force[i].z();
    else
      corners = std::max(corners, b.nodal_force[i].norm());
  }
  EXPECT_NEAR(midside, total, 1e-6 * total);
  EXPECT_LT(corners, 1e-6 * total);
  // The run through the runner gives the same force.
  const RunResult r = run(j);
  EXPECT_NEAR(r.summary["contact"]["bodies"][0]["final_force_N"][2].get<double>(), total, 1e-6 * total);
}

/// A small sphere indentation of a bonded block, neo-Hookean: the contact force equals the support
/// reaction, the force is positive, and every step converges in a few outer iterations with the
/// default contact options, for each element. (P2 with a multiplier per face point, 6 per
/// triangle, redundant against the face nodes, needed more than the default 30: docs/contact.md.)
TEST_F(ElementRunnerTest, SphereIndentationRunsWithEveryElement) {
  write_gmsh22(make_box_mesh(Vec3(-0.01, -0.01, 0), Vec3(0.01, 0.01, 0.01), 4, 4, 2),
               (dir_ / "block.msh").string());
  json j = json::parse(R"({
    "name": "indent", "model": "hyperelastic_tl", "mesh": {"file": "block.msh"},
    "material": {"law": "neo_hookean", "E": 3000, "nu": 0.45, "density": 1000},
    "boundary": [{"name": "bottom", "nodes": {"plane": {"axis": "z", "value": 0}}}],
    "contact": {"bodies": [{"name": "indenter", "type": "sphere", "center": [0, 0, 0.015], "radius": 0.005,
                            "displacement": [0, 0, -0.001], "function": {"type": "ramp", "t0": 0, "t1": 1}}]},
    "solver": {"type": "static", "steps": 2}
  })");
  for (const char* element : {"p1", "p1_anp", "p2", "p2_mean_dilatation"}) {
    j["name"] = std::string("indent-") + element;
    j["mesh"]["element"] = element;
    const RunResult r = run(j);
    const double f = r.summary["contact"]["bodies"][0]["final_force_N"][2].get<double>();
    EXPECT_GT(f, 0.0) << element;
    EXPECT_NEAR(f, r.summary["final_reactions_N"]["bottom"][2].get<double>(), 1e-6 * f) << element;
    int most = 0;
    for (const auto& n : r.summary["contact"]["outer_iterations_per_step"])
      most = std::max(most, n.get<int>());
    EXPECT_LE(most, 10) << element;
    std::printf("[ measured ] %s sphere indentation: at most %d outer iterations per step\n", element, most);
  }
}

TEST_F(ElementRunnerTest, TensorMassOnAQuadraticElementIsRefused) {
  json j = pressed(100.0, "p2");
  j["model"] = "tensor_mass";
  try {
    run(j);
    ADD_FAILURE() << "not refused";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'mesh.element'"), std::string::npos) << m;
    EXPECT_NE(m.find("'model'"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace tmlab::tm
