// The forward model of discover: without effects it equals the closed forms it is built on
// (platen_state for an elastic law, Lee-Radok for a sphere under loading and hold); each effect
// changes it as its equation says (contact offset = shifted displacement, compliance satisfies
// d = d_s + c F, offsets and drifts add, the extra Prony term relaxes).
#include "calibration/discover/benchmark.hpp"
#include "calibration/discover/effects.hpp"

#include "calibration/closed_forms/homogeneous.hpp"
#include "calibration/closed_forms/indentation.hpp"
#include "calibration/fit/model_spec.hpp"
#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::discover {
namespace {

measured::DataSet ramp_platen() {
  measured::DataSet d;
  d.meta.name = "t";
  d.meta.test = measured::TestType::unconfined_compression;
  d.meta.sample.shape = measured::SampleShape::cylinder;
  d.meta.sample.radius_m = 0.01;
  d.meta.sample.height_m = 0.01;
  d.meta.sample.bottom = measured::Interface::frictionless;
  d.meta.sample.platens = measured::Interface::frictionless;
  measured::Test t;
  for (int i = 0; i <= 100; ++i) {
    t.time_s.push_back(0.1 * i);
    t.displacement_m.push_back(i <= 50 ? 4e-5 * i : 2e-3);
    t.force_N.push_back(1.0);
  }
  d.tests.push_back(t);
  return d;
}

std::vector<double> values(const std::vector<fit::Parameter>& ps) {
  std::vector<double> x;
  for (const auto& p : ps) x.push_back(p.value);
  return x;
}

TEST(Effects, ElasticPlatenEqualsTheClosedForm) {
  const Prepared p = prepare(ramp_platen(), 1000);
  Structure s;
  s.law = MaterialLaw::Yeoh;
  s.prony_terms = 0;
  auto ps = structure_parameters(s, p, 0.49, true);
  auto x = values(ps);
  x[0] = 5e3;
  x[1] = 2e3;
  x[2] = 1e3;
  const auto f = DiscoverModel(p, s).predict_series(x)[0];
  fit::ModelSpec spec;
  spec.law = MaterialLaw::Yeoh;
  const tm::Law law = fit::build_law(spec, x);
  for (std::size_t i = 1; i < f.size(); i += 10)
    EXPECT_DOUBLE_EQ(f[i], closed_forms::platen_state(law, closed_forms::PlatenTest::Unconfined, 0.01,
                                                      3.14159265358979323846e-4, p.series[0].d[i])
                               .force);
}

TEST(Effects, SphereEqualsLeeRadokUnderLoadingAndHold) {
  measured::DataSet d = ramp_platen();
  d.meta.test = measured::TestType::indentation;
  d.meta.indenter = measured::Indenter{measured::IndenterShape::sphere, 0.005, std::nullopt};
  d.meta.sample.shape = measured::SampleShape::half_space;
  d.meta.sample.platens.reset();
  // Fine steps: the exact-linear step interpolates the Hertz force linearly in time, Lee-Radok d^{3/2}.
  d.tests[0].time_s.clear();
  d.tests[0].displacement_m.clear();
  d.tests[0].force_N.clear();
  for (int i = 0; i <= 2000; ++i) {
    d.tests[0].time_s.push_back(0.005 * i);
    d.tests[0].displacement_m.push_back(i <= 1000 ? 2e-7 * i : 2e-4);
    d.tests[0].force_N.push_back(1.0);
  }
  const Prepared p = prepare(d, 100000);
  Structure s;
  auto ps = structure_parameters(s, p, 0.45, true);
  auto x = values(ps);
  x[fit::index_of(ps, "young")] = 10e3;
  x[fit::index_of(ps, "e1")] = 5e3;
  x[fit::index_of(ps, "e2")] = 3e3;
  x[fit::index_of(ps, "tau1")] = 0.3;
  x[fit::index_of(ps, "tau2")] = 3.0;
  const auto f = DiscoverModel(p, s).predict_series(x)[0];
  closed_forms::RelaxationModulus e{10e3, {5e3, 3e3}, {0.3, 3.0}};
  closed_forms::DepthHistory h{p.series[0].t, p.series[0].d};
  const auto lr = closed_forms::lee_radok_sphere(e, 0.45, 0.005, h);
  double worst = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    worst = std::max(worst, std::abs(f[i] - lr[i]));
    peak = std::max(peak, std::abs(lr[i]));
  }
  EXPECT_LT(worst, 1e-3 * peak);
}

