// The simplex rules against the exact integrals of barycentric monomials:
//   tet:      int l0^a l1^b l2^c l3^d dV / V = a! b! c! d! 3! / (a+b+c+d+3)!
//   triangle: int l0^a l1^b l2^c dA / A     = a! b! c! 2! / (a+b+c+2)!
// for every monomial up to the rule's degree (2q - 3 for the collapsed tet rule, 5 for Dunavant's).
#include "verification/numerics/quadrature.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::verify::numerics {
namespace {

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

TEST(DuffyRule, PointsAndWeights) {
  for (int q = 2; q <= 6; ++q) {
    const TetRule r = duffy_rule(q);
    ASSERT_EQ(r.weight.size(), static_cast<std::size_t>(q * q * q));
    ASSERT_EQ(r.bary.size(), r.weight.size());
    double sum = 0.0;
    for (std::size_t g = 0; g < r.weight.size(); ++g) {
      EXPECT_GT(r.weight[g], 0.0);
      double bsum = 0.0;
      for (double b : r.bary[g]) {
        EXPECT_GT(b, 0.0);
        EXPECT_LT(b, 1.0);
        bsum += b;
      }
      EXPECT_NEAR(bsum, 1.0, 1e-15);
      sum += r.weight[g];
    }
    EXPECT_NEAR(sum, 1.0, 1e-14) << "q = " << q;
  }
}

TEST(DuffyRule, ExactForMonomialsUpToDegree2qMinus3) {
  for (int q = 2; q <= 5; ++q) {
    const TetRule r = duffy_rule(q);
    const int degree = 2 * q - 3;
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b)
        for (int c = 0; a + b + c <= degree; ++c)
          for (int d = 0; a + b + c + d <= degree; ++d) {
            const double exact = factorial(a) * factorial(b) * factorial(c) * factorial(d) * 6.0 /
                                 factorial(a + b + c + d + 3);
            double sum = 0.0;
            for (std::size_t g = 0; g < r.weight.size(); ++g) {
              const auto& l = r.bary[g];
              sum +=
                  r.weight[g] * std::pow(l[0], a) * std::pow(l[1], b) * std::pow(l[2], c) * std::pow(l[3], d);
            }
            EXPECT_NEAR(sum, exact, 1e-14) << "q = " << q << ", exponents " << a << b << c << d;
          }
  }
}

TEST(DuffyRule, NotExactBeyondItsDegree) {
  // q = 2 integrates degree 1 exactly, not l1^4 (exact 4! 3! / 7! = 1/35).
  const TetRule r = duffy_rule(2);
  double sum = 0.0;
  for (std::size_t g = 0; g < r.weight.size(); ++g) sum += r.weight[g] * std::pow(r.bary[g][1], 4);
  EXPECT_GT(std::abs(sum - 1.0 / 35.0), 1e-4);
}

TEST(DunavantRule, ExactForMonomialsUpToDegree5) {
  double wsum = 0.0;
  for (int q = 0; q < 7; ++q) {
    wsum += kTriW[q];
    EXPECT_NEAR(kTriB[q][0] + kTriB[q][1] + kTriB[q][2], 1.0, 1e-15);
  }
  EXPECT_NEAR(wsum, 1.0, 1e-15);
  for (int a = 0; a <= 5; ++a)
    for (int b = 0; a + b <= 5; ++b)
      for (int c = 0; a + b + c <= 5; ++c) {
        const double exact = factorial(a) * factorial(b) * factorial(c) * 2.0 / factorial(a + b + c + 2);
        double sum = 0.0;
        for (int q = 0; q < 7; ++q)
          sum += kTriW[q] * std::pow(kTriB[q][0], a) * std::pow(kTriB[q][1], b) * std::pow(kTriB[q][2], c);
        EXPECT_NEAR(sum, exact, 1e-14) << "exponents " << a << b << c;
      }
}

}  // namespace
}  // namespace tmlab::verify::numerics
