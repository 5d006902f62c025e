// ImplicitDynamics: backward Euler and Newmark show their observed orders (1 and 2) and backward
// Euler with large steps reaches the static rest state of the damped cantilever (issue test 5).
#include "tensormass/solvers/implicit_dynamics.hpp"
#include "tensormass/solvers/tests/cantilever.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::tm {
namespace {

using testing::Cantilever;

/// Issue test 5 (implicit half): backward Euler with near-critical damping and large steps comes to
/// rest at the static solution (the explicit half is in test_explicit_dynamics.cpp).
TEST(ImplicitDynamics, BackwardEulerComesToRestAtTheStaticSolution) {
  Cantilever c;
  const testing::CantileverRest rest = testing::cantilever_rest(c);
  MechanicalSystem sys = c.system(rest.damping);
  ImplicitDynamics integ(sys, ImplicitScheme::BackwardEuler, NewtonOptions{});
  VecX zero = VecX::Zero(sys.num_dofs());
  integ.initialize(0.0, zero, zero);
  double t = 0.0;
  const double dt = 0.02;
  for (int k = 0; k < 400; ++k, t += dt) integ.step(t, dt);
  EXPECT_LT((integ.displacement() - rest.u_static).norm() / rest.scale, 1e-6);
}

TEST(ImplicitDynamics, ObservedOrdersOfBackwardEulerAndNewmark) {
  Cantilever c(4, 1);
  const double T = testing::kOrderTestEndTime;
  MechanicalSystem sys = testing::smooth_gravity_system(c);
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
  const double p_be = testing::observed_order(implicit_run(ImplicitScheme::BackwardEuler), T / 100);
  const double p_nm = testing::observed_order(implicit_run(ImplicitScheme::Newmark), T / 100);
  EXPECT_NEAR(p_be, 1.0, 0.15);
  EXPECT_NEAR(p_nm, 2.0, 0.15);
}

}  // namespace
}  // namespace tmlab::tm
