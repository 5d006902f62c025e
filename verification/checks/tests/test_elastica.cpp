// The elastica tip (quadrature of the first integral) against an independent oracle: shooting on
// the boundary-value problem theta'' = -k cos(theta), theta(0) = 0, theta'(1) = 0 with RK4, plus the
// small-load limit of linear beam theory and Bisshopp & Drucker's published table (1945).
#include "core/base/error.hpp"
#include "verification/checks/elastica.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::verify {
namespace {

/// Integrates (theta, theta', x, y) over s in [0, 1] from theta'(0) = m by RK4 with n steps.
struct Shot {
  double theta, dtheta, x, y;
};
Shot shoot(double k, double m, int n) {
  auto f = [k](const Shot& s) {
    return Shot{s.dtheta, -k * std::cos(s.theta), std::cos(s.theta), std::sin(s.theta)};
  };
  auto axpy = [](const Shot& a, double h, const Shot& b) {
    return Shot{a.theta + h * b.theta, a.dtheta + h * b.dtheta, a.x + h * b.x, a.y + h * b.y};
  };
  Shot s{0.0, m, 0.0, 0.0};
  const double h = 1.0 / n;
  for (int i = 0; i < n; ++i) {
    const Shot k1 = f(s), k2 = f(axpy(s, 0.5 * h, k1)), k3 = f(axpy(s, 0.5 * h, k2)), k4 = f(axpy(s, h, k3));
    s = Shot{s.theta + h / 6 * (k1.theta + 2 * k2.theta + 2 * k3.theta + k4.theta),
             s.dtheta + h / 6 * (k1.dtheta + 2 * k2.dtheta + 2 * k3.dtheta + k4.dtheta),
             s.x + h / 6 * (k1.x + 2 * k2.x + 2 * k3.x + k4.x),
             s.y + h / 6 * (k1.y + 2 * k2.y + 2 * k3.y + k4.y)};
  }
  return s;
}

/// theta'(0) in (0, k] such that theta'(1) = 0 (bisection: the tip curvature decreases with m).
Shot shooting_solution(double k) {
  double lo = 0.0, hi = k;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (shoot(k, mid, 4000).dtheta > 0.0 ? hi : lo) = mid;
  }
  return shoot(k, 0.5 * (lo + hi), 4000);
}

TEST(Elastica, AgreesWithShootingOnTheBoundaryValueProblem) {
  for (double k : {0.5, 2.0, 10.0, 30.0}) {
    const ElasticaTip tip = elastica_cantilever_tip(k);
    const Shot s = shooting_solution(k);
    EXPECT_NEAR(tip.theta0, s.theta, 1e-8) << "k = " << k;
    EXPECT_NEAR(tip.transverse, s.y, 1e-8) << "k = " << k;
    EXPECT_NEAR(tip.axial, s.x, 1e-8) << "k = " << k;
  }
}

TEST(Elastica, SmallLoadIsLinearBeamTheory) {
  // Euler-Bernoulli: tip deflection P L^3 / (3 E I) = k L / 3, rotation k / 2; shortening O(k^2).
  const double k = 1e-3;
  const ElasticaTip tip = elastica_cantilever_tip(k);
  EXPECT_NEAR(tip.transverse, k / 3.0, 1e-6 * k);
  EXPECT_NEAR(tip.theta0, k / 2.0, 1e-6 * k);
  EXPECT_NEAR(1.0 - tip.axial, 0.0, k * k);
}

TEST(Elastica, PublishedValues) {
  // Bisshopp & Drucker, Q. Appl. Math. 3 (1945) 272, Table 1: P L^2/EI = 1: y/L = 0.30172,
  // shortening 0.05643; P L^2/EI = 10: y/L = 0.81061, shortening 0.55500 (4-5 digits printed).
  const ElasticaTip one = elastica_cantilever_tip(1.0), ten = elastica_cantilever_tip(10.0);
  EXPECT_NEAR(one.transverse, 0.30172, 2e-5);
  EXPECT_NEAR(1.0 - one.axial, 0.05643, 2e-5);
  EXPECT_NEAR(ten.transverse, 0.81061, 2e-5);
  EXPECT_NEAR(1.0 - ten.axial, 0.55500, 2e-5);
}

TEST(Elastica, LoadParameterOutOfRangeIsRefused) {
  EXPECT_THROW(elastica_cantilever_tip(0.0), Error);
  EXPECT_THROW(elastica_cantilever_tip(-1.0), Error);
  EXPECT_THROW(elastica_cantilever_tip(std::nan("")), Error);
}

}  // namespace
}  // namespace tmlab::verify
