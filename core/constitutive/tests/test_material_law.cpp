// The law vocabulary: names round-trip, small-strain moduli of each law against hand values, and the
// parameter checks (which key is named, Ogden's stability condition).
#include "core/constitutive/material_law.hpp"

#include <gtest/gtest.h>

namespace tmlab {
namespace {

TEST(MaterialLaw, NamesRoundTrip) {
  for (const char* n : kMaterialLawNames) EXPECT_EQ(to_string(material_law_from_string(n).value()), n);
  EXPECT_FALSE(material_law_from_string("hooke"));
  EXPECT_TRUE(law_takes_young_poisson(MaterialLaw::NeoHookean));
  EXPECT_FALSE(law_takes_young_poisson(MaterialLaw::Ogden));
}

TEST(MaterialLaw, SmallStrainModuliOfEachLaw) {
  LawParameters p;
  p.young = 3000.0, p.poisson = 0.25;  // G = 1200, K = 2000
  const SmallStrainModuli e = small_strain_moduli(MaterialLaw::StVK, p);
  EXPECT_DOUBLE_EQ(e.shear, 1200.0);
  EXPECT_DOUBLE_EQ(e.bulk, 2000.0);
  EXPECT_NEAR(e.young(), 3000.0, 1e-9);
  EXPECT_NEAR(e.poisson(), 0.25, 1e-15);
  EXPECT_NEAR(e.lambda(), 1200.0, 1e-9);  // E nu / ((1+nu)(1-2nu))
  p.kappa = 5000.0;
  p.c10 = 100.0, p.c01 = 50.0;
  EXPECT_DOUBLE_EQ(small_strain_moduli(MaterialLaw::MooneyRivlin, p).shear, 300.0);
  EXPECT_DOUBLE_EQ(small_strain_moduli(MaterialLaw::Yeoh, p).shear, 200.0);
  p.mu = {400.0, -10.0}, p.alpha = {2.0, -2.0};
  EXPECT_DOUBLE_EQ(small_strain_moduli(MaterialLaw::Ogden, p).shear, 410.0);
  p.c1 = 20.0, p.c2 = 3.0;
  EXPECT_DOUBLE_EQ(small_strain_moduli(MaterialLaw::VerondaWestmann, p).shear, 60.0);
  EXPECT_DOUBLE_EQ(small_strain_moduli(MaterialLaw::VerondaWestmann, p).bulk, 5000.0);
  // kappa from nu gives that nu back.
  const SmallStrainModuli m{300.0, bulk_from_poisson(300.0, 0.45)};
  EXPECT_NEAR(m.poisson(), 0.45, 1e-14);
}

TEST(MaterialLaw, ImpossibleParametersNameTheirKey) {
  LawParameters p;
  p.young = 1000.0, p.poisson = 0.5;
  EXPECT_EQ(law_parameter_problem(MaterialLaw::NeoHookean, p).key, "nu");
  p.poisson = 0.3;
  EXPECT_TRUE(law_parameter_problem(MaterialLaw::NeoHookean, p).empty());
  EXPECT_EQ(law_parameter_problem(MaterialLaw::Yeoh, p).key, "kappa");  // kappa = 0
  p.kappa = 1e4;
  EXPECT_EQ(law_parameter_problem(MaterialLaw::Yeoh, p).key, "c10");
  p.c10 = 100.0, p.c01 = -100.0;
  EXPECT_EQ(law_parameter_problem(MaterialLaw::MooneyRivlin, p).key, "c01");
  p.c01 = -50.0;
  EXPECT_TRUE(law_parameter_problem(MaterialLaw::MooneyRivlin, p).empty());
  p.mu = {100.0, 50.0}, p.alpha = {2.0};
  EXPECT_EQ(law_parameter_problem(MaterialLaw::Ogden, p).key, "alpha");
  p.alpha = {2.0, 0.0};
  EXPECT_EQ(law_parameter_problem(MaterialLaw::Ogden, p).key, "alpha");
  // Stability: sum_p mu_p alpha_p = 200 - 250 < 0.
  p.alpha = {2.0, -5.0};
  const LawParameterProblem unstable = law_parameter_problem(MaterialLaw::Ogden, p);
  EXPECT_EQ(unstable.key, "mu");
  EXPECT_NE(unstable.reason.find("stability"), std::string::npos) << unstable.reason;
  p.alpha = {2.0, -1.0};
  EXPECT_TRUE(law_parameter_problem(MaterialLaw::Ogden, p).empty());
  p.c1 = 10.0, p.c2 = 0.0;
  EXPECT_EQ(law_parameter_problem(MaterialLaw::VerondaWestmann, p).key, "c2");
}

}  // namespace
}  // namespace tmlab
