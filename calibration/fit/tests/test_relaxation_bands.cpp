// Tests of the relaxation-time bands: the range from the data's sampling, ordered disjoint bands
// per Prony term, the refusals, and the at-bound report.
#include "calibration/fit/relaxation_bands.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tmlab::fit {
namespace {

/// A ramp of 5 samples in 1 s and a hold of 3 quadratically spaced samples to 6 s.
measured::DataSet ramp_hold() {
  measured::DataSet d;
  d.meta.name = "ramp_hold";
  measured::Test t;
  for (const double s : {0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.0 + 5.0 / 9.0, 1.0 + 20.0 / 9.0, 6.0}) {
    t.time_s.push_back(s);
    t.displacement_m.push_back(std::min(s, 1.0) * 1e-3);
    t.force_N.push_back(1.0);
  }
  d.tests.push_back(t);
  return d;
}

TEST(RelaxationBands, RangeIsAFractionOfTheShortestIntervalAndAMultipleOfTheDuration) {
  const RelaxationRange r = relaxation_range(ramp_hold(), 0.5, 1.0);
  EXPECT_NEAR(r.tau_min, 0.1, 1e-12);  // 0.5 x 0.2 s
  EXPECT_NEAR(r.tau_max, 6.0, 1e-12);
  EXPECT_NEAR(relaxation_range(ramp_hold(), 1.0, 2.0).tau_max, 12.0, 1e-12);
}

TEST(RelaxationBands, TermsGetOrderedDisjointBandsCoveringTheRange) {
  const ModelSpec spec = parse_model_spec("stvk+prony:3,poisson=0.45");
  std::vector<Parameter> p = law_parameters(spec, 4000.0, 6.0);
  // Without bands the relaxation times start in decreasing order and are bounded below by 0 only.
  EXPECT_GT(p[index_of(p, "tau1")].value, p[index_of(p, "tau2")].value);
  EXPECT_EQ(p[index_of(p, "tau1")].lower, 0.0);
  const RelaxationRange r{0.1, 100.0};
  band_relaxation_times(p, spec, r);
  EXPECT_NO_THROW(validate(p));
  const Parameter &t1 = p[index_of(p, "tau1")], &t2 = p[index_of(p, "tau2")], &t3 = p[index_of(p, "tau3")];
  EXPECT_DOUBLE_EQ(t1.lower, 0.1);
  EXPECT_NEAR(t1.upper, 1.0, 1e-12);  // three decades, one per term
  EXPECT_DOUBLE_EQ(t2.lower, t1.upper);
  EXPECT_NEAR(t2.upper, 10.0, 1e-11);
  EXPECT_DOUBLE_EQ(t3.lower, t2.upper);
  EXPECT_DOUBLE_EQ(t3.upper, 100.0);
  for (const Parameter* q : {&t1, &t2, &t3}) {
    EXPECT_NEAR(q->value, std::sqrt(q->lower * q->upper), 1e-12 * q->value) << q->name;
    EXPECT_GT(q->start_low, q->lower) << q->name;
    EXPECT_LT(q->start_high, q->upper) << q->name;
    EXPECT_EQ(q->transform(), Transform::Logit) << q->name;  // both bounds hold at every trial
  }
  // The moduli are untouched.
  EXPECT_EQ(p[index_of(p, "e1")].lower, 0.0);
}

TEST(RelaxationBands, RefusesFixedTimesAndBadRanges) {
  const ModelSpec spec = parse_model_spec("stvk+prony:2");
  std::vector<Parameter> p = law_parameters(spec, 4000.0, 6.0);
  fix(p, "tau2", 2.0);
  EXPECT_THROW(band_relaxation_times(p, spec, {0.1, 6.0}), Error);
  std::vector<Parameter> q = law_parameters(spec, 4000.0, 6.0);
  EXPECT_THROW(band_relaxation_times(q, spec, {1.0, 0.5}), Error);
  EXPECT_THROW(band_relaxation_times(q, spec, {0.0, 0.5}), Error);
  EXPECT_THROW(relaxation_range(ramp_hold(), 0.0, 1.0), Error);
  EXPECT_THROW(relaxation_range(ramp_hold(), 0.5, -1.0), Error);
  EXPECT_THROW(relaxation_range(ramp_hold(), 100.0, 1.0), Error);  // floor 20 s above the 6 s ceiling
  measured::DataSet one = ramp_hold();
  one.tests[0].time_s.resize(1);
  try {
    relaxation_range(one, 0.5, 1.0);
    ADD_FAILURE() << "a single sample has no sampling interval";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ramp_hold test 1"), std::string::npos) << e.what();
  }
  // Without Prony terms nothing changes.
  const ModelSpec el = parse_model_spec("neo_hookean");
  std::vector<Parameter> e = law_parameters(el, 4000.0, 6.0);
  const std::vector<Parameter> before = e;
  band_relaxation_times(e, el, {0.1, 6.0});
  ASSERT_EQ(e.size(), before.size());
  for (std::size_t i = 0; i < e.size(); ++i) EXPECT_EQ(e[i].lower, before[i].lower);
}

TEST(RelaxationBands, BoundReachedNamesTheEdge) {
  Parameter p;
  p.name = "tau1";
  p.lower = 0.1;
  p.upper = 1.1;
  EXPECT_EQ(bound_reached(p, 0.1005), "lower");
  EXPECT_EQ(bound_reached(p, 0.5), "");
  EXPECT_EQ(bound_reached(p, 1.0995), "upper");
  p.upper = std::numeric_limits<double>::infinity();
  EXPECT_EQ(bound_reached(p, 0.1), "");  // one-sided: no band to be at the edge of
}

}  // namespace
}  // namespace tmlab::fit
