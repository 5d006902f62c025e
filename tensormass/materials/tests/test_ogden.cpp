// Ogden (N terms): derivatives by finite differences (including equal and nearly equal principal
// stretches), small-strain limit, objectivity and isotropy, the reduction to Mooney-Rivlin
// (alpha = 2, -2), the divided difference, and the stability check.
#include "core/base/error.hpp"
#include "tensormass/materials/mooney_rivlin.hpp"
#include "tensormass/materials/ogden.hpp"
#include "tensormass/materials/tests/law_checks.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm {
namespace {

using namespace law_testing;

// Ogden's three-term fit to Treloar's rubber data (kPa), with a bulk modulus.
Ogden treloar() { return Ogden({630.0, 1.2, -10.0}, {1.3, 5.0, -2.0}, 1e5); }

TEST(Ogden, StressAndTangentAreDerivatives) {
  check_derivatives(treloar(), 400.0, 51);
  check_derivatives(Ogden({1.0}, {9.0}, 20.0), 4.5, 52);             // one strongly stiffening term
  check_derivatives(Ogden({2.0, -0.5}, {0.5, -3.5}, 3.0), 1.0, 53);  // non-integer, negative alpha
}

TEST(Ogden, SmallStrainLimitIsLinearElasticity) {
  const double E = 3000.0, nu = 0.45, mu = E / (2 * (1 + nu)), kappa = E / (3 * (1 - 2 * nu));
  // 1/2 sum mu_p alpha_p = mu: terms (alpha 4, share 0.7) and (alpha -2, share 0.3)
  check_small_strain(Ogden({0.7 * mu / 2, -0.3 * mu}, {4.0, -2.0}, kappa), E, nu);
}

TEST(Ogden, ObjectiveAndIsotropic) { check_objectivity_and_isotropy(treloar(), 54); }

TEST(Ogden, AlphaTwoAndMinusTwoIsMooneyRivlin) {
  // lb1^2 + lb2^2 + lb3^2 = I1b and lb1^-2 + lb2^-2 + lb3^-2 = I2b (lb1 lb2 lb3 = 1), so
  // mu = [2 c10, -2 c01], alpha = [2, -2] is Mooney-Rivlin, at every deformation including the
  // equal-stretch ones where the eigenvectors are not unique.
  const double c10 = 0.7, c01 = 0.25, kappa = 6.0;
  check_same_law(Ogden({2 * c10, -2 * c01}, {2.0, -2.0}, kappa), MooneyRivlin(c10, c01, kappa), 55);
}

TEST(Ogden, EqualStretchLimitIsContinuous) {
  // The tangent at exactly equal stretches and at stretches 1e-7 apart agree to O(1e-7).
  const Ogden m = treloar();
  const Mat3 E0 = green_strain(Eigen::Vector3d(0.8, 0.8, 1.3).asDiagonal().toDenseMatrix());
  const Mat3 E1 = green_strain(Eigen::Vector3d(0.8, 0.8 + 1e-7, 1.3).asDiagonal().toDenseMatrix());
  const Mat6 D0 = m.tangent_matrix(E0), D1 = m.tangent_matrix(E1);
  EXPECT_LE((D0 - D1).norm(), 1e-5 * D0.norm());
  EXPECT_GT((D0 - D1).norm(), 0.0);
}

TEST(Ogden, PowerDividedDifferenceIsAccurate) {
  for (double k : {-2.0, -0.35, 0.5, 3.0}) {
    EXPECT_DOUBLE_EQ(Ogden::power_divided_difference(k, 2.0, 2.0), k * std::pow(2.0, k - 1));
    EXPECT_NEAR(Ogden::power_divided_difference(k, 2.0, 3.0),
                (std::pow(2.0, k) - std::pow(3.0, k)) / (2.0 - 3.0), 1e-14 * std::abs(k));
    // nearly equal: the naive quotient loses ~8 digits; the expm1 form keeps them. Reference by
    // Taylor series: DD = k a^{k-1} (1 + (k-1)/2 d/a + (k-1)(k-2)/6 (d/a)^2), d = b - a.
    const double a = 2.0, d = 1e-9, b = a + d;
    const double ref =
        k * std::pow(a, k - 1) * (1 + (k - 1) / 2 * d / a + (k - 1) * (k - 2) / 6 * (d / a) * (d / a));
    EXPECT_NEAR(Ogden::power_divided_difference(k, a, b), ref, 1e-14 * std::abs(ref));
  }
}

std::string message(std::vector<double> mu, std::vector<double> alpha, double kappa) {
  try {
    Ogden(std::move(mu), std::move(alpha), kappa);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

TEST(Ogden, RejectsUnstableOrMalformedParameters) {
  EXPECT_NE(message({1.0, -1.0}, {2.0, 2.0}, 1.0).find("sum_p mu_p alpha_p > 0"), std::string::npos);
  EXPECT_NE(message({-1.0}, {2.0}, 1.0).find("got -2"), std::string::npos);
  EXPECT_NE(message({1.0}, {0.0}, 1.0).find("alpha[0]"), std::string::npos);
  EXPECT_NE(message({1.0, 2.0}, {1.0}, 1.0).find("same number of terms"), std::string::npos);
  EXPECT_NE(message({}, {}, 1.0).find("at least one term"), std::string::npos);
  EXPECT_NE(message({1.0}, {2.0}, -1.0).find("kappa"), std::string::npos);
  EXPECT_NE(message({1.0, NAN}, {2.0, 1.0}, 1.0).find("mu[1]"), std::string::npos);
  EXPECT_TRUE(message({-1.0}, {-2.0}, 1.0).empty());  // mu alpha > 0 with both negative: stable
}

}  // namespace
}  // namespace tmlab::tm
