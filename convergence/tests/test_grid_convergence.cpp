// Tests of the convergence numerics (convergence/grid_convergence.hpp) against closed forms:
// f(h) = f0 + C h^p gives back p and f0 (constant and non-constant ratios), the GCI and the
// estimated errors follow their formulas, oscillatory / diverging / stalled / inconsistent
// sequences are not asymptotic, bad input throws naming the argument.
#include "convergence/grid_convergence.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace tmlab::convergence {
namespace {

/// f0 + C h^p on the given sizes.
std::vector<double> power_law(const std::vector<double>& h, double f0, double c, double p) {
  std::vector<double> f;
  for (const double x : h) f.push_back(f0 + c * std::pow(x, p));
  return f;
}

/// The message of the tmlab::Error `fn` throws ("" when it throws none).
template <class Fn>
std::string error_of(Fn fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(GridConvergence, ObservedOrderOfAPowerLawIsItsExponent) {
  // h = 1, 1/2, 1/4: f2 - f1 = C (1/4 - 1), f3 - f2 = C (1/16 - 1/4): ratio 4 = 2^2.
  EXPECT_DOUBLE_EQ(observed_order(1.0 + 3.0, 1.0 + 3.0 / 4.0, 1.0 + 3.0 / 16.0, 2.0), 2.0);
  // A ratio of 3 and p = 1: differences -2C/3 and -2C/9.
  EXPECT_NEAR(observed_order(5.0 + 1.0, 5.0 + 1.0 / 3.0, 5.0 + 1.0 / 9.0, 3.0), 1.0, 1e-14);
  // The general form agrees with the closed form on a constant ratio.
  const std::vector<double> h{0.3, 0.2, 0.2 / 1.5};
  const std::vector<double> f = power_law(h, 2.0, -0.7, 1.7);
  EXPECT_NEAR(observed_order_h(h[0], h[1], h[2], f[0], f[1], f[2]), observed_order(f[0], f[1], f[2], 1.5),
              1e-12);
  EXPECT_NEAR(observed_order(f[0], f[1], f[2], 1.5), 1.7, 1e-12);
}

TEST(GridConvergence, NonConstantRatiosRecoverTheExponentExactly) {
  // Ratios 1.5 then 1.25 (rounded cell counts 4, 6, 7.5 say) and several exponents.
  const std::vector<double> h{0.25, 0.25 / 1.5, 0.25 / 1.5 / 1.25};
  for (const double p : {0.5, 1.0, 2.0, 3.0}) {
    const std::vector<double> f = power_law(h, 10.0, 4.0, p);
    EXPECT_NEAR(observed_order_h(h[0], h[1], h[2], f[0], f[1], f[2]), p, 1e-10) << "p = " << p;
  }
  // A diverging sequence (p < 0: the differences grow) keeps its negative order.
  const std::vector<double> g = power_law(h, 1.0, 0.01, -1.0);
  EXPECT_NEAR(observed_order_h(h[0], h[1], h[2], g[0], g[1], g[2]), -1.0, 1e-10);
  // The model side (r21^p - 1) / (1 - r32^-p) increases with p, so the root is unique: checked on
  // a grid of orders for ratios on both sides of each other.
  for (const auto& [r21, r32] : {std::pair{2.0, 1.1}, {1.1, 2.0}, {1.5, 1.5}, {3.0, 1.01}}) {
    double previous = -1e300;
    for (int i = 0; i < 160; ++i) {
      const double p = -19.95 + 0.25 * i;  // never 0, where the expression is 0/0 (its limit is a/b)
      const double model = std::expm1(p * std::log(r21)) / -std::expm1(-p * std::log(r32));
      EXPECT_GT(model, previous) << "r21 " << r21 << " r32 " << r32 << " p " << p;
      previous = model;
    }
  }
}

TEST(GridConvergence, QuadraticSequenceRecoversOrderExtrapolationErrorsAndGci) {
  // f(h) = f0 + C h^2 on four levels with ratio 2.
  const double f0 = 3.25, c = -0.8;
  const std::vector<double> h{0.4, 0.2, 0.1, 0.05};
  const std::vector<double> f = power_law(h, f0, c, 2.0);
  const ConvergenceAnalysis a = analyse_convergence(h, f);
  EXPECT_TRUE(a.asymptotic) << a.reason;
  EXPECT_EQ(a.verdict, "asymptotic");
  EXPECT_TRUE(a.constant_ratio);
  EXPECT_TRUE(a.note.empty());
  ASSERT_EQ(a.triples.size(), 2u);
  for (const TripleOrder& t : a.triples) EXPECT_NEAR(t.order, 2.0, 1e-12);
  EXPECT_NEAR(a.order_spread, 0.0, 1e-12);
  EXPECT_NEAR(a.order, 2.0, 1e-12);
  EXPECT_NEAR(a.extrapolated, f0, 1e-14);
  EXPECT_TRUE(std::isnan(a.ratio[0]));
  for (std::size_t k = 1; k < 4; ++k) EXPECT_DOUBLE_EQ(a.ratio[k], 2.0);
  for (std::size_t k = 0; k < 4; ++k) {
    // The error of level k is |C| h_k^2 / |f0|.
    EXPECT_NEAR(a.relative_error[k], std::abs(c) * h[k] * h[k] / f0, 1e-13) << "level " << k + 1;
  }
  EXPECT_TRUE(std::isnan(a.gci[0]));
  for (std::size_t k = 1; k < 4; ++k) {
    // GCI_k = 1.25 |f_k - f_{k-1}| / |f_k| / (2^2 - 1) = 1.25 |C| (h_{k-1}^2 - h_k^2) / (3 |f_k|) =
    // 1.25 |C| h_k^2 / |f_k|: the estimated error of f_k against f0 scaled by f0 / f_k, times Fs.
    EXPECT_NEAR(a.gci[k], 1.25 * std::abs(c) * h[k] * h[k] / std::abs(f[k]), 1e-13) << "level " << k + 1;
    EXPECT_NEAR(a.gci[k], gci(f[k - 1], f[k], 2.0, 2.0), 1e-15);
  }
  EXPECT_NEAR(richardson(f[2], f[3], 2.0, 2.0), f0, 1e-14);
}

TEST(GridConvergence, NonConstantRatioSequenceExtrapolatesExactly) {
  // Cell counts 4, 6, 9, 13 (ratio 1.5 rounded): h = 1 / cells, p = 1.
  const std::vector<double> h{1.0 / 4, 1.0 / 6, 1.0 / 9, 1.0 / 13};
  const std::vector<double> f = power_law(h, -2.0, 0.5, 1.0);
  const ConvergenceAnalysis a = analyse_convergence(h, f);
  EXPECT_TRUE(a.asymptotic) << a.reason;
  EXPECT_FALSE(a.constant_ratio);
  for (const TripleOrder& t : a.triples) EXPECT_NEAR(t.order, 1.0, 1e-10);
  EXPECT_NEAR(a.extrapolated, -2.0, 1e-12);
  EXPECT_NEAR(a.ratio[3], 13.0 / 9.0, 1e-15);
}

TEST(GridConvergence, ThreeLevelsGiveOneOrderWithANote) {
  const std::vector<double> h{1.0, 0.5, 0.25};
  const ConvergenceAnalysis a = analyse_convergence(h, power_law(h, 1.0, 1.0, 1.0));
  EXPECT_TRUE(a.asymptotic);
  EXPECT_FALSE(a.note.empty());
  EXPECT_NEAR(a.order, 1.0, 1e-14);
  EXPECT_NEAR(a.extrapolated, 1.0, 1e-14);
}

TEST(GridConvergence, OscillatorySequenceIsNotAsymptotic) {
  const std::vector<double> h{1.0, 0.5, 0.25, 0.125};
  const ConvergenceAnalysis a = analyse_convergence(h, {1.0, 1.2, 1.15, 1.16});
  EXPECT_FALSE(a.asymptotic);
  EXPECT_EQ(a.verdict, "not asymptotic");
  EXPECT_NE(a.reason.find("oscillatory"), std::string::npos) << a.reason;
  EXPECT_NE(a.reason.find("levels 1-2-3"), std::string::npos) << a.reason;
  EXPECT_TRUE(std::isnan(a.extrapolated));
  EXPECT_TRUE(std::isnan(a.order));
  EXPECT_EQ(a.triples[0].problem, "oscillatory");
  EXPECT_TRUE(std::isnan(a.triples[0].order));
  for (const double e : a.relative_error) EXPECT_TRUE(std::isnan(e));
  for (const double g : a.gci) EXPECT_TRUE(std::isnan(g));
  // The closed form says so too: no order.
  EXPECT_TRUE(std::isnan(observed_order(1.0, 1.2, 1.15, 2.0)));
}

TEST(GridConvergence, InconsistentOrdersAreNotAsymptotic) {
  // First triple p = 1 (differences halve), second p = 2 (differences quarter): spread 1 > 0.3.
  const std::vector<double> h{1.0, 0.5, 0.25, 0.125};
  const ConvergenceAnalysis a = analyse_convergence(h, {0.0, 0.8, 1.2, 1.3});
  EXPECT_FALSE(a.asymptotic);
  EXPECT_NEAR(a.triples[0].order, 1.0, 1e-14);
  EXPECT_NEAR(a.triples[1].order, 2.0, 1e-14);
  EXPECT_NEAR(a.order_spread, 1.0, 1e-14);
  EXPECT_NE(a.reason.find("differ by 1"), std::string::npos) << a.reason;
  EXPECT_TRUE(std::isnan(a.extrapolated));
  // Orders within 0.3 of each other pass: p = 2, then p = 2.25.
  const double d1 = 0.4, d2 = 0.1, d3 = d2 / std::pow(2.0, 2.25);
  const ConvergenceAnalysis b = analyse_convergence(h, {0.0, d1, d1 + d2, d1 + d2 + d3});
  EXPECT_TRUE(b.asymptotic) << b.reason;
  EXPECT_NEAR(b.order, 2.25, 1e-12);
  EXPECT_NEAR(b.order_spread, 0.25, 1e-12);
  // A custom spread limit below it refuses.
  EXPECT_FALSE(analyse_convergence(h, {0.0, d1, d1 + d2, d1 + d2 + d3}, 0.2).asymptotic);
}

TEST(GridConvergence, DivergingAndStalledSequencesAreNotAsymptotic) {
  const std::vector<double> h{1.0, 0.5, 0.25};
  const ConvergenceAnalysis grow = analyse_convergence(h, {1.0, 1.1, 1.3});
  EXPECT_FALSE(grow.asymptotic);
  EXPECT_NE(grow.reason.find("diverging"), std::string::npos) << grow.reason;
  EXPECT_NEAR(grow.triples[0].order, -1.0, 1e-12);
  const ConvergenceAnalysis flat = analyse_convergence(h, {1.0, 2.0, 2.0});
  EXPECT_FALSE(flat.asymptotic);
  EXPECT_NE(flat.reason.find("zero"), std::string::npos) << flat.reason;
  EXPECT_TRUE(std::isnan(observed_order(1.0, 1.0, 1.0, 2.0)));
}

TEST(GridConvergence, BadInputThrowsNamingTheArgument) {
  EXPECT_NE(error_of([] {
              analyse_convergence({1.0, 0.5}, {1.0, 2.0});
            }).find("value: 2 levels"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              analyse_convergence({1.0, 0.5}, {1.0, 2.0, 3.0});
            }).find("h: 2 sizes"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              analyse_convergence({1.0, 0.5, 0.5}, {1.0, 2.0, 3.0});
            }).find("does not refine"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              analyse_convergence({1.0, 2.0, 0.5}, {1.0, 2.0, 3.0});
            }).find("level 2"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              analyse_convergence({1.0, 0.5, -0.1}, {1.0, 2.0, 3.0});
            }).find("h of level 3"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              analyse_convergence({1.0, 0.5, 0.25}, {1.0, NAN, 3.0});
            }).find("value of level 2"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              analyse_convergence({1.0, INFINITY, 0.25}, {1.0, 2.0, 3.0});
            }).find("h of level 2"),
            std::string::npos);
  EXPECT_NE(error_of([] { observed_order(1.0, 2.0, 2.5, 1.0); }).find("ratio"), std::string::npos);
  EXPECT_NE(error_of([] { observed_order(1.0, 2.0, 2.5, 0.5); }).find("ratio"), std::string::npos);
  EXPECT_NE(error_of([] { observed_order(1.0, NAN, 2.5, 2.0); }).find("f2"), std::string::npos);
  EXPECT_NE(error_of([] { observed_order_h(1.0, 1.0, 0.5, 1.0, 2.0, 2.5); }).find("decrease"),
            std::string::npos);
  EXPECT_NE(error_of([] { observed_order_h(1.0, 0.5, 0.0, 1.0, 2.0, 2.5); }).find("positive"),
            std::string::npos);
  EXPECT_NE(error_of([] { observed_order_h(1.0, 0.5, 0.25, 1.0, 2.0, INFINITY); }).find("f3"),
            std::string::npos);
}

}  // namespace
}  // namespace tmlab::convergence
