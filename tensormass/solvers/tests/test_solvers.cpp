// Solver tests: static Newton, explicit central difference, implicit backward Euler / Newmark (loads,
// constraints and time functions have their own tests beside their sources).
// The cantilever under gravity must reach the same rest state with all three (issue test 5), each
// time integrator shows its observed order, and the explicit stability estimate is meaningful.
#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/solvers/explicit_dynamics.hpp"
#include "tensormass/solvers/implicit_dynamics.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/lumped_mass.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::tm {
namespace {

/// A 40 x 10 x 10 mm soft cantilever clamped at x = 0 (E = 100 kPa, nu = 0.3, rho = 1000): its own
/// weight bends it by ~4 mm, a geometrically nonlinear but well-posed static problem.
struct Cantilever {
  Mesh mesh;
  StVenantKirchhoff material = StVenantKirchhoff::from_young_poisson(100e3, 0.3);
  double density = 1000.0;
  std::unique_ptr<TensorMassStVK> model;

  explicit Cantilever(int nx = 8, int n = 2) {
    mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(0.04, 0.01, 0.01), nx, n, n);
    model = std::make_unique<TensorMassStVK>(mesh, material);
  }
  MechanicalSystem system(RayleighDamping damping, Vec3 g = Vec3(0, 0, -9.81),
                          TimeFunction gravity_function = TimeFunction::constant()) const {
    NodeSelector clamp;
    clamp.kind = NodeSelector::Kind::Plane;
    clamp.axis = 0;
    clamp.value = 0.0;
    DirichletCondition fixed;
    fixed.name = "clamp";
    fixed.nodes = select_nodes(mesh, clamp);
    const VecX node_mass = lumped_node_mass(mesh, density);
    ExternalLoads loads(mesh, node_mass);
    Gravity grav;
    grav.acceleration = g;
    grav.function = gravity_function;
    loads.add(grav);
    return MechanicalSystem(*model, lumped_dof_mass(node_mass), DirichletSet(mesh.num_points(), {fixed}),
                            loads, damping);
  }
};

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

/// Issue test 5: static, explicit-to-rest and implicit-to-rest give the same equilibrium.
TEST(Solvers, StaticExplicitAndImplicitAgreeAtRest) {
  Cantilever c;
  MechanicalSystem sys_static = c.system({});
  VecX u_static = VecX::Zero(sys_static.num_dofs());
  StaticSolver(sys_static, NewtonOptions{}).advance(0.0, 1.0, u_static);
  const double scale = u_static.norm();

  // Damping near critical for the first bending mode: omega_1 from the static deflection.
  // Mass damping alpha = 2 zeta omega_1 with zeta ~ 1.
  double tip = 0.0;
  for (Index i = 0; i < c.mesh.num_points(); ++i) tip = std::min(tip, u_static[3 * i + 2]);
  const double omega1 = std::sqrt(9.81 / std::abs(tip));
  const RayleighDamping damping{2.0 * omega1, 0.0};

  // Implicit backward Euler with large steps to rest.
  {
    MechanicalSystem sys = c.system(damping);
    ImplicitDynamics integ(sys, ImplicitScheme::BackwardEuler, NewtonOptions{});
    VecX zero = VecX::Zero(sys.num_dofs());
    integ.initialize(0.0, zero, zero);
    double t = 0.0;
    const double dt = 0.02;
    for (int k = 0; k < 400; ++k, t += dt) integ.step(t, dt);
    EXPECT_LT((integ.displacement() - u_static).norm() / scale, 1e-6);
  }
  // Explicit central difference to rest.
  {
    MechanicalSystem sys = c.system(damping);
    const StabilityEstimate est = estimate_critical_time_step(sys);
    const double dt = 0.8 * est.dt_critical;
    CentralDifference integ(sys, dt);
    VecX zero = VecX::Zero(sys.num_dofs());
    integ.initialize(0.0, zero, zero);
    double t = 0.0;
    const double t_end = 40.0 / omega1 * 2.0;
    while (t < t_end) {
      integ.step(t, dt);
      t += dt;
    }
    EXPECT_LT((integ.displacement() - u_static).norm() / scale, 1e-5);
  }
}