TEST(Effects, BulkRelaxationToTheSamePoissonRatioIsTheBaselineAndOtherwiseRelaxesMore) {
  const Prepared p = prepare(ramp_platen(), 1000);
  Structure base;
  auto ps0 = structure_parameters(base, p, 0.45, true);
  auto x0 = values(ps0);
  x0[fit::index_of(ps0, "young")] = 20e3;
  x0[fit::index_of(ps0, "e1")] = 8e3;
  x0[fit::index_of(ps0, "e2")] = 4e3;
  x0[fit::index_of(ps0, "tau1")] = 0.5;
  x0[fit::index_of(ps0, "tau2")] = 3.0;
  const auto f0 = DiscoverModel(p, base).predict_series(x0)[0];
  const Structure s = with_effect(base, "separate_bulk_shear_relaxation");
  EXPECT_FALSE(not_applicable("separate_bulk_shear_relaxation", base, p).empty());  // confounded on one rig
  auto ps = structure_parameters(s, p, 0.45, true);
  auto x = values(ps);
  for (const char* n : {"young", "e1", "e2", "tau1", "tau2"})
    x[fit::index_of(ps, n)] = x0[fit::index_of(ps0, n)];
  x[fit::index_of(ps, "tau_bulk")] = 1.0;
  x[fit::index_of(ps, "drained_poisson")] = 0.45;
  auto f = DiscoverModel(p, s).predict_series(x)[0];
  for (std::size_t i = 0; i < f.size(); ++i) EXPECT_NEAR(f[i], f0[i], 1e-10 * f0[50]);
  // A drained ratio below the instantaneous one: the same force at the start of the ramp, less in the hold.
  x[fit::index_of(ps, "drained_poisson")] = 0.1;
  f = DiscoverModel(p, s).predict_series(x)[0];
  EXPECT_NEAR(f[1], f0[1], 0.05 * f0[1]);
  EXPECT_LT(f.back(), 0.95 * f0.back());
}

TEST(Effects, ExperimentEffectsDoWhatTheirEquationsSay) {
  const Prepared p = prepare(ramp_platen(), 1000);
  Structure base;
  base.prony_terms = 0;
  auto ps0 = structure_parameters(base, p, 0.45, true);
  auto x0 = values(ps0);
  x0[0] = 20e3;
  const auto f0 = DiscoverModel(p, base).predict_series(x0)[0];
  // Offsets and drift add.
  Structure s = with_effect(with_effect(base, "force_offset"), "force_drift");
  auto ps = structure_parameters(s, p, 0.45, true);
  auto x = values(ps);
  x[0] = 20e3;
  x[fit::index_of(ps, "force_offset")] = 0.1;
  x[fit::index_of(ps, "force_drift")] = 0.01;
  auto f = DiscoverModel(p, s).predict_series(x)[0];
  for (std::size_t i = 0; i < f.size(); ++i) EXPECT_NEAR(f[i], f0[i] + 0.1 + 0.01 * p.series[0].t[i], 1e-12);
  // Contact offset: the force at d is the baseline force at d - d0, zero before contact.
  s = with_effect(base, "contact_offset");
  ps = structure_parameters(s, p, 0.45, true);
  x = values(ps);
  x[0] = 20e3;
  x[fit::index_of(ps, "contact_offset")] = 4e-4;  // 10 samples of the ramp
  f = DiscoverModel(p, s).predict_series(x)[0];
  EXPECT_EQ(f[5], 0.0);
  for (std::size_t i = 10; i <= 50; ++i) EXPECT_NEAR(f[i], f0[i - 10], 1e-9 * f0[50]);
  // Compliance: the sample displacement d_s solves d = d_s + c F(d_s).
  s = with_effect(base, "instrument_compliance");
  ps = structure_parameters(s, p, 0.45, true);
  x = values(ps);
  x[0] = 20e3;
  const double c = 1e-4;
  x[fit::index_of(ps, "compliance")] = c;
  f = DiscoverModel(p, s).predict_series(x)[0];
  fit::ModelSpec spec;
  spec.law = MaterialLaw::StVK;
  const tm::Law law = fit::build_law(spec, x);
  for (std::size_t i = 5; i < f.size(); i += 7) {
    const double ds = p.series[0].d[i] - c * f[i];
    EXPECT_NEAR(closed_forms::platen_state(law, closed_forms::PlatenTest::Unconfined, 0.01,
                                           3.14159265358979323846e-4, ds)
                    .force,
                f[i], 1e-8 * f[i]);
    EXPECT_LT(f[i], f0[i]);
  }
}

