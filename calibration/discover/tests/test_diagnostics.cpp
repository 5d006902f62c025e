// The residual diagnostics on series whose answer is known: white noise passes every decisive
// test, an AR(1) series fails Ljung-Box and the runs test, a sinusoid is found periodic at its
// frequency, a trend is not called periodic, and the noise level is recovered from a smooth curve.
#include "calibration/discover/diagnostics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tmlab::discover {
namespace {

std::vector<double> white(std::size_t n, double sigma, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, sigma);
  std::vector<double> v(n);
  for (auto& x : v) x = g(rng);
  return v;
}

TEST(Diagnostics, WhiteNoisePassesRunsAndLjungBox) {
  int failures = 0;
  for (unsigned s = 1; s <= 20; ++s) {
    const auto r = white(500, 1.0, s);
    if (runs_test(r).p < 1e-3) ++failures;
    if (ljung_box(r).p < 1e-3) ++failures;
  }
  // 40 tests at alpha = 1e-3: one failure would already be unlikely (4 %).
  EXPECT_LE(failures, 1);
  const double dw = durbin_watson(white(2000, 1.0, 3));
  EXPECT_NEAR(dw, 2.0, 0.15);
  const auto jb = jarque_bera(white(2000, 1.0, 4));
  EXPECT_GT(jb.p, 1e-3);
  EXPECT_NEAR(jb.kurtosis, 3.0, 0.3);
}

TEST(Diagnostics, Ar1FailsRunsAndLjungBox) {
  const auto e = white(500, 1.0, 7);
  std::vector<double> r(e.size());
  r[0] = e[0];
  for (std::size_t i = 1; i < r.size(); ++i) r[i] = 0.8 * r[i - 1] + e[i];
  EXPECT_LT(runs_test(r).p, 1e-6);
  EXPECT_LT(ljung_box(r).p, 1e-10);
  EXPECT_LT(durbin_watson(r), 1.0);
}

TEST(Diagnostics, RunsTestCountsRuns) {
  const RunsResult r = runs_test({1, 1, -1, -1, 1, 0, 1, -1});
  EXPECT_EQ(r.positive, 4u);
  EXPECT_EQ(r.negative, 3u);
  EXPECT_EQ(r.runs, 4u);  // ++ -- ++ -  (the zero skipped)
}

TEST(Diagnostics, JarqueBeraFailsSkewed) {
  auto r = white(2000, 1.0, 9);
  for (auto& x : r) x = x * x;  // chi-square 1: skewness 2.8
  EXPECT_LT(jarque_bera(r).p, 1e-10);
}

TEST(Diagnostics, NoiseLevelOfASmoothCurve) {
  const auto e = white(3000, 0.05, 11);
  std::vector<double> x(e.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 10.0 * std::sin(double(i) / 300.0) + e[i];
  EXPECT_NEAR(noise_level(x), 0.05, 0.005);
}

TEST(Diagnostics, FisherFindsASinusoidAndNotATrend) {
  std::vector<double> t(600), r = white(600, 1.0, 13), trend(600);
  for (std::size_t i = 0; i < t.size(); ++i) {
    t[i] = 0.2 * double(i);
    r[i] += 0.8 * std::sin(2.0 * 3.14159265358979 * 0.7 * t[i]);
    trend[i] = 0.01 * double(i) * double(i) / 600.0;
  }
  const Periodicity p = fisher_periodicity(t, r);
  EXPECT_TRUE(p.uniform);
  EXPECT_LT(p.p, 1e-10);
  EXPECT_NEAR(p.frequency_hz, 0.7, 0.01);
  const Periodicity n = fisher_periodicity(t, white(600, 1.0, 14));
  EXPECT_GT(n.p, 1e-3);
  // A smooth misfit puts its power in the lowest ordinates: below the cycle threshold.
  const Periodicity q = fisher_periodicity(t, trend);
  EXPECT_LT(q.cycles, 5.0);
  // Non-uniform sampling: no periodogram.
  t[5] += 0.05;
  EXPECT_FALSE(fisher_periodicity(t, r).uniform);
}

TEST(Diagnostics, PhasesAndCycles) {
  std::vector<double> t, d;
  // Two cycles: ramp, hold, unload each.
  for (int c = 0; c < 2; ++c)
    for (int i = 0; i < 30; ++i) {
      t.push_back(double(t.size()));
      d.push_back(i < 10 ? i : i < 20 ? 10.0 : 30.0 - i);
    }
  const PhaseLabels pl = classify_phases(t, d, 1.0);
  EXPECT_EQ(pl.phase[5], Phase::ramp);
  EXPECT_EQ(pl.phase[15], Phase::hold);
  EXPECT_EQ(pl.phase[25], Phase::unload);
  EXPECT_EQ(pl.cycle[5], 1);
  EXPECT_EQ(pl.cycle[35], 2);
}

TEST(Diagnostics, StudyCallsNoiseNoiseAndASinusoidPeriodic) {
  SeriesView s;
  s.id = "a";
  const auto e = white(400, 0.01, 21);
  for (std::size_t i = 0; i < 400; ++i) {
    s.t.push_back(0.2 * double(i));
    s.d.push_back(i < 200 ? 1e-5 * double(i) : 2e-3);
    s.force.push_back(100.0 * s.d.back() + e[i]);
    s.residual.push_back(e[i]);
  }
  const ResidualStudy noise = study_residual({s}, 1.0, 100.0);
  EXPECT_FALSE(noise.structured);
  EXPECT_EQ(describe_signature(noise), "");
  for (std::size_t i = 0; i < 400; ++i)
    s.residual[i] += 0.02 * std::sin(2.0 * 3.14159265358979 * 0.7 * s.t[i]);
  const ResidualStudy per = study_residual({s}, 1.0, 100.0);
  EXPECT_TRUE(per.structured);
  EXPECT_NE(describe_signature(per).find("periodic at 0.7 Hz"), std::string::npos) << describe_signature(per);
}

TEST(Diagnostics, EveryDiagnosticHasAStatisticAndAThresholdEvenForATrend) {
  // A smooth misfit (a slow bow, as a baseline leaves): its largest periodogram ordinate lies below
  // five cycles, so it is not called periodic, but the report still gets the statistic.
  SeriesView s;
  s.id = "a";
  const auto e = white(300, 0.01, 5);
  for (std::size_t i = 0; i < 300; ++i) {
    s.t.push_back(0.2 * double(i));
    s.d.push_back(1e-5 * double(i));
    s.force.push_back(100.0 * s.d.back() + e[i]);
    s.residual.push_back(0.1 * std::sin(3.14159265358979 * double(i) / 300.0) + e[i]);
  }
  const ResidualStudy st = study_residual({s}, 1.0, 100.0);
  EXPECT_TRUE(st.structured);
  for (const auto& d : st.diagnostics) {
    EXPECT_TRUE(std::isfinite(d.statistic)) << d.name << ": " << d.note;
    EXPECT_FALSE(d.threshold.empty()) << d.name;
    if (d.name == "periodicity") {
      EXPECT_TRUE(d.passed) << d.note;
      EXPECT_LT(st.period.cycles, 5.0);
      EXPECT_NE(d.note.find("a trend, not a period"), std::string::npos) << d.note;
    }
  }
  EXPECT_EQ(describe_signature(st).find("periodic"), std::string::npos) << describe_signature(st);
}

}  // namespace
}  // namespace tmlab::discover
