// Veronda-Westmann: derivatives by finite differences, small-strain limit, objectivity, parameter
// checks, and the closed-form simple-shear stress.
#include "core/base/error.hpp"
#include "tensormass/materials/tests/law_checks.hpp"
#include "tensormass/materials/veronda_westmann.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm {
namespace {

using namespace law_testing;

TEST(VerondaWestmann, StressAndTangentAreDerivatives) {
  check_derivatives(VerondaWestmann(200.0, 5.0, 20000.0), 1000.0, 41);
  check_derivatives(VerondaWestmann(1.0, 0.5, 3.0), 0.5, 42);
}

TEST(VerondaWestmann, SmallStrainLimitIsLinearElasticity) {
  const double E = 3000.0, nu = 0.45, mu = E / (2 * (1 + nu)), kappa = E / (3 * (1 - 2 * nu));
  check_small_strain(VerondaWestmann(mu / 4.0, 4.0, kappa), E, nu);  // mu = c1 c2
}

TEST(VerondaWestmann, ObjectiveAndIsotropic) {
  check_objectivity_and_isotropy(VerondaWestmann(0.5, 2.0, 5.0), 43);
}

TEST(VerondaWestmann, SimpleShearClosedForm) {
  // J = 1, I1b = I2b = 3 + g^2: sigma_12 = 2 (Psi_1 + Psi_2) g = 2 c1 c2 (e^{c2 g^2} - 1/2) g.
  const double c1 = 0.5, c2 = 2.0;
  const VerondaWestmann m(c1, c2, 5.0);
  for (double g : {0.1, 0.5, 1.0}) {
    Mat3 F = Mat3::Identity();
    F(0, 1) = g;
    const Mat3 sigma = F * m.pk2_stress(green_strain(F)) * F.transpose();
    const double expect = 2 * c1 * c2 * (std::exp(c2 * g * g) - 0.5) * g;
    EXPECT_NEAR(sigma(0, 1), expect, 1e-12 * expect);
  }
}

TEST(VerondaWestmann, RejectsBadParametersNamingThem) {
  auto msg = [](double a, double b, double k) {
    try {
      VerondaWestmann(a, b, k);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(msg(0.0, 1.0, 1.0).find("c1 = 0"), std::string::npos);
  EXPECT_NE(msg(1.0, -1.0, 1.0).find("c2 = -1"), std::string::npos);
  EXPECT_NE(msg(1.0, 1.0, 0.0).find("kappa"), std::string::npos);
}

}  // namespace
}  // namespace tmlab::tm
