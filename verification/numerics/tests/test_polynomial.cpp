// Polynomial arithmetic against products, sums and derivatives worked by hand, and the C1 ramp
// against its defining values (0 and 1 at the ends, zero slope there, 1/2 in the middle).
#include "verification/numerics/polynomial.hpp"

#include <gtest/gtest.h>

namespace tmlab::verify::numerics {
namespace {

TEST(Polynomial, ProductOfBinomials) {
  EXPECT_EQ(poly_mul({1.0, 1.0}, {1.0, 1.0}), (Poly{1.0, 2.0, 1.0}));
  EXPECT_EQ(poly_mul({1.0, -2.0, 3.0}, {0.0, 4.0}), (Poly{0.0, 4.0, -8.0, 12.0}));
  EXPECT_EQ(poly_mul({2.0}, {1.0, 3.0}), (Poly{2.0, 6.0}));
}

TEST(Polynomial, ScaledSumTakesTheLongerLength) {
  EXPECT_EQ(poly_add({1.0, 2.0}, {0.0, 0.0, 3.0}, 2.0), (Poly{1.0, 2.0, 6.0}));
  EXPECT_EQ(poly_add({1.0, 2.0, 5.0}, {4.0}), (Poly{5.0, 2.0, 5.0}));
  EXPECT_EQ(poly_add({1.0, 2.0}, {1.0, 2.0}, -1.0), (Poly{0.0, 0.0}));
}

TEST(Polynomial, Derivative) {
  EXPECT_EQ(poly_deriv({5.0, 3.0, 0.0, 2.0}), (Poly{3.0, 0.0, 6.0}));
  EXPECT_EQ(poly_deriv({7.0}), (Poly{0.0}));
}

TEST(Polynomial, HornerEvaluation) {
  const Poly p{1.0, -3.0, 2.0};  // (1 - t)(1 - 2t)
  EXPECT_EQ(poly_eval(p, 0.5), 0.0);
  EXPECT_EQ(poly_eval(p, 1.0), 0.0);
  EXPECT_EQ(poly_eval(p, 2.0), 3.0);
  EXPECT_EQ(poly_eval(p, 0.0), 1.0);
  EXPECT_EQ(poly_eval({}, 4.0), 0.0);
}

TEST(Polynomial, SmoothRampHitsItsEndsWithZeroSlope) {
  const double t1 = 2.5;
  const Poly f = smooth_ramp_poly(t1);
  const Poly df = poly_deriv(f);
  EXPECT_DOUBLE_EQ(poly_eval(f, 0.0), 0.0);
  EXPECT_NEAR(poly_eval(f, t1), 1.0, 1e-15);
  EXPECT_NEAR(poly_eval(f, 0.5 * t1), 0.5, 1e-15);
  EXPECT_NEAR(poly_eval(df, 0.0), 0.0, 1e-15);
  EXPECT_NEAR(poly_eval(df, t1), 0.0, 1e-15);
  // 3 s^2 - 2 s^3 at s = 0.25: 3/16 - 2/64 = 5/32.
  EXPECT_NEAR(poly_eval(f, 0.25 * t1), 5.0 / 32.0, 1e-15);
}

}  // namespace
}  // namespace tmlab::verify::numerics
