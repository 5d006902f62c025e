// The exponential moments against their closed forms (I_0 = tau (1 - e^{-t/tau}),
// I_1 = tau t - tau^2 (1 - e^{-t/tau})) on both branches (series below t = tau, recursion above),
// against composite Simpson quadrature for a higher moment, and the hereditary integral of a linear
// and a quadratic driver against the same closed forms, with the decay after the ramp.
#include "verification/numerics/exp_moments.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::verify::numerics {
namespace {

double simpson_moment(double t, double tau, int k, int intervals) {
  auto f = [&](double s) { return std::pow(s, k) * std::exp(-(t - s) / tau); };
  const double h = t / intervals;
  double sum = f(0.0) + f(t);
  for (int i = 1; i < intervals; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(i * h);
  return sum * h / 3.0;
}

TEST(ExpMoments, FirstTwoMomentsOnBothBranches) {
  const double tau = 0.7;
  for (double x : {1e-6, 0.05, 0.3, 0.999, 1.0, 1.7, 12.0}) {
    const double t = x * tau;
    const auto I = exp_moments(t, tau, 1);
    ASSERT_EQ(I.size(), 2u);
    const double one_minus = -std::expm1(-t / tau);
    const double I0 = tau * one_minus;
    const double I1 = tau * t - tau * tau * one_minus;
    EXPECT_NEAR(I[0], I0, 1e-14 * I0) << "t/tau = " << x;
    // I_1 ~ t^2 / 2 for small t: the closed form cancels, so compare with the series' own scale.
    const double I1_scale = x < 0.1 ? 1e-9 * t * t : 1e-13 * I1;
    EXPECT_NEAR(I[1], I1, I1_scale) << "t/tau = " << x;
  }
}

TEST(ExpMoments, HigherMomentsAgainstSimpson) {
  const double tau = 2.0;
  for (double x : {0.4, 0.99, 1.01, 3.0}) {
    const double t = x * tau;
    const auto I = exp_moments(t, tau, 4);
    for (int k = 0; k <= 4; ++k) {
      const double ref = simpson_moment(t, tau, k, 4000);
      EXPECT_NEAR(I[static_cast<std::size_t>(k)], ref, 1e-11 * ref) << "k = " << k << ", t/tau = " << x;
    }
  }
}

TEST(ExpMoments, SmallTimeLimit) {
  // t << tau: I_k = t^{k+1} / (k + 1) (1 - t / ((k+2) tau) + O(t^2 / tau^2)).
  const double tau = 1.0, t = 1e-4;
  const auto I = exp_moments(t, tau, 3);
  for (int k = 0; k <= 3; ++k) {
    const double lead = std::pow(t, k + 1) / (k + 1);
    const double approx = lead * (1.0 - t / ((k + 2.0) * tau));
    EXPECT_NEAR(I[static_cast<std::size_t>(k)], approx, 1e-7 * lead) << "k = " << k;
  }
}

TEST(Hereditary, LinearAndQuadraticDrivers) {
  const double tau = 0.5, t1 = 1.5;
  const Poly linear{0.0, 2.0};          // Y = 2 t, Y' = 2
  const Poly quadratic{0.0, 0.0, 1.0};  // Y = t^2, Y' = 2 t
  for (double t : {0.1, 0.5, 1.0, 1.5}) {
    const double one_minus = -std::expm1(-t / tau);
    EXPECT_NEAR(hereditary(linear, t1, tau, t), 2.0 * tau * one_minus, 1e-14) << "t = " << t;
    EXPECT_NEAR(hereditary(quadratic, t1, tau, t), 2.0 * (tau * t - tau * tau * one_minus), 1e-14)
        << "t = " << t;
  }
  // After the ramp the driver is constant: h decays with exp(-(t - t1)/tau).
  const double h1 = 2.0 * tau * -std::expm1(-t1 / tau);
  for (double t : {1.6, 2.0, 4.0})
    EXPECT_NEAR(hereditary(linear, t1, tau, t), h1 * std::exp(-(t - t1) / tau), 1e-14) << "t = " << t;
  // A constant driver has no history.
  EXPECT_EQ(hereditary({3.0}, t1, tau, 1.0), 0.0);
}

}  // namespace
}  // namespace tmlab::verify::numerics
