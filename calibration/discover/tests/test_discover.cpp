// The loop end to end on noise-only data (adds nothing, claims no structure, report.json has the
// keys of the issue) and the held-out folds. Effects present and outside the library: the quick
// benchmark (test_benchmark.cpp).
#include "calibration/discover/benchmark.hpp"
#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace tmlab::discover {
namespace {

TEST(Discover, NoiseOnlyAddsNothing) {
  Options o;
  const Report r = run(make_set("noise_only", 1).data, o);
  EXPECT_TRUE(r.selected.empty());
  EXPECT_FALSE(r.unexplained);
  EXPECT_EQ(r.signature, "");
  const auto j = to_json(r);
  for (const char* k : {"dataset", "baseline", "steps", "selected_effects", "final", "unexplained_structure",
                        "unexplained_signature"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_TRUE(j["baseline"].contains("rel_rms"));
  EXPECT_FALSE(j.contains("discretisation_gate"));  // no gate without --forward fe_rig
}

TEST(Discover, LawSwappedInFromTheFittedBaselineReachesTheNoise) {
  // The benchmark's Yeoh set (bench-yeoh_hyperelastic-4): the Yeoh candidate, started from the
  // fitted St VK baseline as the loop starts it, must fit to the noise (0.3 % of the peak force):
  // the data are Yeoh with the baseline's two Prony terms. Before the relaxation times were bounded
  // by the longest test, the baseline put its stiffness into a term at tau ~ 1e13 s with E_inf ~
  // 0.01 Pa, the Yeoh fit started at that E_inf and stopped at RMS 0.27 N (8 x the noise), and a
  // later extra_prony_term absorbed the rest.
  Options o;
  const Prepared p = prepare(make_set("yeoh_hyperelastic", 4).data, o.max_samples);
  Structure base;
  const Fitted b = fit_structure(p, base, structure_parameters(base, p, o.poisson, true), o, 3 * o.starts);
  for (std::size_t i = 0; i < b.parameters.size(); ++i) {
    if (b.parameters[i].name.rfind("tau", 0) == 0) {
      EXPECT_LE(b.x[i], p.duration) << b.parameters[i].name;
    }
  }
  const Structure yeoh = with_effect(base, "yeoh_hyperelastic");
  const Fitted y =
      fit_structure(p, yeoh, structure_parameters(yeoh, p, o.poisson, true, &base, &b.x), o, o.starts);
  EXPECT_LT(y.fit.rms, 1.1 * 0.003 * p.peak_force);
  EXPECT_FALSE(y.study.structured);
}

TEST(Discover, AGainTheCurrentModelReachesItselfIsNotCreditedToTheEffect) {
  // The benchmark's unconfined extra_prony_term set (bench-extra_prony_term-1). The baseline's
  // multi-start stops at RMS 0.029 N; the same two-term model re-fitted from the three-term
  // candidate's optimum reaches 0.0084 N. Before the refit check, how much of a candidate's gain
  // was the optimizer's depended on the last bits of the BLAS under GSL: through `tmlab` (netlib
  // BLAS) the three-term fit stopped at 0.0074 N and force_drift was accepted after it in round 2
  // (its gain, 0.0074 -> 0.0070 N, was the three-term model's own optimum). Now each gain is
  // measured against the current model re-fitted from the candidate's optimum: the error before is
  // the better baseline optimum, and exactly the planted term is found.
  Options o;
  const Report r = run(make_set("extra_prony_term", 1).data, o);
  ASSERT_EQ(r.final_effects.size(), 1u);
  EXPECT_EQ(r.final_effects[0], "extra_prony_term");
  EXPECT_FALSE(r.unexplained);
  EXPECT_LT(r.baseline.fit.rms, 0.5 * 0.02927);  // the re-fitted baseline, not the first multi-start
  EXPECT_LT(r.final.fit.rms, 1.1 * 0.003 * r.data.peak_force);
  bool checked = false;
  for (const auto& st : r.steps) checked |= std::isfinite(st.current_refit_rms);
  EXPECT_TRUE(checked);
  EXPECT_EQ(to_json(r)["steps"][0]["criterion"].count("current_refit_from_candidate_rms_N"), 1u);
}

TEST(Discover, TheDiscretisationGateComparesTheRmsImprovementWithTheRigsChange) {
  EXPECT_DOUBLE_EQ(rms_improvement(5.0, 3.0), 4.0);
  EXPECT_EQ(rms_improvement(3.0, 5.0), 0.0);  // a worse candidate improves nothing
  DiscretisationGate g;
  EXPECT_FALSE(stands_in_for_discretisation(g, 5.0, 0.0));  // not applied: no gate
  g.applied = true;
  g.change_rms = 1.0;
  g.factor = 2.0;
  EXPECT_FALSE(stands_in_for_discretisation(g, 5.0, 3.0));  // 4 > 2 x 1
  EXPECT_TRUE(stands_in_for_discretisation(g, 5.0, 4.8));   // sqrt(25 - 23.04) = 1.4 <= 2
  EXPECT_EQ(discretisation_reason(g, 5.0, 4.8).rfind("stands in for discretisation error", 0), 0u);
}

TEST(Discover, AnEffectWhoseGainTheRigsDiscretisationCouldMakeIsNotAccepted) {
  // The set of AGainTheCurrentModelReachesItselfIsNotCreditedToTheEffect, where extra_prony_term is
  // accepted. A gate whose discretisation change is the baseline's own RMS: no candidate can improve
  // the RMS by more than the current RMS (<= the baseline's), so by 2 x that none can, and each that
  // passes BIC is refused with the reason.
  Options o;
  int calls = 0;
  o.discretisation = [&calls](const Prepared&, const Fitted& baseline) {
    ++calls;
    DiscretisationGate g;
    g.applied = true;
    g.change_rms = baseline.fit.rms;
    g.rig = "coarse";
    g.refined_rig = "fine";
    return g;
  };
  const Report r = run(make_set("extra_prony_term", 1).data, o);
  EXPECT_EQ(calls, 1);
  EXPECT_TRUE(r.selected.empty());
  bool refused = false;
  for (const auto& st : r.steps)
    if (st.reason.rfind("stands in for discretisation error", 0) == 0) {
      refused = true;
      EXPECT_FALSE(st.accepted);
      EXPECT_LE(st.improvement_rms, 2.0 * r.discretisation.change_rms);
    }
  EXPECT_TRUE(refused);
  const auto j = to_json(r);
  ASSERT_TRUE(j.contains("discretisation_gate"));
  EXPECT_TRUE(j["discretisation_gate"]["applied"].get<bool>());
  EXPECT_EQ(j["discretisation_gate"]["factor"].get<double>(), 2.0);
  EXPECT_NE(j["selection_rule"].get<std::string>().find("discretisation"), std::string::npos);
  EXPECT_EQ(j["steps"][0]["criterion"].count("improvement_rms_N"), 1u);
}

TEST(Discover, BackwardStepRemovesAnEffectThatNoLongerEarnsItsPlace) {
  // Data with a contact offset only. A model that carries a force offset as well (as if a force
  // offset had been accepted in an earlier round, before the contact offset explained the toe):
  // after the contact offset's acceptance the backward step must take the force offset out again.
  Options o;
  const Prepared p = prepare(make_set("contact_offset", 1).data, o.max_samples);
  Structure base;
  Structure both = with_effect(with_effect(base, "force_offset"), "contact_offset");
  Fitted cur = fit_structure(p, both, structure_parameters(both, p, o.poisson, true), o, o.starts);
  std::vector<Step> steps;
  const auto removed = backward_step(p, base, cur, "contact_offset", 2, o, steps);
  ASSERT_EQ(removed.size(), 1u);
  EXPECT_EQ(removed[0], "force_offset");
  EXPECT_FALSE(cur.structure.has("force_offset"));
  EXPECT_TRUE(cur.structure.has("contact_offset"));
  ASSERT_EQ(steps.size(), 1u);
  EXPECT_TRUE(steps[0].removal);
  EXPECT_TRUE(steps[0].accepted);
  EXPECT_LT(steps[0].delta_bic, 0.0);  // BIC falls without it: it never paid for its parameter
  // An effect that is present is kept: with a force drift just added, the contact offset stays.
  Structure drift = with_effect(with_effect(base, "contact_offset"), "force_drift");
  Fitted cur2 = fit_structure(p, drift, structure_parameters(drift, p, o.poisson, true), o, o.starts);
  std::vector<Step> steps2;
  EXPECT_TRUE(backward_step(p, base, cur2, "force_drift", 2, o, steps2).empty());
  ASSERT_EQ(steps2.size(), 1u);
  EXPECT_EQ(steps2[0].effect, "contact_offset");
  EXPECT_FALSE(steps2[0].accepted);
  EXPECT_TRUE(cur2.structure.has("contact_offset"));
}

TEST(Discover, TestScaleControlRecoversAFactorPerTest) {
  // A "model" whose forces are the data's divided by a factor per test: the control's least-squares
  // factors are those factors and its residual vanishes; with one test it does not apply.
  Options o;
  const Prepared p = prepare(make_set("noise_only", 1).data, o.max_samples);
  ASSERT_EQ(p.series.size(), 3u);
  const std::vector<double> factor = {1.15, 1.0, 0.9};
  Fitted f;
  f.fit.k = 5;
  for (std::size_t k = 0; k < p.series.size(); ++k) {
    f.prediction.emplace_back();
    for (const double y : p.series[k].f) f.prediction.back().push_back(y / factor[k]);
  }
  const TestScaleControl c = test_scale_control(p, f);
  ASSERT_TRUE(c.applicable);
  ASSERT_EQ(c.scale.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(c.scale[k], factor[k], 1e-12) << k;
  EXPECT_LT(c.rms, 1e-12 * p.peak_force);
  EXPECT_EQ(c.free_parameters, 8u);
  measured::DataSet single = make_set("noise_only", 1).data;
  single.tests.resize(1);
  const Prepared p1 = prepare(single, o.max_samples);
  Fitted f1;
  f1.prediction = {p1.series[0].f};
  EXPECT_FALSE(test_scale_control(p1, f1).applicable);
}

TEST(Discover, ADifferenceBetweenTestsIsFlaggedNotForced) {
  // The benchmark's preconditioning set (the first test's force 15 % higher, outside the library).
  // Two shared effects that each pass BIC and held-out prediction on it (measured: force_drift's BIC
  // falls by 113 and its held-out RMS from 0.159 to 0.149 N): without the test-consistency control
  // the loop adds one; with it, nothing, and the structure is reported as a difference between tests.
  Options o;
  o.effects = {"force_drift", "strain_dependent_relaxation"};
  o.max_rounds = 1;
  const measured::DataSet d = make_set("preconditioning", 19).data;
  Options off = o;
  off.test_control = false;
  const Report forced = run(d, off);
  EXPECT_FALSE(forced.selected.empty());  // what the control prevents
  // With the effect forced, the final residual is still mostly a difference between the tests,
  // and the signature says so.
  EXPECT_TRUE(forced.unexplained);
  EXPECT_GE(forced.control.explained_share, 0.5);
  EXPECT_NE(forced.signature.find("would explain"), std::string::npos) << forced.signature;
  const Report r = run(d, o);
  EXPECT_TRUE(r.selected.empty());
  EXPECT_TRUE(r.unexplained);
  EXPECT_TRUE(r.control.decided);
  EXPECT_NE(r.signature.find("tests inconsistent"), std::string::npos) << r.signature;
  ASSERT_EQ(r.control.scale.size(), 3u);
  // The first test stands out, by about the planted 15 % relative to the others.
  EXPECT_NEAR(r.control.scale[0] / r.control.scale[1], 1.15, 0.02);
  EXPECT_EQ(to_json(r)["test_consistency_control"]["decided"], true);
}

TEST(Discover, ANoiseLikeOrPeriodicResidualIsNotCalledADifferenceBetweenTests) {
  // The resonance set: structure remains (periodic), but a factor per test explains none of it.
  Options o;
  const Report r = run(make_set("actuator_resonance", 18).data, o);
  EXPECT_TRUE(r.unexplained);
  EXPECT_TRUE(r.control.applicable);
  EXPECT_FALSE(r.control.decided);
  EXPECT_LT(r.control.explained_share, 0.05);
  EXPECT_EQ(r.signature.find("tests inconsistent"), std::string::npos) << r.signature;
  // Noise only: nothing to explain, so no share.
  const Report n = run(make_set("noise_only", 15).data, o);
  EXPECT_FALSE(n.unexplained);
  EXPECT_EQ(n.signature, "");
}

TEST(Discover, WithoutEffectUndoesWithEffect) {
  Structure base;
  for (const char* e : {"extra_prony_term", "yeoh_hyperelastic", "force_drift"}) {
    const Structure s = with_effect(with_effect(base, "contact_offset"), e);
    const Structure back = without_effect(s, e, base);
    EXPECT_EQ(back.label(), with_effect(base, "contact_offset").label()) << e;
  }
  EXPECT_THROW(without_effect(base, "force_drift", base), Error);
  EXPECT_THROW(without_effect(base, "extra_prony_term", base), Error);
}

TEST(Discover, ProgressSaysWhichSamplesAreKept) {
  EXPECT_EQ(stride_text(1), "all samples kept");
  EXPECT_EQ(stride_text(2), "every 2nd sample kept");
  EXPECT_EQ(stride_text(3), "every 3rd sample kept");
  EXPECT_EQ(stride_text(4), "every 4th sample kept");
  EXPECT_EQ(stride_text(11), "every 11th sample kept");
  EXPECT_EQ(stride_text(21), "every 21st sample kept");
}

TEST(Discover, HeldOutFoldsCoverEverySampleOnce) {
  const Prepared one = prepare(make_set("noise_only", 1).data, 100000);
  const auto folds = held_out_folds(one);
  ASSERT_EQ(folds.size(), 3u);  // three tests: one left out per fold
  for (std::size_t i = 0; i < one.size(); ++i) {
    int out = 0;
    for (const auto& f : folds) out += f[i] ? 0 : 1;
    EXPECT_EQ(out, 1) << i;
  }
  measured::DataSet single = make_set("noise_only", 1).data;
  single.tests.resize(1);
  const Prepared p1 = prepare(single, 100000);
  const auto f1 = held_out_folds(p1);
  ASSERT_EQ(f1.size(), 2u);  // even and odd time blocks
  for (std::size_t i = 0; i < p1.size(); ++i) EXPECT_NE(f1[0][i], f1[1][i]);
}

/// One noise-free ramp (issue 26): the first test of the benchmark's unconfined protocol, cut at
/// the end of its loading ramp (12.5 s), its forces those of the baseline's law and Prony terms at
/// the benchmark's values (St VK, E_inf 30 kPa, nu 0.49, e 12 and 8 kPa, tau 0.5 and 15 s) without
/// noise. tau2 lies beyond the longest test, where the baseline's relaxation times are bounded, so
/// the baseline fits it to 5e-5 of the peak force, not exactly: a smooth residual with no noise.
measured::DataSet noise_free_ramp() {
  measured::DataSet d = make_set("noise_only", 1).data;
  d.meta.name = "noise_free_ramp";
  d.tests.resize(1);
  measured::Test& t = d.tests[0];
  std::size_t end = 1;
  while (end < t.size() && t.displacement_m[end] > t.displacement_m[end - 1]) ++end;
  t.time_s.resize(end);
  t.displacement_m.resize(end);
  t.force_N.resize(end);
  const Prepared p = prepare(d, 1u << 30);
  const Structure base;
  std::vector<fit::Parameter> ps = structure_parameters(base, p, 0.49, true);
  std::vector<double> x;
  for (const auto& q : ps) x.push_back(q.value);
  for (const auto& [n, v] : std::vector<std::pair<std::string, double>>{
           {"young", 30e3}, {"e1", 12e3}, {"e2", 8e3}, {"tau1", 0.5}, {"tau2", 15.0}})
    x[fit::index_of(ps, n)] = v;
  t.force_N = DiscoverModel(p, base).predict_series(x)[0];
  return d;
}

TEST(Discover, ANoiseFreeRampSelectsNothing) {
  // Before: force_drift accepted (BIC -241, held-out RMS 3.3e-4 -> 3.0e-5 N), then
  // strain_dependent_relaxation tried: with no noise, the BIC's noise scale is the residual itself,
  // so any candidate that bends the curve toward a smooth residual is "very strong" evidence.
  Options o;
  const Report r = run(noise_free_ramp(), o);
  std::string steps;
  for (const auto& s : r.steps) steps += s.effect + (s.accepted ? " accepted: " : ": ") + s.reason + "\n";
  EXPECT_TRUE(r.selected.empty()) << steps;
  EXPECT_TRUE(r.steps.empty()) << steps;
  EXPECT_LT(r.baseline.fit.rms, 0.5 * r.baseline.study.noise_sigma);
  EXPECT_NE(r.stop_reason.find("below 0.5 x the data's noise level"), std::string::npos) << r.stop_reason;
  std::cout << "noise-free ramp: baseline RMS " << r.baseline.fit.rms << " N, noise level "
            << r.baseline.study.noise_sigma << " N\n";
  // The same ramp with the benchmark's noise (0.3 % of the peak force): the baseline's residual is
  // the noise, well above half the noise level, so the rule leaves noisy data alone.
  measured::DataSet noisy = noise_free_ramp();
  std::mt19937_64 rng(7);
  double peak = 0.0;
  for (const double f : noisy.tests[0].force_N) peak = std::max(peak, std::abs(f));
  std::normal_distribution<double> n(0.0, 0.003 * peak);
  for (double& f : noisy.tests[0].force_N) f += n(rng);
  const Prepared p = prepare(noisy, o.max_samples);
  const Structure base;
  const Fitted b = fit_structure(p, base, structure_parameters(base, p, o.poisson, true), o, 3 * o.starts);
  EXPECT_GT(b.fit.rms, 0.8 * b.study.noise_sigma) << b.fit.rms << " " << b.study.noise_sigma;
}

TEST(Discover, AnExactLinearRampSelectsNothing) {
  // The hostile probe's case (issue 26): a cylinder compressed to 10 % along an exactly linear curve,
  // written to 9 digits. Its noise level is round-off and the St VK baseline's residual is far above
  // it, so the residual rule above does not fire; before, force_drift was accepted (time is
  // proportional to displacement on one ramp, so a drift stands in for the missing law).
  measured::DataSet d;
  d.meta.name = "linear_ramp";
  d.meta.test = measured::TestType::unconfined_compression;
  d.meta.sample.shape = measured::SampleShape::cylinder;
  d.meta.sample.radius_m = 0.025;
  d.meta.sample.height_m = 0.03;
  d.meta.sample.platens = measured::Interface::frictionless;
  measured::Test t;
  const double area = 3.141592653589793 * 0.025 * 0.025;
  for (int i = 0; i < 40; ++i) {
    const double u = 0.003 * i / 39.0;
    t.time_s.push_back(0.45 * i);
    t.displacement_m.push_back(u);
    t.force_N.push_back(20000.0 * area * u / 0.03);
  }
  d.tests.push_back(t);
  Options o;
  const Report r = run(d, o);
  std::string steps;
  for (const auto& s : r.steps) steps += s.effect + (s.accepted ? " accepted: " : ": ") + s.reason + "\n";
  EXPECT_TRUE(r.selected.empty()) << steps << r.stop_reason;
  EXPECT_NE(r.stop_reason.find("no measurable noise"), std::string::npos) << r.stop_reason;
}

}  // namespace
}  // namespace tmlab::discover
