// Mesh-convergence measurement of the sphere indentation against Hertz (label `slow`, on demand:
// ctest -L contact_hertz). A rigid sphere of radius R indents a St VK block by d = 0.1 R: quarter
// model [0, 3R]^2 x [-3R, 0] on symmetry rollers with a clamped bottom, graded towards the contact
// (x = 3R xi^2 per axis, n cells per axis). Prints F/F_Hertz per mesh and the observed order of
// the force differences between successive meshes (n doubling). The limit is not Hertz: the block
// is finite (3R, about 9.5 contact radii) and St VK is geometrically nonlinear, so the strict
// Hertz case of the verification catalogue needs a larger domain; this test checks that the
// discrete force converges (differences shrink) and documents the numbers.
#include "tensormass/contact/contact_solver.hpp"

#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/system/lumped_mass.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

namespace tmlab::tm {
namespace {

constexpr double kYoung = 10e3, kPoisson = 0.3;

struct Result {
  int n = 0;
  double force = 0.0;   // full-model force on the sphere, N
  double radius = 0.0;  // area-equivalent contact radius, m
  int active = 0;
};

Result indent(int n, double R, double d) {
  const double W = 3.0 * R;
  Mesh mesh = make_box_mesh(Vec3(0, 0, -1), Vec3(1, 1, 0), n, n, n);
  for (Vec3& p : mesh.points) {
    p.x() = W * p.x() * p.x();
    p.y() = W * p.y() * p.y();
    p.z() = -W * p.z() * p.z();
  }
  auto plane = [&](int axis, double v, std::array<bool, 3> comp, const char* name) {
    DirichletCondition c;
    c.name = name;
    c.nodes = select_nodes(mesh, NodeSelector::plane(axis, v, 1e-12 * W));
    c.components = comp;
    return c;
  };
  std::vector<DirichletCondition> bc = {plane(0, 0.0, {true, false, false}, "x0"),
                                        plane(1, 0.0, {false, true, false}, "y0"),
                                        plane(2, -W, {true, true, true}, "bottom")};
  const StVenantKirchhoff mat = StVenantKirchhoff::from_young_poisson(kYoung, kPoisson);
  TensorMassStVK model(mesh, mat);
  const VecX node_mass = lumped_node_mass(mesh, 1000.0);
  MechanicalSystem sys(model, lumped_dof_mass(node_mass), DirichletSet(mesh.num_points(), bc),
                       ExternalLoads(mesh, node_mass));
  RigidBody sphere = RigidBody::sphere("indenter", Vec3(0, 0, R), R);
  sphere.displacement = Vec3(0, 0, -d);
  sphere.function = TimeFunction::ramp(0.0, 1.0);
  VecX u = VecX::Zero(sys.num_dofs());
  ContactStaticSolver solver(sys, mesh, {sphere}, ContactOptions{}, NewtonOptions{}, 0.0, u);
  solver.set_linear_solver(ConstrainedLinearSolver::Kind::ConjugateGradient);
  const int steps = 5;
  ContactStepReport rep;
  for (int k = 1; k <= steps; ++k) rep = solver.advance(double(k - 1) / steps, double(k) / steps, u);
  Result r;
  r.n = n;
  r.force = 4.0 * rep.bodies[0].force.z();
  r.radius = std::sqrt(4.0 * rep.bodies[0].area / 3.14159265358979323846);
  r.active = rep.bodies[0].active_nodes;
  return r;
}

TEST(ContactHertz, SphereForceConvergesUnderMeshRefinement) {
  const double R = 0.01, d = 0.1 * R;
  const double Fh = 4.0 / 3.0 * kYoung / (1.0 - kPoisson * kPoisson) * std::sqrt(R) * std::pow(d, 1.5);
  const double ah = std::sqrt(R * d);
  std::vector<Result> res;
  for (int n : {4, 8, 16}) {
    res.push_back(indent(n, R, d));
    const Result& r = res.back();
    std::printf(
        "n = %2d: F = %.6e N, F/F_Hertz = %.4f (error %+.2f %%), a_eq/a_Hertz = %.3f, active nodes %d\n", r.n,
        r.force, r.force / Fh, 100.0 * (r.force / Fh - 1.0), r.radius / ah, r.active);
  }
  const double d1 = std::abs(res[1].force - res[0].force), d2 = std::abs(res[2].force - res[1].force);
  std::printf("observed order of the force differences (n = 4, 8, 16): %.2f\n", std::log2(d1 / d2));
  std::printf("Richardson estimate of the mesh limit: F/F_Hertz = %.4f\n",
              (res[2].force + (res[2].force - res[1].force) / (d1 / d2 - 1.0)) / Fh);
  EXPECT_LT(d2, d1);
}

}  // namespace
}  // namespace tmlab::tm
