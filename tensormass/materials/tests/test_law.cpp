// The Law variant: it forwards to each law unchanged, adapts St Venant-Kirchhoff (whose tangent
// takes no E) and gives its 6x6 tangent, and names each law as the factory does.
#include "tensormass/materials/law.hpp"
#include "tensormass/materials/tests/law_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace tmlab::tm {
namespace {

using namespace law_testing;

TEST(Law, StVenantKirchhoffThroughTheVariant) {
  const auto m = StVenantKirchhoff::from_young_poisson(3000.0, 0.45);
  const Law law(m);
  EXPECT_EQ(law.name(), "stvk");
  EXPECT_TRUE(law.is_stvk());
  std::mt19937 rng(61);
  for (const auto& d : deformations(rng)) {
    const Mat3 E = green_strain(d.F), dE = random_sym(rng, 1.0);
    // (not bit-equal: the compiler may contract the two call sites differently)
    EXPECT_DOUBLE_EQ(law.energy_density(E), m.energy_density(E));
    EXPECT_LE((law.pk2_stress(E) - m.pk2_stress(E)).norm(), 1e-15 * m.pk2_stress(E).norm());
    EXPECT_LE((law.tangent(E, dE) - m.tangent(dE)).norm(), 1e-15 * m.tangent(dE).norm());
    EXPECT_LE((apply_tangent(law.tangent_matrix(E), dE) - m.tangent(dE)).norm(),
              1e-13 * m.tangent(dE).norm());
  }
  check_derivatives(law, m.mu, 62);
  check_small_strain(law, 3000.0, 0.45);
}

TEST(Law, ForwardsEveryLawUnchanged) {
  const std::vector<Law> laws = {NeoHookean(2.0, 1.0), MooneyRivlin(0.3, 0.2, 4.0), Yeoh(0.5, 0.1, 0.01, 4.0),
                                 Ogden({1.0, 0.1}, {2.5, -1.0}, 4.0), VerondaWestmann(0.5, 2.0, 4.0)};
  const std::vector<std::string> names = {"neo_hookean", "mooney_rivlin", "yeoh", "ogden",
                                          "veronda_westmann"};
  std::mt19937 rng(63);
  const Mat3 E = green_strain(random_f(rng, 0.7, 0.3)), dE = random_sym(rng, 1.0);
  for (std::size_t k = 0; k < laws.size(); ++k) {
    const Law& law = laws[k];
    EXPECT_EQ(law.name(), names[k]);
    EXPECT_FALSE(law.is_stvk());
    std::visit(
        [&](const auto& m) {
          if constexpr (!std::is_same_v<std::decay_t<decltype(m)>, StVenantKirchhoff>) {
            EXPECT_EQ(law.energy_density(E), m.energy_density(E));
            EXPECT_EQ(law.pk2_stress(E), m.pk2_stress(E));
            EXPECT_EQ(law.tangent(E, dE), m.tangent(E, dE));
            EXPECT_EQ(law.tangent_matrix(E), m.tangent_matrix(E));
            EXPECT_EQ(law.small_strain().mu, m.small_strain().mu);
          }
        },
        law.variant());
  }
}

TEST(Law, ConfinedCompressionStVKSoftensNeoHookeanDoesNot) {
  // F = diag(s, 1, 1). St VK: P_11 = s S_11 = (lambda + 2 mu) s (s^2 - 1)/2 has its largest
  // magnitude at s = 1/sqrt(3) and returns to 0 as s -> 0: a push beyond that load has no
  // equilibrium (what caps indentation depth). Neo-Hookean: |P_11| grows without bound as s -> 0.
  const double E = 3000.0, nu = 0.45;
  const Law stvk = StVenantKirchhoff::from_young_poisson(E, nu), nh = NeoHookean::from_young_poisson(E, nu);
  auto p11 = [](const Law& law, double s) {
    const Mat3 F = Eigen::Vector3d(s, 1, 1).asDiagonal().toDenseMatrix();
    return (F * law.pk2_stress(green_strain(F)))(0, 0);
  };
  const double s_peak = 1.0 / std::sqrt(3.0), lm = stvk.small_strain().lambda + 2 * stvk.small_strain().mu;
  EXPECT_NEAR(p11(stvk, s_peak), lm * s_peak * (s_peak * s_peak - 1) / 2, 1e-12 * lm);
  EXPECT_GT(p11(stvk, 0.3), p11(stvk, s_peak));  // softening: less compressive stress at s = 0.3
  EXPECT_GT(p11(stvk, 0.8), p11(stvk, s_peak));
  double prev = 0.0;
  for (double s = 0.95; s > 0.02; s -= 0.05) {
    EXPECT_LT(p11(nh, s), prev) << s;  // monotone
    prev = p11(nh, s);
  }
  std::printf(
      "confined compression, E = %g, nu = %g: St VK max |P11| = %.1f Pa at s = 0.577; neo-Hookean "
      "|P11| at s = 0.577, 0.3, 0.05: %.1f, %.1f, %.1f Pa\n",
      E, nu, -p11(stvk, s_peak), -p11(nh, s_peak), -p11(nh, 0.3), -p11(nh, 0.05));
}

}  // namespace
}  // namespace tmlab::tm
