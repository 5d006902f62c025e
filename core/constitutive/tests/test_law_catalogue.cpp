// The law catalogue is consistent: one row per law in enum order with its kMaterialLawNames name,
// admissible sample values pass law_parameter_problem, each bound refuses the value just outside it
// naming the parameter's case key, and the shear moduli are the closed forms of the theory
// (docs/theory/hyperelastic-laws.md). The factory side (each law built and linearised) is
// tensormass/materials/tests/test_law_factory.cpp.
#include "core/constitutive/law_catalogue.hpp"

#include "core/testing/law_samples.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tmlab {
namespace {

TEST(LawCatalogue, OneRowPerLawInEnumOrder) {
  ASSERT_EQ(law_catalogue().size(), std::size(kMaterialLawNames));
  std::size_t k = 0;
  for (const LawDescriptor& d : law_catalogue()) {
    EXPECT_EQ(static_cast<std::size_t>(d.law), k);
    EXPECT_STREQ(d.name, kMaterialLawNames[k]);
    EXPECT_EQ(&law_descriptor(d.law), &d);
    EXPECT_EQ(law_name_list()[k], d.name);
    EXPECT_EQ(law_takes_young_poisson(d.law), d.bulk == BulkResponse::YoungPoisson) << d.name;
    EXPECT_TRUE(d.hyperelastic_tl && d.dealii_reference) << d.name;  // every law runs on both
    EXPECT_EQ(d.tensor_mass, d.law == MaterialLaw::StVK) << d.name;  // the paper's kernel is St VK's
    EXPECT_FALSE(d.parameters.empty()) << d.name;
    for (const LawParameterInfo& info : d.parameters) {
      EXPECT_TRUE(info.list ? info.values != nullptr : info.scalar != nullptr) << d.name << "." << info.name;
      EXPECT_LT(info.fit.lower, info.fit.upper) << d.name << "." << info.name;
      EXPECT_GE(info.fit.lower, info.lower.value) << d.name << "." << info.name;  // the box is admissible
      EXPECT_LE(info.fit.upper, info.upper.value) << d.name << "." << info.name;
    }
    ++k;
  }
}

TEST(LawCatalogue, SampleValuesAreAdmissible) {
  for (const LawDescriptor& d : law_catalogue()) {
    const LawParameters p = testing::sample_parameters(d.law);
    const LawParameterProblem problem = law_parameter_problem(d.law, p);
    EXPECT_TRUE(problem.empty()) << d.name << ": " << problem.key << " " << problem.reason;
    EXPECT_GT(small_strain_moduli(d.law, p).shear, 0.0) << d.name;
  }
}

TEST(LawCatalogue, EachBoundRefusesNamingItsKey) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const LawDescriptor& d : law_catalogue()) {
    for (const LawParameterInfo& info : d.parameters) {
      std::vector<double> outside = {nan, std::numeric_limits<double>::infinity()};
      if (std::isfinite(info.lower.value))
        outside.push_back(info.lower.closed ? std::nextafter(info.lower.value, -1e300) : info.lower.value);
      if (std::isfinite(info.upper.value))
        outside.push_back(info.upper.closed ? std::nextafter(info.upper.value, 1e300) : info.upper.value);
      if (info.nonzero) outside.push_back(0.0);
      for (const double v : outside) {
        LawParameters p = testing::sample_parameters(d.law);
        if (info.list)
          (p.*info.values).back() = v;
        else
          p.*info.scalar = v;
        const LawParameterProblem problem = law_parameter_problem(d.law, p);
        EXPECT_EQ(problem.key, info.case_key) << d.name << " " << info.name << " = " << v;
        EXPECT_FALSE(parameter_refusal(info, v).empty()) << d.name << " " << info.name << " = " << v;
      }
    }
    if (d.bulk == BulkResponse::KappaOrPoisson) {
      LawParameters p = testing::sample_parameters(d.law);
      p.kappa = 0.0;
      EXPECT_EQ(law_parameter_problem(d.law, p).key, "kappa") << d.name;
    }
  }
  // The wording names the interval with the key.
  EXPECT_EQ(parameter_refusal(poisson_parameter(), 0.5), "must satisfy -1 < nu < 0.5 (got 0.5)");
  EXPECT_EQ(parameter_refusal(bulk_modulus_parameter(), -2.0), "must be > 0 (got -2)");
}

TEST(LawCatalogue, ShearModuliAreTheClosedForms) {
  LawParameters p = testing::sample_parameters(MaterialLaw::StVK);
  EXPECT_EQ(law_descriptor(MaterialLaw::StVK).shear_modulus(p), p.young / (2.0 * (1.0 + p.poisson)));
  p = testing::sample_parameters(MaterialLaw::MooneyRivlin);
  EXPECT_EQ(law_descriptor(MaterialLaw::MooneyRivlin).shear_modulus(p), 2.0 * (p.c10 + p.c01));
  p = testing::sample_parameters(MaterialLaw::Yeoh);
  EXPECT_EQ(law_descriptor(MaterialLaw::Yeoh).shear_modulus(p), 2.0 * p.c10);
  p = testing::sample_parameters(MaterialLaw::Ogden);
  double g = 0.0;
  for (std::size_t k = 0; k < p.mu.size(); ++k) g += 0.5 * p.mu[k] * p.alpha[k];
  EXPECT_EQ(law_descriptor(MaterialLaw::Ogden).shear_modulus(p), g);
  p = testing::sample_parameters(MaterialLaw::VerondaWestmann);
  EXPECT_EQ(law_descriptor(MaterialLaw::VerondaWestmann).shear_modulus(p), p.c1 * p.c2);
}

TEST(LawCatalogue, CaseKeysAreTheParametersThenTheBulkChoice) {
  EXPECT_EQ(law_case_keys(MaterialLaw::StVK), (std::vector<std::string>{"E", "nu"}));
  EXPECT_EQ(law_case_keys(MaterialLaw::Yeoh), (std::vector<std::string>{"c10", "c20", "c30", "kappa", "nu"}));
  EXPECT_EQ(law_case_keys(MaterialLaw::Ogden), (std::vector<std::string>{"mu", "alpha", "kappa", "nu"}));
  EXPECT_TRUE(law_descriptor(MaterialLaw::Ogden).has_terms());
  EXPECT_FALSE(law_descriptor(MaterialLaw::Yeoh).has_terms());
}

}  // namespace
}  // namespace tmlab
