// St Venant-Kirchhoff material: parameter checks, S = dW/dE, dS = C : dE, Lame round trip.
#include "core/base/error.hpp"
#include "tensormass/materials/stvk_material.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>

namespace tmlab::tm {
namespace {

Mat3 random_sym(std::mt19937& rng, double s) {
  std::uniform_real_distribution<double> d(-s, s);
  Mat3 A;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) A(i, j) = d(rng);
  return 0.5 * (A + A.transpose());
}

TEST(StVK, LameFromYoungPoissonCorrectedMu) {
  const auto m = StVenantKirchhoff::from_young_poisson(3000.0, 0.45);
  EXPECT_NEAR(m.mu, 3000.0 / (2.0 * 1.45), 1e-12);  // docs/theory/seed-errata.md, eq. 5
  EXPECT_NEAR(m.lambda, 3000.0 * 0.45 / (1.45 * 0.1), 1e-9);
  EXPECT_NEAR(m.young(), 3000.0, 1e-9);
  EXPECT_NEAR(m.poisson(), 0.45, 1e-14);
}

TEST(StVK, RejectsBadParametersNamingThem) {
  auto message = [](double E, double nu) {
    try {
      StVenantKirchhoff::from_young_poisson(E, nu);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(0.0, 0.3).find("Young's modulus E"), std::string::npos);
  EXPECT_NE(message(-5.0, 0.3).find("-5"), std::string::npos);
  EXPECT_NE(message(1.0, 0.5).find("Poisson's ratio nu"), std::string::npos);
  EXPECT_NE(message(1.0, -1.0).find("nu = -1"), std::string::npos);
  EXPECT_NE(message(1.0, 0.7).find("0.7"), std::string::npos);
  EXPECT_NO_THROW(StVenantKirchhoff::from_young_poisson(1.0, -0.5));
  EXPECT_NO_THROW(StVenantKirchhoff::from_young_poisson(1.0, 0.499));
}

TEST(StVK, StressIsEnergyGradientAndTangentIsStressDerivative) {
  std::mt19937 rng(7);
  const auto m = StVenantKirchhoff::from_young_poisson(2.0, 0.3);
  for (int trial = 0; trial < 5; ++trial) {
    const Mat3 E = random_sym(rng, 0.3), dE = random_sym(rng, 1.0);
    const double h = 1e-5;
    // dW/dE : dE by central difference (W quadratic: exact up to round-off)
    const double fd = (m.energy_density(E + h * dE) - m.energy_density(E - h * dE)) / (2 * h);
    EXPECT_NEAR(fd, m.pk2_stress(E).cwiseProduct(dE).sum(), 1e-9);
    const Mat3 dS_fd = (m.pk2_stress(E + h * dE) - m.pk2_stress(E - h * dE)) / (2 * h);
    EXPECT_LT((dS_fd - m.tangent(dE)).norm(), 1e-9 * m.tangent(dE).norm());
  }
}

}  // namespace
}  // namespace tmlab::tm