TEST(Effects, PronyRelaxesInTheHoldAndTheExtraTermAddsToIt) {
  const Prepared p = prepare(ramp_platen(), 1000);
  Structure s;  // stvk + prony:2
  auto ps = structure_parameters(s, p, 0.45, true);
  auto x = values(ps);
  x[fit::index_of(ps, "young")] = 20e3;
  x[fit::index_of(ps, "e1")] = 10e3;
  x[fit::index_of(ps, "e2")] = 1.0;
  x[fit::index_of(ps, "tau1")] = 1.0;
  x[fit::index_of(ps, "tau2")] = 1.0;
  const auto f = DiscoverModel(p, s).predict_series(x)[0];
  EXPECT_GT(f[51], f[100]);  // relaxes in the hold
  // Long after the ramp: the long-term (elastic) force.
  Structure e = s;
  e.prony_terms = 0;
  const auto fe = DiscoverModel(p, e).predict_series({20e3, 0.45})[0];
  EXPECT_NEAR(f[100], fe[100], 0.01 * fe[100]);
  const Structure s3 = with_effect(s, "extra_prony_term");
  EXPECT_EQ(s3.prony_terms, 3);
  auto ps3 = structure_parameters(s3, p, 0.45, true, &s, &x);
  // The old terms are carried over; the new one starts in the widest gap.
  EXPECT_EQ(ps3[fit::index_of(ps3, "tau1")].value, 1.0);
  EXPECT_EQ(ps3[fit::index_of(ps3, "e1")].value, 10e3);
}

TEST(Effects, RelaxationTimesAreBoundedByTheLongestTest) {
  // A term that has not decayed by the end of the data is elastic stiffness, confounded with E_inf:
  // every tau is bounded by the longest test, for a baseline, an added term and values carried over.
  const Prepared p = prepare(make_set("noise_only", 1).data, 100000);
  Structure s;
  const auto ps = structure_parameters(s, p, 0.49, true);
  std::vector<double> x;
  for (const auto& q : ps) x.push_back(q.value);
  x[fit::index_of(ps, "tau2")] = 1e13;  // a previous optimum outside the range is not carried over
  const Structure s3 = with_effect(s, "extra_prony_term");
  for (const auto& v : {ps, structure_parameters(s3, p, 0.49, true, &s, &x)})
    for (const auto& q : v)
      if (q.name.rfind("tau", 0) == 0) {
        EXPECT_LE(q.upper, p.duration) << q.name;
        EXPECT_LT(q.value, q.upper) << q.name;
        EXPECT_LT(q.start_high, q.upper) << q.name;
      }
}

