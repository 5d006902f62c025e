// Separate bulk and shear relaxation (bulk_shear.hpp) against its equations: with the drained
// Poisson ratio equal to the instantaneous one it is the baseline's Prony operator sample by sample;
// a step of the input relaxes as the analytic rig moduli say (confined M(t) = K(t) + 4/3 G(t),
// unconfined E(t) a single exponential at tau' = tau_b (3 K0 + G0) / (3 K_inf + G0), indentation
// E*(t) from its instantaneous to its long-term value).
#include "calibration/discover/bulk_shear.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace tmlab::discover {
namespace {

struct Moduli {
  double g0, k0, kinf;
};

Moduli moduli(double nu0, double nu_inf) {
  const double g0 = 1.0 / (2.0 * (1.0 + nu0));
  return {g0, 1.0 / (3.0 * (1.0 - 2.0 * nu0)), 2.0 * g0 * (1.0 + nu_inf) / (3.0 * (1.0 - 2.0 * nu_inf))};
}

TEST(BulkShear, EqualPoissonRatiosGiveTheBaselinePronyOperator) {
  const std::vector<double> alpha = {0.4, 0.25}, tau = {0.5, 15.0};
  for (const BulkShearRig rig :
       {BulkShearRig::confined, BulkShearRig::uniaxial_stress, BulkShearRig::indentation}) {
    BulkShearRelaxation r(rig, alpha, tau, 0.49, 0.49, 3.0);
    std::vector<double> h(2, 0.0);
    double y_prev = 0.0;
    for (int i = 0; i < 300; ++i) {
      const double t = 0.2 * i, dt = i ? 0.2 : 0.0;
      const double y = t < 10.0 ? 0.1 * t * t : (t < 40.0 ? 10.0 : std::max(0.0, 10.0 - 0.5 * (t - 40.0)));
      double f = y;
      for (std::size_t j = 0; j < 2; ++j) {
        const double rr = dt / tau[j], e = i ? std::exp(-rr) : 0.0, b = i ? (1.0 - e) / rr : 1.0;
        h[j] = e * h[j] + b * (y - y_prev);
        f += alpha[j] * h[j];
      }
      y_prev = y;
      const double out = r.step(dt, y);
      r.commit();
      EXPECT_NEAR(out, f, 1e-11 * (1.0 + std::abs(f))) << "sample " << i;
    }
  }
}

/// The response to a unit step of the input, sampled at dt, at the times `at`.
std::vector<double> step_response(BulkShearRig rig, double nu0, double nu_inf, double tau_b, double dt,
                                  const std::vector<double>& at) {
  BulkShearRelaxation r(rig, {}, {}, nu0, nu_inf, tau_b);
  std::vector<double> out;
  double t = 0.0;
  double v = r.step(0.0, 1.0);
  r.commit();
  for (const double ta : at) {
    while (t < ta - 0.5 * dt) {
      v = r.step(dt, 1.0);
      r.commit();
      t += dt;
    }
    out.push_back(v);
  }
  return out;
}

TEST(BulkShear, ConfinedStepRelaxesAsKPlusFourThirdsG) {
  const double nu0 = 0.45, nu_inf = 0.2, tau_b = 2.0;
  const Moduli m = moduli(nu0, nu_inf);
  const std::vector<double> at = {0.0, 1.0, 2.0, 5.0, 30.0};
  const auto out = step_response(BulkShearRig::confined, nu0, nu_inf, tau_b, 0.01, at);
  for (std::size_t i = 0; i < at.size(); ++i) {
    const double k = m.kinf + (m.k0 - m.kinf) * std::exp(-at[i] / tau_b);
    EXPECT_NEAR(out[i], (k + 4.0 / 3.0 * m.g0) / (m.k0 + 4.0 / 3.0 * m.g0), 1e-9) << at[i];
  }
}

TEST(BulkShear, UnconfinedStepIsOneExponentialAtTheShiftedTime) {
  const double nu0 = 0.45, nu_inf = 0.2, tau_b = 2.0;
  const Moduli m = moduli(nu0, nu_inf);
  const double e0 = 9.0 * m.k0 * m.g0 / (3.0 * m.k0 + m.g0),
               einf = 9.0 * m.kinf * m.g0 / (3.0 * m.kinf + m.g0);
  const double tau_shift = tau_b * (3.0 * m.k0 + m.g0) / (3.0 * m.kinf + m.g0);
  const std::vector<double> at = {0.0, 1.0, 3.0, 8.0, 60.0};
  const auto out = step_response(BulkShearRig::uniaxial_stress, nu0, nu_inf, tau_b, 0.002, at);
  for (std::size_t i = 0; i < at.size(); ++i) {
    const double e = einf + (e0 - einf) * std::exp(-at[i] / tau_shift);
    EXPECT_NEAR(out[i], e / e0, 2e-5) << at[i];
  }
  // The relaxation is visible (nu 0.45 -> 0.2 relaxes E by more than 10 %) and smaller than the
  // confined one (there K dominates M).
  EXPECT_LT(out.back(), 0.9);
  const auto conf = step_response(BulkShearRig::confined, nu0, nu_inf, tau_b, 0.01, {60.0});
  EXPECT_LT(conf.back(), out.back());
}

TEST(BulkShear, IndentationStepGoesFromInstantaneousToDrainedReducedModulus) {
  const double nu0 = 0.49, nu_inf = 0.3, tau_b = 1.0;
  const auto out = step_response(BulkShearRig::indentation, nu0, nu_inf, tau_b, 0.01, {0.0, 400.0});
  EXPECT_NEAR(out[0], 1.0, 1e-12);
  // (the slow pole: tau_b (3 K0 + 4 G0) / (3 K_inf + 4 G0) = 14.6 s; 400 s is 27 of them)
  // E* = 2 G / (1 - nu): the drained over the instantaneous reduced modulus is (1 - nu0) / (1 - nu_inf).
  EXPECT_NEAR(out[1], (1.0 - nu0) / (1.0 - nu_inf), 1e-6);
}

}  // namespace
}  // namespace tmlab::discover
