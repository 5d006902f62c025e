// PronySeries: the two conventions (seed eq. 10 long-term, eq. 24 instantaneous;
// docs/theory/seed-errata.md row "10 vs 24"), the relaxation function, validation messages and the
// strict JSON form.
#include "core/base/error.hpp"
#include "tensormass/viscoelastic/prony_series.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tmlab::tm {
namespace {

/// Runs f, expects a tmlab::Error whose message contains every fragment.
template <class F>
void expect_error(F f, std::initializer_list<const char*> fragments) {
  try {
    f();
    FAIL() << "expected tmlab::Error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    for (const char* frag : fragments)
      EXPECT_NE(msg.find(frag), std::string::npos) << "'" << frag << "' not in: " << msg;
  }
}

TEST(PronySeries, LongTermRelaxationFunction) {
  const PronySeries p = PronySeries::from_long_term({0.5, 1.5}, {0.1, 2.0});
  EXPECT_EQ(p.size(), 2u);
  EXPECT_DOUBLE_EQ(p.alpha_sum(), 2.0);
  EXPECT_DOUBLE_EQ(p.relaxation(0.0), 3.0);  // E(0)/E_inf = 1 + sum alpha
  EXPECT_NEAR(p.relaxation(1.0), 1.0 + 0.5 * std::exp(-10.0) + 1.5 * std::exp(-0.5), 1e-15);
  EXPECT_DOUBLE_EQ(p.relaxation(1e6), 1.0);
  EXPECT_DOUBLE_EQ(p.instantaneous_modulus(1000.0), 3000.0);
  EXPECT_DOUBLE_EQ(p.long_term_modulus(3000.0), 1000.0);
  EXPECT_FALSE(p.is_elastic());
  EXPECT_TRUE(PronySeries::from_long_term({0.0}, {1.0}).is_elastic());
}

TEST(PronySeries, InstantaneousConventionConvertsBothWays) {
  // Nava-style g: alpha_j = g_j / (1 - sum g), E_inf = E_0 (1 - sum g)   (errata eq. 24)
  const std::vector<double> g{0.3, 0.2};
  const PronySeries p = PronySeries::from_instantaneous(g, {0.5, 5.0});
  EXPECT_NEAR(p.alpha(0), 0.6, 1e-15);
  EXPECT_NEAR(p.alpha(1), 0.4, 1e-15);
  const std::vector<double> back = p.instantaneous_weights();
  EXPECT_NEAR(back[0], 0.3, 1e-15);
  EXPECT_NEAR(back[1], 0.2, 1e-15);
  EXPECT_NEAR(p.long_term_modulus(4000.0), 4000.0 * 0.5, 1e-9);
  // Same function in both normalisations: E_0 r(t) / r(0) = E_0 (1 - sum g (1 - e^{-t/tau})).
  for (double t : {0.0, 0.3, 2.0, 20.0}) {
    const double nava = 1.0 - 0.3 * (1.0 - std::exp(-t / 0.5)) - 0.2 * (1.0 - std::exp(-t / 5.0));
    EXPECT_NEAR(p.relaxation(t) / p.relaxation(0.0), nava, 1e-15) << t;
  }
}

TEST(PronySeries, ValidationNamesTheTermAndValue) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  expect_error([] { PronySeries::from_long_term({}, {}); }, {"empty"});
  expect_error([] { PronySeries::from_long_term({1.0, 2.0}, {1.0}); }, {"2 weights", "1 relaxation"});
  expect_error([] { PronySeries::from_long_term({1.0, 2.0}, {1.0, -1.0}); }, {"term 1", "tau = -1", "> 0"});
  expect_error([] { PronySeries::from_long_term({1.0}, {0.0}); }, {"term 0", "tau = 0"});
  expect_error(
      [] {
        PronySeries::from_long_term({1.0, -0.5}, {1.0, 1.0});
      },
      {"term 1", "alpha = -0.5", ">= 0"});
  expect_error([&] { PronySeries::from_long_term({nan}, {1.0}); }, {"term 0", "not finite"});
  expect_error([&] { PronySeries::from_long_term({1.0}, {inf}); }, {"term 0", "tau", "not finite"});
  expect_error([] { PronySeries::from_instantaneous({0.6, 0.4}, {1.0, 2.0}); }, {"sum to 1", "< 1"});
  expect_error([] { PronySeries::from_instantaneous({0.6, 0.5}, {1.0, 2.0}); }, {"sum to 1.1"});
  expect_error([] { PronySeries::from_instantaneous({-0.1}, {1.0}); }, {"term 0", "g = -0.1"});
}