TEST(Effects, ADeadTermIsNotCarriedOverAndTheNewTermStartsBetweenLiveOnes) {
  // A previous optimum whose first Prony term died (tau1 -> 0, as a St VK baseline left it on the
  // benchmark's extra_prony_term set): the dead time is not carried over (a fit started there could
  // not move it, and the loop then needed two extra terms for one), and the new term starts in the
  // widest log-gap between the live terms and the data's range, not at the dead one.
  const Prepared p = prepare(make_set("noise_only", 1).data, 100000);
  Structure s;
  const auto ps = structure_parameters(s, p, 0.49, true);
  std::vector<double> x;
  for (const auto& q : ps) x.push_back(q.value);
  x[fit::index_of(ps, "e1")] = 5e3;
  x[fit::index_of(ps, "tau1")] = 1e-151;
  x[fit::index_of(ps, "tau2")] = 5.3;
  const auto& tau1 = ps[fit::index_of(ps, "tau1")];
  EXPECT_TRUE(pinned_at_bound(tau1, 1e-151));
  EXPECT_TRUE(pinned_at_bound(tau1, tau1.upper * (1.0 - 1e-9)));
  EXPECT_FALSE(pinned_at_bound(tau1, 0.5));
  EXPECT_TRUE(pinned_at_bound(ps[fit::index_of(ps, "e1")], 1e-30));
  EXPECT_FALSE(pinned_at_bound(ps[fit::index_of(ps, "e1")], 5e3));
  const Structure s3 = with_effect(s, "extra_prony_term");
  const auto ps3 = structure_parameters(s3, p, 0.49, true, &s, &x);
  const double ta = 2.0 * p.min_dt;
  EXPECT_GT(ps3[fit::index_of(ps3, "tau1")].value, ta);  // restarted inside the resolvable range
  EXPECT_EQ(ps3[fit::index_of(ps3, "e1")].value, 5e3);   // the live values are carried over
  EXPECT_EQ(ps3[fit::index_of(ps3, "tau2")].value, 5.3);
  EXPECT_NEAR(ps3[fit::index_of(ps3, "tau3")].value, std::sqrt(ta * 5.3), 1e-9);
}

TEST(Effects, ApplicabilityAndLibrary) {
  const Prepared p = prepare(ramp_platen(), 1000);
  Structure s;
  EXPECT_EQ(not_applicable("yeoh_hyperelastic", s, p), "");
  EXPECT_NE(not_applicable("finite_layer_thickness", s, p), "");
  EXPECT_NE(not_applicable("poroelastic_relaxation", s, p), "");
  EXPECT_EQ(effect_law("ogden_hyperelastic"), MaterialLaw::Ogden);
  EXPECT_FALSE(effect_law("contact_offset"));
  EXPECT_THROW(effect_info("no_such_effect"), Error);
  for (const auto& e : effect_library()) {
    EXPECT_FALSE(e.signature.empty()) << e.name;
    EXPECT_FALSE(e.change.empty()) << e.name;
  }
}

TEST(Effects, SyntheticSetsAreValidAndDiffer) {
  const SyntheticSet a = make_set("noise_only", 1), b = make_set("contact_offset", 1);
  EXPECT_EQ(a.data.tests.size(), 3u);
  EXPECT_EQ(a.kind, Truth::noise_only);
  EXPECT_EQ(b.kind, Truth::library);
  EXPECT_EQ(make_set("actuator_resonance", 1).kind, Truth::outside_library);
  // Before contact the offset set reads only noise.
  EXPECT_LT(std::abs(b.data.tests[0].force_N[1]), 0.05);
  EXPECT_TRUE(library_match("yeoh_hyperelastic", {"ogden_hyperelastic"}));
  EXPECT_FALSE(library_match("contact_offset", {"contact_offset", "force_offset"}));
}

}  // namespace
}  // namespace tmlab::discover
