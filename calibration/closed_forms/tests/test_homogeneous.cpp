// Tests of the homogeneous platen closed forms: the St VK limits with known formulas, the
// small-strain limit of every law, a free lateral face, and the St VK compression limit point.
#include "calibration/closed_forms/homogeneous.hpp"

#include "core/base/error.hpp"
#include "tensormass/materials/law_factory.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace tmlab::closed_forms {
namespace {

tm::Law law(const std::string& name, const nlohmann::json& params) {
  return tm::make_law(name, params, "test");
}

TEST(PlatenState, StVkUniaxialStressAndStrain) {
  const tm::Law stvk = law("stvk", {{"young", 10000.0}, {"poisson", 0.3}});
  const double H = 0.03, A = 2e-3, d = 0.003, l = 1.0 - d / H, ezz = 0.5 * (l * l - 1.0);
  const PlatenState u = platen_state(stvk, PlatenTest::Unconfined, H, A, d);
  EXPECT_NEAR(u.force, -l * 10000.0 * ezz * A, 1e-12 * u.force);
  // St VK lateral Green strain E_xx = -nu E_zz.
  EXPECT_NEAR(0.5 * (u.lateral_stretch * u.lateral_stretch - 1.0), -0.3 * ezz, 1e-14);
  const double lambda = 10000.0 * 0.3 / (1.3 * 0.4), mu = 10000.0 / 2.6;
  const PlatenState c = platen_state(stvk, PlatenTest::Confined, H, A, d);
  EXPECT_NEAR(c.force, -l * (lambda + 2 * mu) * ezz * A, 1e-12 * c.force);
  EXPECT_EQ(c.lateral_stretch, 1.0);
}

TEST(PlatenState, EveryLawHasTheSmallStrainModulusAndAFreeLateralFace) {
  const double E = 5000.0, nu = 0.4, mu = E / (2 * (1 + nu)), kappa = E / (3 * (1 - 2 * nu));
  const std::vector<std::pair<std::string, nlohmann::json>> laws = {
      {"stvk", {{"young", E}, {"poisson", nu}}},
      {"neo_hookean", {{"young", E}, {"poisson", nu}}},
      {"mooney_rivlin", {{"c10", 0.3 * mu}, {"c01", 0.2 * mu}, {"kappa", kappa}}},
      {"yeoh", {{"c10", 0.5 * mu}, {"c20", 0.1 * mu}, {"kappa", kappa}}},
      {"ogden", {{"mu", {mu}}, {"alpha", {2.0}}, {"kappa", kappa}}},
  };
  for (const auto& [name, params] : laws) {
    const tm::Law m = law(name, params);
    const double d = 1e-7 * 0.03;  // strain 1e-7: the linear regime
    const PlatenState s = platen_state(m, PlatenTest::Unconfined, 0.03, 1.0, d);
    EXPECT_NEAR(s.nominal_stress / 1e-7, E, 1e-4 * E) << name;
    // The lateral PK2 stress vanishes at the computed lateral stretch.
    tm::Mat3 e = tm::Mat3::Zero();
    e(0, 0) = e(1, 1) = 0.5 * (s.lateral_stretch * s.lateral_stretch - 1.0);
    e(2, 2) = 0.5 * (s.stretch * s.stretch - 1.0);
    EXPECT_LT(std::abs(m.pk2_stress(e)(0, 0)), 1e-9 * E) << name;
    // At 30 % compression the lateral face is still free and the force positive.
    const PlatenState big = platen_state(m, PlatenTest::Unconfined, 0.03, 1.0, 0.009);
    EXPECT_GT(big.force, 0.0) << name;
  }
}

TEST(PlatenState, RefusesImpossibleStates) {
  const tm::Law nh = law("neo_hookean", {{"young", 1000.0}, {"poisson", 0.3}});
  EXPECT_THROW(platen_state(nh, PlatenTest::Unconfined, 0.03, 1.0, 0.03), Error);
  EXPECT_THROW(platen_state(nh, PlatenTest::Unconfined, -1.0, 1.0, 0.001), Error);
  EXPECT_THROW(platen_state(nh, PlatenTest::Unconfined, 0.03, 0.0, 0.001), Error);
}

}  // namespace
}  // namespace tmlab::closed_forms