TEST(ExplicitDynamics, RejectsTimeStepAboveCriticalAndBlowsUpThere) {
  Cantilever c(4, 1);
  MechanicalSystem sys = c.system({}, Vec3::Zero());
  const StabilityEstimate est = estimate_critical_time_step(sys);
  EXPECT_GT(est.dt_critical, est.dt_guaranteed * 0.999);
  EXPECT_THROW(CentralDifference(sys, 1.05 * est.dt_critical), Error);

  // A small random initial velocity: stable at 0.95 dt_crit, unstable at 1.05 dt_crit.
  VecX v0 = VecX::Zero(sys.num_dofs());
  for (Eigen::Index i = 0; i < v0.size(); ++i) v0[i] = 1e-4 * std::sin(0.7 * static_cast<double>(i) + 0.3);
  sys.bc().zero_constrained(v0);
  auto run = [&](double dt, int steps) {
    CentralDifference integ(sys, dt, /*check_stability=*/false);
    integ.initialize(0.0, VecX::Zero(sys.num_dofs()), v0);
    double t = 0.0;
    for (int k = 0; k < steps; ++k, t += dt) integ.step(t, dt);
    return integ.displacement().norm();
  };
  const double stable = run(0.95 * est.dt_critical, 3000);
  EXPECT_LT(stable, 1e-3);
  // Just above the limit the highest mode grows without bound; the integrator stops with an error.
  try {
    run(1.05 * est.dt_critical, 3000);
    FAIL() << "expected the run above the critical step to blow up";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unstable at step"), std::string::npos) << e.what();
  }
}

/// Observed order in dt by self-convergence: e(dt) = |u_dt(T) - u_{dt/2}(T)| shrinks as dt^p.
template <class Run>
double observed_order(Run run, double dt) {
  const VecX a = run(dt), b = run(dt / 2), c2 = run(dt / 4);
  return std::log2((a - b).norm() / (b - c2).norm());
}

TEST(TimeIntegrators, ObservedOrders) {
  // Gravity switched on smoothly over [0, T] (C1 ramp) so that the stiff, unresolved modes are
  // hardly excited and the error measured is that of the resolved motion.
  Cantilever c(4, 1);
  const double T = 0.05;
  MechanicalSystem sys = c.system({5.0, 0.0}, Vec3(0, 0, -9.81), TimeFunction::smooth_ramp(0.0, T));
  VecX zero = VecX::Zero(sys.num_dofs());
  auto implicit_run = [&](ImplicitScheme s) {
    return [&, s](double dt) {
      ImplicitDynamics integ(sys, s, NewtonOptions{40, 1e-11, 1e-16});
      integ.initialize(0.0, zero, zero);
      const int n = static_cast<int>(std::lround(T / dt));
      double t = 0.0;
      for (int k = 0; k < n; ++k, t += dt) integ.step(t, dt);
      return VecX(integ.displacement());
    };
  };
  const double p_be = observed_order(implicit_run(ImplicitScheme::BackwardEuler), T / 100);
  const double p_nm = observed_order(implicit_run(ImplicitScheme::Newmark), T / 100);
  EXPECT_NEAR(p_be, 1.0, 0.15);
  EXPECT_NEAR(p_nm, 2.0, 0.15);

  const double dt_crit = estimate_critical_time_step(sys).dt_critical;
  auto explicit_run = [&](double dt) {
    CentralDifference integ(sys, dt);
    integ.initialize(0.0, zero, zero);
    const int n = static_cast<int>(std::lround(T / dt));
    double t = 0.0;
    for (int k = 0; k < n; ++k, t += dt) integ.step(t, dt);
    return VecX(integ.displacement());
  };
  const double dt0 = T / std::ceil(T / (0.5 * dt_crit));
  const double p_cd = observed_order(explicit_run, dt0);
  EXPECT_NEAR(p_cd, 2.0, 0.15);
}

TEST(Newton, PrescribedDisplacementIsReachedAndReactionBalancesLoad) {
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
