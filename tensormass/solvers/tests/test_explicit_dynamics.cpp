// CentralDifference: the critical time step estimate is meaningful (rejected above it, stable
// below, blow-up caught above), second order observed, and it reaches the static rest state of the
// damped cantilever (issue test 5).
#include "core/base/error.hpp"
#include "tensormass/solvers/explicit_dynamics.hpp"
#include "tensormass/solvers/tests/cantilever.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace tmlab::tm {
namespace {

using testing::Cantilever;

/// Issue test 5 (explicit half): central differences with near-critical damping come to rest at
/// the static solution (the implicit half is in test_implicit_dynamics.cpp).
TEST(ExplicitDynamics, ComesToRestAtTheStaticSolution) {
  Cantilever c;
  const testing::CantileverRest rest = testing::cantilever_rest(c);
  MechanicalSystem sys = c.system(rest.damping);
  const StabilityEstimate est = estimate_critical_time_step(sys);
  const double dt = 0.8 * est.dt_critical;
  CentralDifference integ(sys, dt);
  VecX zero = VecX::Zero(sys.num_dofs());
  integ.initialize(0.0, zero, zero);
  double t = 0.0;
  const double t_end = 40.0 / rest.omega1 * 2.0;
  while (t < t_end) {
    integ.step(t, dt);
    t += dt;
  }
  EXPECT_LT((integ.displacement() - rest.u_static).norm() / rest.scale, 1e-5);
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

TEST(ExplicitDynamics, ObservedOrderIsTwo) {
  Cantilever c(4, 1);
  const double T = testing::kOrderTestEndTime;
  MechanicalSystem sys = testing::smooth_gravity_system(c);
  VecX zero = VecX::Zero(sys.num_dofs());
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
  const double p_cd = testing::observed_order(explicit_run, dt0);
  EXPECT_NEAR(p_cd, 2.0, 0.15);
}

}  // namespace
}  // namespace tmlab::tm
