// Tests of the closed-form indentation solutions: the elastic formulas, the finite-layer series, and
// the Lee-Radok hereditary integrals against brute-force quadrature.
#include "calibration/closed_forms/indentation.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <functional>

namespace tmlab::closed_forms {
namespace {

// Composite Simpson rule on [a, b] with n (even) intervals: the slow, obviously correct oracle.
double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += (i % 2 == 1 ? 4.0 : 2.0) * f(a + i * h);
  return s * h / 3.0;
}

RelaxationModulus two_term_modulus() {
  RelaxationModulus m;
  m.e_inf = 3000.0;
  m.moduli = {1500.0, 800.0};
  m.taus = {0.4, 5.0};
  return m;
}

TEST(Hertz, ForceAndRadius) {
  // F = 4/3 E/(1-nu^2) sqrt(R) d^{3/2}: E = 3 kPa, nu = 0.45, R = 5 mm, d = 0.5 mm.
  const double f = hertz_force(3000.0, 0.45, 0.005, 0.0005);
  EXPECT_NEAR(f, 4.0 / 3.0 * 3000.0 / (1.0 - 0.2025) * std::sqrt(0.005) * std::pow(0.0005, 1.5), 1e-15);
  EXPECT_DOUBLE_EQ(hertz_contact_radius(0.005, 0.0005), std::sqrt(0.005 * 0.0005));
  EXPECT_EQ(hertz_force(3000.0, 0.45, 0.005, -1e-3), 0.0);
  EXPECT_THROW(hertz_force(-1.0, 0.45, 0.005, 0.001), Error);
  EXPECT_THROW(hertz_force(1.0, 0.6, 0.005, 0.001), Error);
  EXPECT_THROW(hertz_force(1.0, 0.3, 0.0, 0.001), Error);
}

TEST(Sneddon, Force) {
  EXPECT_NEAR(sneddon_force(1e4, 0.3, 0.002, 1e-4), 2.0 * 0.002 * 1e4 * 1e-4 / 0.91, 1e-16);
  EXPECT_EQ(sneddon_force(1e4, 0.3, 0.002, 0.0), 0.0);
}

TEST(FiniteLayer, PublishedCoefficientsAtHalf) {
  // Dimitriadis et al. 2002 quote, for nu = 0.5, 1 + 1.133 chi + 1.283 chi^2 + 0.769 chi^3 + ...
  // (bonded) and 1 + 0.884 chi + 0.781 chi^2 + 0.386 chi^3 + 0.0048 chi^4 (frictionless). The series
  // is a polynomial in chi: recover its coefficients from five values.
  const auto coefficients = [](LayerSupport s) {
    // chi = sqrt(R d)/h with R = h = 1: chi = sqrt(d).
    std::array<double, 5> c{};
    const double x[5] = {0.1, 0.3, 0.5, 0.7, 0.9};
    Eigen::Matrix<double, 5, 5> a;
    Eigen::Matrix<double, 5, 1> y;
    for (int i = 0; i < 5; ++i) {
      for (int j = 0; j < 5; ++j) a(i, j) = std::pow(x[i], j);
      y(i) = finite_layer_factor(0.5, 1.0, x[i] * x[i], 1.0, s);
    }
    const Eigen::Matrix<double, 5, 1> sol = a.fullPivLu().solve(y);
    for (int j = 0; j < 5; ++j) c[static_cast<std::size_t>(j)] = sol(j);
    return c;
  };
  const auto b = coefficients(LayerSupport::Bonded);
  EXPECT_NEAR(b[0], 1.0, 1e-9);
  EXPECT_NEAR(b[1], 1.133, 5e-4);
  EXPECT_NEAR(b[2], 1.283, 5e-4);
  EXPECT_NEAR(b[3], 0.769, 5e-4);
  const auto f = coefficients(LayerSupport::Frictionless);
  EXPECT_NEAR(f[1], 0.884, 5e-4);
  EXPECT_NEAR(f[2], 0.781, 5e-4);
  EXPECT_NEAR(f[3], 0.386, 5e-4);
  EXPECT_NEAR(f[4], 0.0048, 5e-4);
  EXPECT_EQ(finite_layer_factor(0.45, 0.005, 0.0, 0.02, LayerSupport::Bonded), 1.0);
  EXPECT_THROW(finite_layer_factor(0.45, 0.005, 0.004, 0.002, LayerSupport::Bonded), Error);
}

TEST(LeeRadok, ElasticLimitIsHertz) {
  RelaxationModulus m;
  m.e_inf = 5000.0;
  const DepthHistory h = ramp_hold(0.002, 1.0, {0.0, 0.25, 0.5, 1.0, 3.0});
  const std::vector<double> f = lee_radok_sphere(m, 0.45, 0.005, h);
  for (std::size_t k = 0; k < f.size(); ++k) {
    EXPECT_NEAR(f[k], hertz_force(5000.0, 0.45, 0.005, h.d[k]), 1e-15) << k;
  }
}

TEST(LeeRadok, SphereRampHoldMatchesQuadrature) {
  const RelaxationModulus m = two_term_modulus();
  const double nu = 0.45, radius = 0.005, d_max = 0.002, t_ramp = 1.0;
  const double v = d_max / t_ramp, k = 4.0 * std::sqrt(radius) / (3.0 * (1.0 - nu * nu));
  std::vector<double> times;
  for (int i = 0; i <= 40; ++i) times.push_back(0.1 * i);
  const DepthHistory h = ramp_hold(d_max, t_ramp, times);
  const std::vector<double> f = lee_radok_sphere(m, nu, radius, h);
  for (std::size_t s = 1; s < h.t.size(); ++s) {
    const double t = h.t[s];
    // F(t) = K int_0^min(t, t_r) E(t - s) 1.5 v^{3/2} s^{1/2} ds; with s = u^2 the integrand is smooth.
    const double upper = std::sqrt(std::min(t, t_ramp));
    const double oracle =
        k *
        simpson([&](double u) { return 3.0 * std::pow(v, 1.5) * u * u * m.at(t - u * u); }, 0.0, upper, 4000);
    EXPECT_NEAR(f[s], oracle, 1e-11 * oracle) << "t = " << t;
  }
  // During the hold the force relaxes towards the E_inf Hertz force.
  EXPECT_GT(f[10], f[40]);
  EXPECT_GT(f[40], hertz_force(m.e_inf, nu, radius, d_max));
}

TEST(LeeRadok, FastRampGivesInstantaneousThenLongTermHertz) {
  const RelaxationModulus m = two_term_modulus();
  const DepthHistory h = ramp_hold(0.001, 1e-7, {0.0, 1e-7, 200.0});
  const std::vector<double> f = lee_radok_sphere(m, 0.45, 0.005, h);
  EXPECT_NEAR(f[1], hertz_force(m.instantaneous(), 0.45, 0.005, 0.001), 1e-6 * f[1]);
  EXPECT_NEAR(f[2], hertz_force(m.e_inf, 0.45, 0.005, 0.001), 1e-12 * f[2]);
}

TEST(LeeRadok, SplittingASegmentChangesNothing) {
  const RelaxationModulus m = two_term_modulus();
  DepthHistory coarse{{0.0, 2.0}, {-0.0002, 0.0018}};
  DepthHistory fine{{0.0, 0.2, 0.7, 2.0}, {-0.0002, 0.0, 0.0005, 0.0018}};
  const double a = lee_radok_sphere(m, 0.4, 0.004, coarse).back();
  const double b = lee_radok_sphere(m, 0.4, 0.004, fine).back();
  EXPECT_NEAR(a, b, 1e-12 * a);
}

TEST(LeeRadok, PunchMatchesQuadrature) {
  const RelaxationModulus m = two_term_modulus();
  const double nu = 0.3, a = 0.002, d_max = 0.001, t_ramp = 2.0, v = d_max / t_ramp;
  const DepthHistory h = ramp_hold(d_max, t_ramp, {0.0, 0.5, 1.0, 2.0, 4.0, 9.0});
  const std::vector<double> f = lee_radok_punch(m, nu, a, h);
  for (std::size_t s = 1; s < h.t.size(); ++s) {
    const double t = h.t[s];
    const double oracle = 2.0 * a / (1.0 - nu * nu) *
                          simpson([&](double x) { return v * m.at(t - x); }, 0.0, std::min(t, t_ramp), 2000);
    EXPECT_NEAR(f[s], oracle, 1e-11 * oracle) << "t = " << t;
  }
}

TEST(LeeRadok, RefusesUnloadingAndBadHistories) {
  const RelaxationModulus m = two_term_modulus();
  EXPECT_THROW(lee_radok_sphere(m, 0.45, 0.005, DepthHistory{{0.0, 1.0, 2.0}, {0.0, 0.002, 0.001}}), Error);
  EXPECT_THROW(lee_radok_sphere(m, 0.45, 0.005, DepthHistory{{0.0, 0.0}, {0.0, 0.001}}), Error);
  EXPECT_THROW(lee_radok_sphere(m, 0.45, 0.005, DepthHistory{{0.0}, {0.0, 0.001}}), Error);
  RelaxationModulus bad = m;
  bad.taus[1] = 0.0;
  EXPECT_THROW(lee_radok_sphere(bad, 0.45, 0.005, DepthHistory{{0.0, 1.0}, {0.0, 0.001}}), Error);
  EXPECT_THROW(lee_radok_punch(m, 0.45, 0.005, DepthHistory{{0.0, 1.0, 2.0}, {0.0, 0.002, 0.001}}), Error);
}

}  // namespace
}  // namespace tmlab::closed_forms
