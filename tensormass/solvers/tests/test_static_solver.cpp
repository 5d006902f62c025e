// StaticSolver: load stepping with Newton on the cantilever under gravity (quadratic convergence),
// a prescribed displacement with balanced reactions, and follower pressure (non-symmetric load
// stiffness) against the dead load.
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/solvers/tests/cantilever.hpp"
#include "tensormass/system/lumped_mass.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace tmlab::tm {
namespace {

using testing::Cantilever;

TEST(StaticSolver, CantileverUnderGravityConvergesQuadratically) {
  Cantilever c;
  // Gravity ramped over five load steps: each step converges in a few Newton iterations.
  MechanicalSystem sys = c.system({}, Vec3(0, 0, -9.81), TimeFunction::ramp(0.0, 1.0));
  StaticSolver solver(sys, NewtonOptions{});
  VecX u = VecX::Zero(sys.num_dofs());
  StaticStepReport rep;
  for (int k = 1; k <= 5; ++k) {
    rep = solver.advance(0.2 * (k - 1), 0.2 * k, u);
    EXPECT_TRUE(rep.newton.converged);
    EXPECT_EQ(rep.cutbacks, 0);
    EXPECT_LE(rep.newton.iterations, 8) << "load step " << k;
  }
  // Quadratic convergence: once in the asymptotic range each residual is ~ the square of the last.
  const auto& h = rep.newton.history;
  ASSERT_GE(h.size(), 3u);
  const double r0 = h.front();
  bool saw_quadratic = false;
  for (std::size_t k = 1; k + 1 < h.size(); ++k)
    if (h[k] / r0 < 1e-2 && h[k + 1] / r0 <= 10.0 * std::pow(h[k] / r0, 2)) saw_quadratic = true;
  EXPECT_TRUE(saw_quadratic) << ::testing::PrintToString(h);
  // The tip sags downwards by a visible amount (soft beam: several mm).
  double tip = 0.0;
  for (Index i = 0; i < c.mesh.num_points(); ++i)
    if (c.mesh.points[i].x() > 0.0399) tip = std::min(tip, u[3 * i + 2]);
  EXPECT_LT(tip, -1e-3);
  EXPECT_GT(tip, -0.04);
}

TEST(StaticSolver, PrescribedDisplacementIsReachedAndReactionBalancesLoad) {
  Cantilever c(4, 1);
  NodeSelector tip;
  tip.kind = NodeSelector::Kind::Plane;
  tip.axis = 0;
  tip.value = 0.04;
  NodeSelector clamp = tip;
  clamp.value = 0.0;
  DirichletCondition fixed{
      "clamp", select_nodes(c.mesh, clamp), {true, true, true}, Vec3::Zero(), TimeFunction::constant()};
  DirichletCondition pushed{"tip",
                            select_nodes(c.mesh, tip),
                            {false, false, true},
                            Vec3(0, 0, -0.005),
                            TimeFunction::ramp(0.0, 1.0)};
  const VecX nm = lumped_node_mass(c.mesh, c.density);
  MechanicalSystem sys(*c.model, lumped_dof_mass(nm), DirichletSet(c.mesh.num_points(), {fixed, pushed}),
                       ExternalLoads(c.mesh, nm));
  StaticSolver solver(sys, NewtonOptions{});
  VecX u = VecX::Zero(sys.num_dofs());
  solver.advance(0.0, 1.0, u);
  for (Index n : pushed.nodes) EXPECT_DOUBLE_EQ(u[3 * n + 2], -0.005);
  VecX r;
  c.model->internal_force(u, r);
  const Vec3 r_tip = sys.bc().resultant(1, r);
  const Vec3 r_clamp = sys.bc().resultant(0, r);
  EXPECT_LT(r_tip.z(), 0.0);  // the body resists being pushed down: internal force points down there
  // Global balance in z (no other loads): the two reactions cancel.
  EXPECT_NEAR(r_tip.z() + r_clamp.z(), 0.0, 1e-9 * std::abs(r_tip.z()));
}

/// Follower pressure in a static solve: the non-symmetric load stiffness (sparse LU path) gives
/// Newton convergence, and the answer differs from the dead-load one by an amount second order in
/// the load.
TEST(StaticSolver, FollowerPressureConvergesAndDiffersFromDeadLoad) {
  const Mesh mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(0.01, 0.01, 0.01), 3, 3, 3);
  const StVenantKirchhoff mat = StVenantKirchhoff::from_young_poisson(10e3, 0.3);
  TensorMassStVK model(mesh, mat);
  NodeSelector bottom, top;
  bottom.kind = top.kind = NodeSelector::Kind::Plane;
  bottom.axis = top.axis = 2;
  bottom.value = 0.0;
  top.value = 0.01;
  DirichletCondition fixed{
      "bottom", select_nodes(mesh, bottom), {true, true, true}, Vec3::Zero(), TimeFunction::constant()};
  const VecX nm = lumped_node_mass(mesh, 1000.0);
  auto solve = [&](double p, bool follower, int* iterations) {
    ExternalLoads loads(mesh, nm);
    // A tilted pressure patch: the top face pushed in, with a shear load that rotates it.
    loads.add(SurfacePressure{"top", select_faces(mesh, top), p, follower, TimeFunction::ramp(0.0, 1.0)});
    loads.add(
        NodalForce{"shear", select_nodes(mesh, top), Vec3(p * 1e-5, 0, 0), TimeFunction::ramp(0.0, 1.0)});
    MechanicalSystem sys(model, lumped_dof_mass(nm), DirichletSet(mesh.num_points(), {fixed}), loads);
    StaticSolver solver(sys, NewtonOptions{});
    VecX u = VecX::Zero(sys.num_dofs());
    int its = 0;
    for (int k = 1; k <= 4; ++k) {
      const StaticStepReport r = solver.advance(0.25 * (k - 1), 0.25 * k, u);
      EXPECT_TRUE(r.newton.converged);
      its = std::max(its, r.newton.iterations);
    }
    if (iterations) *iterations = its;
    return u;
  };
  int its = 0;
  const VecX uf = solve(1000.0, true, &its), ud = solve(1000.0, false, nullptr);
  EXPECT_LE(its, 8);
  const double rel_large = (uf - ud).norm() / ud.norm();
  EXPECT_GT(rel_large, 1e-2);
  // The follower-minus-dead difference is second order in the load, so relative to the
  // displacement it shrinks linearly: 100x less load, ~100x smaller relative difference.
  const VecX uf1 = solve(10.0, true, nullptr), ud1 = solve(10.0, false, nullptr);
  const double rel_small = (uf1 - ud1).norm() / ud1.norm();
  EXPECT_LT(rel_small, 0.03 * rel_large) << rel_small << " vs " << rel_large;
}

}  // namespace
}  // namespace tmlab::tm
