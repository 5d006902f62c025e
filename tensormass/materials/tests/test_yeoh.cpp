// Yeoh: derivatives by finite differences, small-strain limit, objectivity, parameter checks,
// the closed-form simple-shear stress, and c20 = c30 = 0 is Mooney-Rivlin with c01 = 0.
#include "core/base/error.hpp"
#include "tensormass/materials/mooney_rivlin.hpp"
#include "tensormass/materials/tests/law_checks.hpp"
#include "tensormass/materials/yeoh.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm {
namespace {

using namespace law_testing;

TEST(Yeoh, StressAndTangentAreDerivatives) {
  check_derivatives(Yeoh(500.0, 1000.0, 250.0, 20000.0), 1000.0, 31);
  check_derivatives(Yeoh(1.0, -0.1, 0.05, 10.0), 1.0, 32);
}

TEST(Yeoh, SmallStrainLimitIsLinearElasticity) {
  const double E = 3000.0, nu = 0.3, mu = E / (2 * (1 + nu)), kappa = E / (3 * (1 - 2 * nu));
  check_small_strain(Yeoh(mu / 2, 5 * mu, 3 * mu, kappa), E, nu);  // c20, c30 do not enter the limit
}

TEST(Yeoh, ObjectiveAndIsotropic) { check_objectivity_and_isotropy(Yeoh(0.5, 0.3, 0.1, 5.0), 33); }

TEST(Yeoh, SimpleShearClosedForm) {
  // J = 1, x = g^2: sigma_12 = 2 (c10 + 2 c20 x + 3 c30 x^2) g (the reference's test, same law).
  const Yeoh m(0.5, 0.3, 0.1, 5.0);
  for (double g : {0.1, 0.5, 1.5}) {
    Mat3 F = Mat3::Identity();
    F(0, 1) = g;
    const Mat3 sigma = F * m.pk2_stress(green_strain(F)) * F.transpose();
    const double x = g * g;
    EXPECT_NEAR(sigma(0, 1), 2 * (0.5 + 0.6 * x + 0.3 * x * x) * g, 1e-12 * g);
  }
}

TEST(Yeoh, FirstOrderIsDecoupledNeoHookean) {
  check_same_law(Yeoh(0.8, 0, 0, 7.0), MooneyRivlin(0.8, 0, 7.0), 34);
}

TEST(Yeoh, RejectsBadParametersNamingThem) {
  EXPECT_THROW(Yeoh(0.0, 1, 1, 1), Error);
  try {
    Yeoh(1.0, NAN, 0, 1);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("c20"), std::string::npos);
  }
  try {
    Yeoh(1.0, 0, 0, -3);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("kappa = -3"), std::string::npos);
  }
}

}  // namespace
}  // namespace tmlab::tm
