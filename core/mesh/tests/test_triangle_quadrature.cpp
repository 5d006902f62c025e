// The 6-point triangle rule integrates every monomial l1^i l2^j of degree <= 4 exactly (the exact
// value i! j! 2 / (i + j + 2)! of the area-normalised integral) and not degree 5 in general; the 6-node
// triangle's shape functions are a partition of unity, interpolate their nodes, and integrate to 0
// (vertices) and 1/3 (midside nodes) of the area: the consistent load of a uniform pressure.
#include "core/mesh/triangle_quadrature.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab {
namespace {

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

double rule(int i, int j) {
  double s = 0.0;
  for (const TrianglePoint& p : triangle_rule_degree4())
    s += p.weight * std::pow(p.l1, i) * std::pow(p.l2, j);
  return s;
}

TEST(TriangleQuadrature, ExactToDegreeFour) {
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; i + j <= 4; ++j) {
      const double exact = 2.0 * factorial(i) * factorial(j) / factorial(i + j + 2);
      EXPECT_NEAR(rule(i, j), exact, 1e-15) << i << " " << j;
    }
  // Degree 5 is beyond it (l1^5: exact 2 * 5! / 7! = 1/21).
  EXPECT_GT(std::abs(rule(5, 0) - 1.0 / 21.0), 1e-6);
}

TEST(TriangleQuadrature, Tri6ShapesAndConsistentLoad) {
  const double nodes[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
  for (int k = 0; k < 6; ++k) {
    const auto n = tri6_shape(nodes[k][0], nodes[k][1]);
    for (int a = 0; a < 6; ++a) EXPECT_NEAR(n[static_cast<std::size_t>(a)], a == k ? 1.0 : 0.0, 1e-15);
  }
  std::array<double, 6> integral{};
  for (const TrianglePoint& p : triangle_rule_degree4()) {
    const auto n = tri6_shape(p.l1, p.l2);
    double sum = 0.0;
    for (int a = 0; a < 6; ++a) {
      integral[static_cast<std::size_t>(a)] += p.weight * n[static_cast<std::size_t>(a)];
      sum += n[static_cast<std::size_t>(a)];
    }
    EXPECT_NEAR(sum, 1.0, 1e-15);
  }
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(integral[static_cast<std::size_t>(a)], 0.0, 1e-15);
  for (int a = 3; a < 6; ++a) EXPECT_NEAR(integral[static_cast<std::size_t>(a)], 1.0 / 3.0, 1e-15);
}

TEST(TriangleQuadrature, Tri6ShapeGradientsByFiniteDifferences) {
  const double l1 = 0.23, l2 = 0.41, h = 1e-6;
  const auto g = tri6_shape_gradient(l1, l2);
  const auto p1 = tri6_shape(l1 + h, l2), m1 = tri6_shape(l1 - h, l2);
  const auto p2 = tri6_shape(l1, l2 + h), m2 = tri6_shape(l1, l2 - h);
  for (std::size_t a = 0; a < 6; ++a) {
    EXPECT_NEAR(g[a][0], (p1[a] - m1[a]) / (2 * h), 1e-8) << a;
    EXPECT_NEAR(g[a][1], (p2[a] - m2[a]) / (2 * h), 1e-8) << a;
  }
}

}  // namespace
}  // namespace tmlab
