// Tests of the SPEC syntax and of the law built from fit parameters.
#include "calibration/fit/model_spec.hpp"

#include "core/base/error.hpp"
#include "core/constitutive/law_catalogue.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace tmlab::fit {
namespace {

TEST(ModelSpec, ParsesLawTermsPronyAndFixedValues) {
  const ModelSpec s = parse_model_spec("ogden:2+prony:3,poisson=0.49,tau1=0.5");
  EXPECT_EQ(s.law, MaterialLaw::Ogden);
  EXPECT_EQ(s.ogden_terms, 2);
  EXPECT_EQ(s.prony_terms, 3);
  ASSERT_EQ(s.fixed.size(), 2u);
  EXPECT_EQ(s.fixed[0].first, "poisson");
  EXPECT_EQ(s.fixed[1].second, 0.5);
  EXPECT_EQ(parse_model_spec("neo_hookean").prony_terms, 0);
}

TEST(ModelSpec, RefusesBadSpecsNamingThePart) {
  for (const char* bad : {"rubber", "neo_hookean:2", "ogden:0", "ogden:x", "stvk+maxwell:2", "stvk,poisson",
                          "stvk,poisson=abc", "stvk,poisson=nan", "stvk+prony:"}) {
    EXPECT_THROW(parse_model_spec(bad), Error) << bad;
  }
  try {
    parse_model_spec("rubber");
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown law 'rubber'"), std::string::npos);
  }
}

TEST(ModelSpec, NumbersFollowTheOneStrictGrammar) {
  // Issue 26: std::stod took hex floats, leading blanks and ".5"; the SPEC now reads numbers as
  // every option and CSV field does (core/base/number.hpp).
  for (const char* bad : {"stvk,poisson=0x0.8p-1", "stvk,poisson= 0.3", "stvk,poisson=.3", "stvk,poisson=3.",
                          "stvk,poisson=0.3 ", "stvk,young=inf", "stvk,young=1e400", "ogden: 2", "ogden:2.0",
                          "stvk+prony:0x2", "stvk+prony:10", "ogden:02x"}) {
    try {
      (void)parse_model_spec(bad);
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("--model '"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(parse_model_spec("stvk,poisson=4.5e-1").fixed[0].second, 0.45);
  EXPECT_EQ(parse_model_spec("stvk,young=+2E4").fixed[0].second, 20000.0);
  EXPECT_EQ(parse_model_spec("ogden:3+prony:9").prony_terms, 9);
}

TEST(ModelSpec, ANameFixedTwiceIsRefusedWithBothValues) {
  try {
    (void)parse_model_spec("stvk,poisson=0.3,young=1e4,poisson=0.45");
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'poisson' is fixed twice (0.3 and 0.45)"), std::string::npos)
        << e.what();
  }
}

TEST(ModelSpec, EveryLawHasTheStartingSmallStrainModulus) {
  for (const char* law :
       {"stvk", "neo_hookean", "mooney_rivlin", "yeoh", "ogden:1", "ogden:2", "veronda_westmann"}) {
    const ModelSpec s = parse_model_spec(law);
    const auto params = law_parameters(s, 9000.0, 10.0);
    EXPECT_NO_THROW(validate(params)) << law;
    std::vector<double> x;
    for (const auto& p : params) x.push_back(p.value);
    const auto [young, nu] = small_strain_young_poisson(s, x);
    // E = 2 mu0 (1 + nu) with mu0 = E_est / 3 and nu = 0.45 (young itself for stvk and neo-Hookean).
    const double expect =
        (std::string(law) == "stvk" || std::string(law) == "neo_hookean") ? 9000.0 : 2 * 3000.0 * 1.45;
    EXPECT_NEAR(young, expect, 1e-9 * expect) << law;
    EXPECT_EQ(nu, 0.45);
    const tm::Law l = build_law(s, x);
    EXPECT_NEAR(l.small_strain().mu, young / (2 * (1 + nu)), 1e-9 * young) << law;
  }
}

// The SPEC takes exactly the catalogue's laws, its parameters under the catalogue's names (lists as
// name1..nameN) with the catalogue's fit boxes, then "poisson" for the decoupled laws.
TEST(ModelSpec, LawsAndParametersAreTheCatalogues) {
  for (const LawDescriptor& d : law_catalogue()) {
    const ModelSpec s = parse_model_spec(std::string(d.name) + (d.has_terms() ? ":2" : ""));
    EXPECT_EQ(s.law, d.law);
    const std::vector<Parameter> params = law_parameters(s, 9000.0, 10.0);
    std::size_t i = 0;
    for (const LawParameterInfo& info : d.parameters)
      for (int k = 0; k < (info.list ? 2 : 1); ++k, ++i) {
        ASSERT_LT(i, params.size()) << d.name;
        EXPECT_EQ(params[i].name, std::string(info.name) + (info.list ? std::to_string(k + 1) : ""))
            << d.name;
        EXPECT_EQ(params[i].unit, info.unit) << d.name;
        EXPECT_EQ(params[i].lower, info.fit.lower) << d.name << " " << params[i].name;
        EXPECT_EQ(params[i].upper, info.fit.upper) << d.name << " " << params[i].name;
      }
    if (d.bulk == BulkResponse::KappaOrPoisson) {
      EXPECT_EQ(params.at(i++).name, "poisson") << d.name;
    }
    EXPECT_EQ(params.size(), i) << d.name;
    if (!d.has_terms()) {
      EXPECT_THROW(parse_model_spec(std::string(d.name) + ":2"), Error) << d.name;
    }
  }
  try {
    (void)parse_model_spec("hooke");
    FAIL() << "accepted";
  } catch (const Error& e) {
    for (const std::string& n : law_name_list())
      EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tmlab::fit
