// Compressible neo-Hookean: derivatives by finite differences, small-strain limit, objectivity,
// parameter checks, and the closed-form stress of uniaxial stretch.
#include "core/base/error.hpp"
#include "tensormass/materials/neo_hookean.hpp"
#include "tensormass/materials/tests/law_checks.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm {
namespace {

using namespace law_testing;

TEST(NeoHookean, StressAndTangentAreDerivatives) {
  const auto m = NeoHookean::from_young_poisson(3000.0, 0.45);
  check_derivatives(m, m.mu(), 11);
}

TEST(NeoHookean, SmallStrainLimitIsLinearElasticity) {
  check_small_strain(NeoHookean::from_young_poisson(3000.0, 0.3), 3000.0, 0.3);
  check_small_strain(NeoHookean::from_young_poisson(50.0, 0.49), 50.0, 0.49);
}

TEST(NeoHookean, ObjectiveAndIsotropic) { check_objectivity_and_isotropy(NeoHookean(2.0, 1.0), 12); }

TEST(NeoHookean, UniaxialStretchClosedForm) {
  // F = diag(s, 1, 1): C = diag(s^2, 1, 1), ln J = ln s, S_11 = mu (1 - 1/s^2) + lambda ln s / s^2.
  const NeoHookean m(4.0, 1.5);
  for (double s : {0.3, 0.8, 1.7}) {
    const Mat3 F = Eigen::Vector3d(s, 1, 1).asDiagonal().toDenseMatrix();
    const Mat3 S = m.pk2_stress(green_strain(F));
    EXPECT_NEAR(S(0, 0), 1.5 * (1 - 1 / (s * s)) + 4.0 * std::log(s) / (s * s),
                1e-13 * (1 + std::abs(S(0, 0))));
    EXPECT_NEAR(S(1, 1), 4.0 * std::log(s), 1e-13 * 4.0);
  }
}

TEST(NeoHookean, EnergyGrowsWithoutBoundUnderCompression) {
  // What St VK cannot do (its energy peaks and softens under compression): W -> infinity as J -> 0.
  const NeoHookean m = NeoHookean::from_young_poisson(1.0, 0.3);
  double prev = 0.0;
  for (double s : {0.5, 0.2, 0.1, 0.01, 1e-4}) {
    const double w = m.energy_density(green_strain(Eigen::Vector3d(s, 1, 1).asDiagonal().toDenseMatrix()));
    EXPECT_GT(w, prev);
    prev = w;
  }
  EXPECT_GT(prev, 10.0);
}

TEST(NeoHookean, RejectsBadParametersNamingThem) {
  auto msg = [](double l, double mu) {
    try {
      NeoHookean(l, mu);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(msg(1.0, 0.0).find("shear modulus"), std::string::npos);
  EXPECT_NE(msg(1.0, -2.0).find("mu = -2"), std::string::npos);
  EXPECT_NE(msg(-1.0, 1.0).find("lambda + 2 mu/3"), std::string::npos);
  EXPECT_NE(msg(NAN, 1.0).find("lambda"), std::string::npos);
  EXPECT_NO_THROW(NeoHookean(-0.5, 1.0));  // negative lambda, positive bulk modulus: allowed
  EXPECT_THROW(NeoHookean::from_young_poisson(1.0, 0.5), Error);
}

}  // namespace
}  // namespace tmlab::tm
