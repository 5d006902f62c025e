// Mooney-Rivlin: derivatives by finite differences, small-strain limit, objectivity, parameter
// checks, and the closed-form simple-shear stress.
#include "core/base/error.hpp"
#include "tensormass/materials/mooney_rivlin.hpp"
#include "tensormass/materials/tests/law_checks.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm {
namespace {

using namespace law_testing;

MooneyRivlin from_young_poisson(double young, double nu, double c01_share) {
  const double mu = young / (2 * (1 + nu)), kappa = young / (3 * (1 - 2 * nu));
  return {(1 - c01_share) * mu / 2, c01_share * mu / 2, kappa};
}

TEST(MooneyRivlin, StressAndTangentAreDerivatives) {
  check_derivatives(from_young_poisson(3000.0, 0.45, 0.4), 1000.0, 21);
  check_derivatives(MooneyRivlin(1.0, -0.2, 30.0), 1.0, 22);  // negative c01 (fits often have one)
}

TEST(MooneyRivlin, SmallStrainLimitIsLinearElasticity) {
  check_small_strain(from_young_poisson(3000.0, 0.3, 0.3), 3000.0, 0.3);
  check_small_strain(from_young_poisson(10.0, 0.499, 0.7), 10.0, 0.499);
}

TEST(MooneyRivlin, ObjectiveAndIsotropic) { check_objectivity_and_isotropy(MooneyRivlin(0.7, 0.2, 5.0), 23); }

TEST(MooneyRivlin, SimpleShearClosedForm) {
  // F = I + g e1 (x) e2 (J = 1, I1 = I2 = 3 + g^2): Cauchy shear sigma_12 = 2 (c10 + c01) g.
  const MooneyRivlin m(0.7, 0.2, 5.0);
  for (double g : {0.1, 1.0, 2.5}) {
    Mat3 F = Mat3::Identity();
    F(0, 1) = g;
    const Mat3 sigma = F * m.pk2_stress(green_strain(F)) * F.transpose();
    EXPECT_NEAR(sigma(0, 1), 2 * (0.7 + 0.2) * g, 1e-12 * g);
  }
}

TEST(MooneyRivlin, RejectsBadParametersNamingThem) {
  auto msg = [](double a, double b, double k) {
    try {
      MooneyRivlin(a, b, k);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(msg(0.1, -0.2, 1.0).find("c10 + c01 = -0.1"), std::string::npos);
  EXPECT_NE(msg(0.1, 0.2, 0.0).find("kappa = 0"), std::string::npos);
  EXPECT_NE(msg(INFINITY, 0.2, 1.0).find("c10"), std::string::npos);
}

}  // namespace
}  // namespace tmlab::tm