TEST(PronySeries, JsonBothConventionsAndStrictKeys) {
  const auto lt = PronySeries::from_json(
      nlohmann::json::parse(R"({"convention": "long_term", "terms": [{"weight": 1.5, "tau": 0.2}]})"),
      "p.json");
  EXPECT_DOUBLE_EQ(lt.alpha(0), 1.5);
  EXPECT_DOUBLE_EQ(lt.tau(0), 0.2);
  const auto in = PronySeries::from_json(
      nlohmann::json::parse(
          R"({"convention": "instantaneous", "terms": [{"weight": 0.25, "tau": 1}, {"weight": 0.25, "tau": 10}]})"),
      "p.json");
  EXPECT_DOUBLE_EQ(in.alpha(0), 0.5);
  EXPECT_DOUBLE_EQ(in.alpha(1), 0.5);
  const auto rt = PronySeries::from_json(in.to_json(), "round trip");
  EXPECT_EQ(rt.alpha(), in.alpha());
  EXPECT_EQ(rt.tau(), in.tau());

  expect_error(
      [] {
        PronySeries::from_json(
            nlohmann::json::parse(
                R"({"convention": "long_term", "terms": [{"weight": 1, "tau": 1}], "extra": 1})"),
            "p.json", "material.prony");
      },
      {"p.json", "material.prony.extra", "unknown"});
  expect_error(
      [] {
        PronySeries::from_json(
            nlohmann::json::parse(
                R"({"convention": "long_term", "terms": [{"weight": 1, "tau": 1, "taux": 2}]})"),
            "p.json");
      },
      {"terms[0].taux", "unknown"});
  expect_error(
      [] {
        PronySeries::from_json(
            nlohmann::json::parse(R"({"convention": "nava", "terms": [{"weight": 1, "tau": 1}]})"), "p.json");
      },
      {"'convention'", "long_term"});
  expect_error(
      [] {
        PronySeries::from_json(nlohmann::json::parse(R"({"convention": "long_term", "terms": []})"),
                               "p.json");
      },
      {"'terms'", "non-empty"});
  expect_error(
      [] {
        PronySeries::from_json(
            nlohmann::json::parse(R"({"convention": "long_term", "terms": [{"weight": 1, "tau": -2}]})"),
            "p.json");
      },
      {"terms[0].tau", "> 0"});
  expect_error(
      [] {
        PronySeries::from_json(
            nlohmann::json::parse(R"({"convention": "long_term", "terms": [{"weight": -1, "tau": 2}]})"),
            "p.json");
      },
      {"terms[0].weight", ">= 0"});
  expect_error(
      [] {
        PronySeries::from_json(
            nlohmann::json::parse(
                R"({"convention": "instantaneous", "terms": [{"weight": 0.7, "tau": 1}, {"weight": 0.3, "tau": 2}]})"),
            "p.json");
      },
      {"p.json", "terms", "< 1"});
  expect_error(
      [] {
        PronySeries::from_json(nlohmann::json::parse(R"({"terms": [{"weight": 1, "tau": 1}]})"), "p.json");
      },
      {"'convention'", "required"});
}

}  // namespace
}  // namespace tmlab::tm
