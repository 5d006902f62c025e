// Tests of the fitting engine with the closed-form forward models (issue 14):
//   1. recovery as a coverage test: synthetic Lee-Radok indentation data (4 depths, 5 free
//      parameters) with Gaussian noise of 1.5 % of the peak force, 50 trials with a fixed seed,
//      multi-start from the data's own estimate; every true parameter must lie in its reported 95 %
//      interval in at least 90 % of the trials (the rates are printed).
//   2. confounding: on indentation data alone the E-nu correlation is above 0.9, the pair is named,
//      and nu is not claimed precisely.
//   and: the same answer on 1 and 2 threads; the L1 cost; a Mooney-Rivlin compression recovery.
#include "calibration/fit/fitter.hpp"
#include "calibration/fit/surrogates.hpp"
#include "calibration/fit/synthetic_data.hpp"
#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstring>
#include <iostream>
#include <random>

namespace tmlab::fit {
namespace {

/// Forces of `spec` at `truth` on the geometry of `d` (the truth given as fixed values).
std::vector<double> truth_forces(const measured::DataSet& d, const std::string& spec,
                                 const std::vector<std::pair<std::string, double>>& truth) {
  measured::DataSet tmp = d;
  for (auto& t : tmp.tests)
    for (double& f : t.force_N) f = 1.0;  // any non-zero force: only the geometry matters here
  Problem p = make_surrogate_problem(tmp, parse_model_spec(spec), truth);
  std::vector<double> x;
  for (const auto& q : p.parameters) x.push_back(q.value);
  return p.model->predict(x);
}

void add_noise(std::vector<double>& f, double fraction_of_peak, std::mt19937_64& rng) {
  double peak = 0.0;
  for (const double v : f) peak = std::max(peak, std::abs(v));
  std::normal_distribution<double> n(0.0, fraction_of_peak * peak);
  for (double& v : f) v += n(rng);
}

const ParameterResult& find(const FitResult& r, const std::string& name) {
  for (const auto& p : r.parameters)
    if (p.name == name) return p;
  throw std::runtime_error("no parameter " + name);
}

TEST(Fitter, CoverageOfThe95PercentIntervalsOnLeeRadokIndentation) {
  const std::vector<std::pair<std::string, double>> truth = {
      {"young", 3000.0}, {"e1", 2000.0}, {"e2", 1000.0}, {"tau1", 0.4}, {"tau2", 4.0}};
  const std::string spec = "stvk+prony:2,poisson=0.45";
  measured::DataSet d = synthetic::indentation_data({0.5e-3, 1e-3, 1.5e-3, 2e-3});
  const std::vector<double> clean = truth_forces(d, spec, truth);
  std::mt19937_64 rng(20261125);
  const int trials = 50;
  std::vector<int> covered(truth.size(), 0);
  long solves = 0;
  for (int trial = 0; trial < trials; ++trial) {
    std::vector<double> f = clean;
    add_noise(f, 0.015, rng);
    synthetic::set_forces(d, f);
    const Problem p = make_surrogate_problem(d, parse_model_spec(spec));
    FitOptions o;
    o.seed = 1000 + unsigned(trial);
    o.profile = false;
    const FitResult r = fit(p, o);
    solves += r.forward_solves;
    for (std::size_t k = 0; k < truth.size(); ++k) {
      const ParameterResult& q = find(r, truth[k].first);
      if (truth[k].second >= q.lower95 && truth[k].second <= q.upper95) ++covered[k];
    }
  }
  for (std::size_t k = 0; k < truth.size(); ++k) {
    const double rate = double(covered[k]) / trials;
    std::cout << "coverage " << truth[k].first << ": " << covered[k] << "/" << trials << " = " << rate
              << "\n";
    EXPECT_GE(rate, 0.9) << truth[k].first;
  }
  std::cout << "forward solves over " << trials << " fits: " << solves << "\n";
}

TEST(Fitter, IndentationAloneConfoundsYoungAndPoisson) {
  // A bonded layer 4 mm thick: the finite-layer factor depends weakly on nu, so J^T J is regular
  // but E and nu are nearly interchangeable (E/(1 - nu^2) is what the force sees).
  measured::DataSet d = synthetic::indentation_data({0.5e-3, 1e-3, 1.5e-3, 2e-3}, 5.0, 4e-3);
  std::vector<double> f = truth_forces(d, "stvk", {{"young", 5000.0}, {"poisson", 0.3}});
  std::mt19937_64 rng(7);
  add_noise(f, 0.01, rng);
  synthetic::set_forces(d, f);
  const FitResult r = fit(make_surrogate_problem(d, parse_model_spec("stvk")), FitOptions{});
  ASSERT_EQ(r.free_names.size(), 2u);
  std::cout << "layer: corr(E, nu) = " << r.correlation[0][1] << ", nu = " << find(r, "poisson").value << " ["
            << find(r, "poisson").lower95 << ", " << find(r, "poisson").upper95 << "]\n";
  EXPECT_GT(std::abs(r.correlation[0][1]), 0.9);
  ASSERT_EQ(r.confounded.size(), 1u);
  EXPECT_NE(r.confounded[0].note.find("E/(1 - nu^2)"), std::string::npos);
  // What nu information there is comes from the layer factor's (empirical) nu dependence; the
  // interval must at least contain the truth.
  const ParameterResult& nu = find(r, "poisson");
  EXPECT_LE(nu.lower95, 0.3);
  EXPECT_GE(nu.upper95, 0.3);
  EXPECT_EQ(r.profile.parameter, "poisson");

  // On a half-space Hertz sees E/(1 - nu^2) only: nu is not identifiable at all.
  measured::DataSet h = synthetic::indentation_data({0.5e-3, 1e-3, 1.5e-3, 2e-3}, 5.0);
  std::vector<double> g = truth_forces(h, "stvk", {{"young", 5000.0}, {"poisson", 0.3}});
  add_noise(g, 0.01, rng);
  synthetic::set_forces(h, g);
  const FitResult s = fit(make_surrogate_problem(h, parse_model_spec("stvk")), FitOptions{});
  std::cout << "half-space: corr(E, nu) = " << s.correlation[0][1] << "\n";
  EXPECT_GT(std::abs(s.correlation[0][1]), 0.9);
  // No precise nu is claimed: not identifiable (infinite standard error) or an interval spanning most
  // of (0, 0.5).
  const ParameterResult& snu = find(s, "poisson");
  std::cout << "half-space: nu identifiable " << snu.identifiable << ", SE " << snu.standard_error << "\n";
  EXPECT_TRUE(!snu.identifiable || snu.upper95 - snu.lower95 > 0.25);
  ASSERT_EQ(s.confounded.size(), 1u);
}

TEST(Fitter, ResultsDoNotDependOnTheThreadCount) {
  measured::DataSet d = synthetic::indentation_data({1e-3, 2e-3}, 10.0);
  std::vector<double> f =
      truth_forces(d, "stvk+prony:1,poisson=0.45", {{"young", 3000.0}, {"e1", 1500.0}, {"tau1", 1.0}});
  std::mt19937_64 rng(3);
  add_noise(f, 0.01, rng);
  synthetic::set_forces(d, f);
  const Problem p = make_surrogate_problem(d, parse_model_spec("stvk+prony:1,poisson=0.45"));
  FitOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const FitResult a = fit(p, one), b = fit(p, two);
  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  for (std::size_t i = 0; i < a.parameters.size(); ++i) {
    EXPECT_EQ(a.parameters[i].value, b.parameters[i].value);
    EXPECT_EQ(a.parameters[i].standard_error, b.parameters[i].standard_error);
  }
  EXPECT_EQ(a.forward_solves, b.forward_solves);
  EXPECT_EQ(a.sse, b.sse);
  // Geodesic acceleration reaches the same optimum.
  FitOptions g;
  g.geodesic = true;
  const FitResult c = fit(p, g);
  for (std::size_t i = 0; i < a.parameters.size(); ++i)
    EXPECT_NEAR(c.parameters[i].value, a.parameters[i].value, 1e-4 * std::abs(a.parameters[i].value))
        << a.parameters[i].name;
}

TEST(Fitter, RecoversMooneyRivlinFromCompressionWithBothCosts) {
  measured::DataSet d = synthetic::compression_data(0.5, 101);
  std::vector<double> f = truth_forces(d, "mooney_rivlin,poisson=0.49", {{"c10", 20000.0}, {"c01", 5000.0}});
  std::mt19937_64 rng(11);
  add_noise(f, 0.01, rng);
  synthetic::set_forces(d, f);
  for (const Cost c : {Cost::LeastSquares, Cost::L1}) {
    FitOptions o;
    o.cost = c;
    const FitResult r = fit(make_surrogate_problem(d, parse_model_spec("mooney_rivlin,poisson=0.49")), o);
    EXPECT_NEAR(find(r, "c10").value, 20000.0, 0.05 * 20000.0) << to_string(c);
    EXPECT_NEAR(find(r, "c01").value, 5000.0, 0.2 * 5000.0) << to_string(c);
    EXPECT_LT(r.rms_percent_peak, 1.5) << to_string(c);
    EXPECT_TRUE(find(r, "poisson").fixed);
    if (c == Cost::LeastSquares) {
      EXPECT_LE(find(r, "c10").lower95, 20000.0);
      EXPECT_GE(find(r, "c10").upper95, 20000.0);
      EXPECT_FALSE(r.profile.parameter.empty());
      EXPECT_EQ(r.profile.points.size(), 11u);
    }
  }
}

TEST(Fitter, SimulatedAnnealingIsReproducibleAndReachesTheMultiStartOptimum) {
  measured::DataSet d = synthetic::indentation_data({1e-3, 2e-3}, 10.0);
  const std::string spec = "stvk+prony:1,poisson=0.45";
  std::vector<double> f = truth_forces(d, spec, {{"young", 3000.0}, {"e1", 1500.0}, {"tau1", 1.0}});
  std::mt19937_64 rng(5);
  add_noise(f, 0.01, rng);
  synthetic::set_forces(d, f);
  const Problem p = make_surrogate_problem(d, parse_model_spec(spec));
  FitOptions ms, sa;
  sa.global = GlobalStage::Siman;
  sa.siman_evaluations = 1500;
  const FitResult a = fit(p, ms), b = fit(p, sa), c = fit(p, sa);
  EXPECT_EQ(b.global_stage, "siman");
  EXPECT_EQ(b.start_costs.size(), 2u);  // the annealed state and the start values
  EXPECT_LE(b.start_costs[0], b.start_costs[1]);
  for (std::size_t i = 0; i < a.parameters.size(); ++i) {
    EXPECT_EQ(b.parameters[i].value, c.parameters[i].value) << "same seed, same result";
    EXPECT_NEAR(b.parameters[i].value, a.parameters[i].value, 1e-4 * std::abs(a.parameters[i].value))
        << a.parameters[i].name;
  }
  EXPECT_EQ(b.forward_solves, c.forward_solves);
}

TEST(Fitter, NoiseSigmaFromSecondDifferences) {
  measured::DataSet d = synthetic::indentation_data({1e-3, 2e-3}, 20.0);
  std::vector<double> f =
      truth_forces(d, "stvk+prony:1,poisson=0.45", {{"young", 3000.0}, {"e1", 1500.0}, {"tau1", 3.0}});
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, 2e-4);
  for (double& v : f) v += n(rng);
  synthetic::set_forces(d, f);
  const Problem p = make_surrogate_problem(d, parse_model_spec("stvk"));
  EXPECT_NEAR(noise_sigma(p.data), 2e-4, 0.2 * 2e-4);
}

TEST(Fitter, AGaussianPriorRegularisesTheConfoundedPoissonRatio) {
  // Hertz on a half-space sees E/(1 - nu^2) only; a prior nu ~ N(0.45, 0.02) makes the pair
  // determined, and the report says the prior, not the data, determines nu.
  measured::DataSet h = synthetic::indentation_data({0.5e-3, 1e-3, 1.5e-3, 2e-3}, 5.0);
  std::vector<double> g = truth_forces(h, "stvk", {{"young", 5000.0}, {"poisson", 0.45}});
  std::mt19937_64 rng(9);
  add_noise(g, 0.01, rng);
  synthetic::set_forces(h, g);
  Problem p = make_surrogate_problem(h, parse_model_spec("stvk"));
  p.priors.push_back({"poisson", 0.45, 0.02});
  const FitResult r = fit(p, FitOptions{});
  const ParameterResult& nu = find(r, "poisson");
  const ParameterResult& e = find(r, "young");
  std::cout << "prior: nu = " << nu.value << " +- " << nu.standard_error << ", E = " << e.value << " +- "
            << e.standard_error << "\n";
  EXPECT_NEAR(nu.value, 0.45, 0.03);
  EXPECT_LT(nu.standard_error, 0.021);  // no more precise than the prior itself
  EXPECT_NEAR(e.value, 5000.0, 0.1 * 5000.0);
  EXPECT_GT(r.noise_sigma, 0.0);
  EXPECT_GE(r.prior_cost, 0.0);
  bool noted = false;
  for (const auto& n : r.notes)
    noted = noted || n.find("the prior, not the data, determines") != std::string::npos;
  EXPECT_TRUE(noted);
  for (const auto& c : r.confounded)
    EXPECT_NE(c.note.find("regularised it with the prior on poisson"), std::string::npos);
  // A prior on a fixed parameter or with the L1 cost is refused.
  Problem q = make_surrogate_problem(h, parse_model_spec("stvk,poisson=0.45"));
  q.priors.push_back({"poisson", 0.45, 0.02});
  EXPECT_THROW(fit(q, FitOptions{}), Error);
  FitOptions l1;
  l1.cost = Cost::L1;
  EXPECT_THROW(fit(p, l1), Error);
}

/// A forward model that records a stop request (as the SIGINT handler would) at its n-th evaluation.
class StopAtEvaluation : public ForwardModel {
 public:
  StopAtEvaluation(std::unique_ptr<ForwardModel> m, long n, std::atomic<long>& calls)
      : m_(std::move(m)), n_(n), calls_(calls) {}
  std::string name() const override { return m_->name(); }
  std::string description() const override { return m_->description(); }
  std::vector<double> predict(const std::vector<double>& x) const override {
    if (++calls_ == n_) set_pending_interrupt(SIGINT);
    return m_->predict(x);
  }

 private:
  std::unique_ptr<ForwardModel> m_;
  long n_;
  std::atomic<long>& calls_;
};

TEST(Fitter, AStopRequestEndsTheFitAtItsNextSafePoint) {
  measured::DataSet d = synthetic::compression_data(0.5, 101);
  synthetic::set_forces(d,
                        truth_forces(d, "mooney_rivlin,poisson=0.49", {{"c10", 20000.0}, {"c01", 5000.0}}));
  FitOptions o;
  o.starts = 1;
  o.local_runs = 1;
  o.threads = 1;
  // Evaluation 1 is the global stage's only start; from 2 on Levenberg-Marquardt runs inside GSL,
  // whose callbacks must not throw: the driver is ended through its error path and the fit throws
  // tmlab::Interrupted once GSL has returned.
  for (const long n : {1L, 2L, 6L}) {
    SCOPED_TRACE("stop request at evaluation " + std::to_string(n));
    Problem pr = make_surrogate_problem(d, parse_model_spec("mooney_rivlin,poisson=0.49"));
    std::atomic<long> calls{0};
    pr.model = std::make_unique<StopAtEvaluation>(std::move(pr.model), n, calls);
    try {
      (void)fit(pr, o);
      ADD_FAILURE() << "the fit ran to its end";
    } catch (const Interrupted& e) {
      EXPECT_EQ(e.signal(), SIGINT);
      EXPECT_NE(std::string(e.what()).find(n == 1 ? "global stage" : "during a local fit"), std::string::npos)
          << e.what();
    }
    // Stopped at once: at most the rest of the Jacobian being formed (2 free parameters), not the
    // rest of the Levenberg-Marquardt run.
    EXPECT_LE(calls.load(), n + 2);
    set_pending_interrupt(0);
  }
}

/// Bit-for-bit equality of two doubles (NaN equals NaN of the same bits).
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!same_bits(a[i], b[i])) return false;
  return true;
}

/// Every field of two fit results equal bit for bit, except the wall-clock time.
void expect_same_fit(const FitResult& a, const FitResult& b) {
  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  for (std::size_t i = 0; i < a.parameters.size(); ++i) {
    const ParameterResult &p = a.parameters[i], &q = b.parameters[i];
    EXPECT_EQ(p.name, q.name);
    EXPECT_TRUE(same_bits(p.value, q.value)) << p.name << " " << p.value << " vs " << q.value;
    EXPECT_TRUE(same_bits(p.standard_error, q.standard_error)) << p.name;
    EXPECT_TRUE(same_bits(p.lower95, q.lower95) && same_bits(p.upper95, q.upper95)) << p.name;
    EXPECT_EQ(p.identifiable, q.identifiable);
  }
  EXPECT_EQ(a.correlation.size(), b.correlation.size());
  for (std::size_t i = 0; i < std::min(a.correlation.size(), b.correlation.size()); ++i)
    EXPECT_TRUE(same_bits(a.correlation[i], b.correlation[i]));
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{a.cost, b.cost},
                                                                   {a.sse, b.sse},
                                                                   {a.rms, b.rms},
                                                                   {a.aic, b.aic},
                                                                   {a.bic, b.bic},
                                                                   {a.prior_cost, b.prior_cost},
                                                                   {a.profile.lower95, b.profile.lower95},
                                                                   {a.profile.upper95, b.profile.upper95}})
    EXPECT_TRUE(same_bits(x, y)) << x << " vs " << y;
  EXPECT_EQ(a.forward_solves, b.forward_solves);
  EXPECT_EQ(a.global_solves, b.global_solves);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.stop_reason, b.stop_reason);
  EXPECT_TRUE(same_bits(a.start_costs, b.start_costs));
  EXPECT_TRUE(same_bits(a.global_costs, b.global_costs));
  EXPECT_TRUE(same_bits(a.prediction, b.prediction));
  EXPECT_EQ(a.profile.parameter, b.profile.parameter);
  ASSERT_EQ(a.profile.points.size(), b.profile.points.size());
  for (std::size_t k = 0; k < a.profile.points.size(); ++k)
    EXPECT_TRUE(same_bits(a.profile.points[k].value, b.profile.points[k].value) &&
                same_bits(a.profile.points[k].sse, b.profile.points[k].sse))
        << "profile point " << k;
  EXPECT_EQ(a.profile.lower_found, b.profile.lower_found);
  EXPECT_EQ(a.notes, b.notes);
  EXPECT_EQ(a.confounded.size(), b.confounded.size());
}

/// Counts the forward model's evaluations.
class Counting : public ForwardModel {
 public:
  Counting(std::unique_ptr<ForwardModel> m, std::atomic<long>& calls) : m_(std::move(m)), calls_(calls) {}
  std::string name() const override { return m_->name(); }
  std::string description() const override { return m_->description(); }
  std::vector<double> predict(const std::vector<double>& x) const override {
    ++calls_;
    return m_->predict(x);
  }

 private:
  std::unique_ptr<ForwardModel> m_;
  std::atomic<long>& calls_;
};

TEST(Fitter, RestoredUnitsGiveTheIdenticalResult) {
  // The units an uninterrupted fit reports (global stage, each local run, each profile point), each
  // handed back as the checkpoint of a fit interrupted right after it: the resumed fit must skip
  // what was restored (fewer forward solves) and end with the identical result.
  measured::DataSet d = synthetic::compression_data(0.5, 101);
  std::vector<double> f = truth_forces(d, "mooney_rivlin,poisson=0.49", {{"c10", 20000.0}, {"c01", 5000.0}});
  std::mt19937_64 rng(11);
  add_noise(f, 0.01, rng);
  synthetic::set_forces(d, f);
  for (const GlobalStage global : {GlobalStage::MultiStart, GlobalStage::Siman}) {
    SCOPED_TRACE(to_string(global));
    FitOptions o;
    o.starts = 6;
    o.local_runs = 3;
    o.global = global;
    o.siman_evaluations = 200;
    std::vector<FitUnits> snapshots;
    o.resume.unit_finished = [&](const FitUnits& u) { snapshots.push_back(u); };
    const Problem pr = make_surrogate_problem(d, parse_model_spec("mooney_rivlin,poisson=0.49"));
    const FitResult full = fit(pr, o);
    // global stage + local runs + 10 profile points
    ASSERT_EQ(snapshots.size(), 1 + snapshots.back().local_runs.size() + 10);
    ASSERT_GE(snapshots.back().local_runs.size(), 2u);
    long previous_calls = 1L << 40;
    for (std::size_t u = 0; u < snapshots.size(); ++u) {
      SCOPED_TRACE("resumed after unit " + std::to_string(u + 1) + " of " + std::to_string(snapshots.size()));
      Problem pc = make_surrogate_problem(d, parse_model_spec("mooney_rivlin,poisson=0.49"));
      std::atomic<long> calls{0};
      pc.model = std::make_unique<Counting>(std::move(pc.model), calls);
      FitOptions r = o;
      std::size_t reported = 0;
      r.resume.restored = &snapshots[u];
      r.resume.unit_finished = [&](const FitUnits&) { ++reported; };
      expect_same_fit(fit(pc, r), full);
      EXPECT_EQ(reported, snapshots.size() - u - 1) << "only the units not restored run";
      EXPECT_LT(calls.load(), previous_calls) << "the restored units were computed again";
      previous_calls = calls.load();
    }
  }
}

/// Records a stop request at the evaluation `stop_at` holds (0: never).
class StopArmed : public ForwardModel {
 public:
  StopArmed(std::unique_ptr<ForwardModel> m, std::atomic<long>& calls, std::atomic<long>& stop_at)
      : m_(std::move(m)), calls_(calls), stop_at_(stop_at) {}
  std::string name() const override { return m_->name(); }
  std::string description() const override { return m_->description(); }
  std::vector<double> predict(const std::vector<double>& x) const override {
    if (++calls_ == stop_at_) set_pending_interrupt(SIGTERM);
    return m_->predict(x);
  }

 private:
  std::unique_ptr<ForwardModel> m_;
  std::atomic<long>& calls_;
  std::atomic<long>& stop_at_;
};

TEST(Fitter, AFitStoppedInsideAUnitResumesFromItsLastFinishedUnit) {
  // A stop request inside the second local run (a few evaluations into it): the fit ends with
  // Interrupted, the run half done is lost; resumed from the units it reported, the second run is
  // done again from its start and the fit ends with the uninterrupted result.
  measured::DataSet d = synthetic::compression_data(0.5, 101);
  synthetic::set_forces(d,
                        truth_forces(d, "mooney_rivlin,poisson=0.49", {{"c10", 20000.0}, {"c01", 5000.0}}));
  FitOptions o;
  o.starts = 4;
  o.local_runs = 2;
  o.threads = 1;
  const FitResult full = fit(make_surrogate_problem(d, parse_model_spec("mooney_rivlin,poisson=0.49")), o);
  Problem pc = make_surrogate_problem(d, parse_model_spec("mooney_rivlin,poisson=0.49"));
  std::atomic<long> calls{0}, stop_at{0};
  pc.model = std::make_unique<StopArmed>(std::move(pc.model), calls, stop_at);
  FitUnits last;
  FitOptions cut = o;
  cut.resume.unit_finished = [&](const FitUnits& u) {
    last = u;
    if (u.local_runs.size() == 1) stop_at = calls + 5;  // inside the next local run
  };
  try {
    (void)fit(pc, cut);
    ADD_FAILURE() << "the fit ran to its end";
  } catch (const Interrupted& e) {
    EXPECT_NE(std::string(e.what()).find("during a local fit"), std::string::npos) << e.what();
  }
  set_pending_interrupt(0);
  ASSERT_TRUE(last.global_done);
  ASSERT_EQ(last.local_runs.size(), 1u);
  FitOptions resumed = o;
  resumed.resume.restored = &last;
  expect_same_fit(fit(make_surrogate_problem(d, parse_model_spec("mooney_rivlin,poisson=0.49")), resumed),
                  full);
}

// Issue 26: a force of the wrong sign for its test. The data problem refuses it (the shared sign
// check); the engine itself, handed such forces anyway, must not read out of range when every
// relative standard error is NaN (the profile likelihood picked "the worst" by comparisons a NaN
// never wins, and indexed one past the free parameters).
measured::DataSet flipped_compression() {
  measured::DataSet d = synthetic::compression_data(0.3, 61);
  std::vector<double> f = truth_forces(d, "neo_hookean", {{"young", 30000.0}, {"poisson", 0.45}});
  for (double& v : f) v = -v;
  synthetic::set_forces(d, f);
  return d;
}

TEST(Fitter, AForceOfTheWrongSignIsRefusedBeforeFitting) {
  try {
    (void)make_surrogate_problem(flipped_compression(), parse_model_spec("neo_hookean"));
    FAIL() << "no refusal";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("force must be positive in compression"), std::string::npos) << m;
    EXPECT_NE(m.find("60 of 61 samples are negative"), std::string::npos) << m;
  }
}

TEST(Fitter, NaNStandardErrorsDoNotBreakTheProfileLikelihood) {
  for (const char* spec : {"stvk", "neo_hookean", "mooney_rivlin,poisson=0.49"}) {
    measured::DataSet d = flipped_compression();
    for (double& f : d.tests[0].force_N) f = -f;  // right sign for the problem's checks ...
    Problem pr = make_surrogate_problem(d, parse_model_spec(spec));
    for (double& f : pr.data.force) f = -f;  // ... then wrong for the engine
    FitOptions o;
    o.starts = 4;
    const FitResult r = fit(pr, o);
    ASSERT_FALSE(r.profile.parameter.empty()) << spec;
    EXPECT_NE(std::find(r.free_names.begin(), r.free_names.end(), r.profile.parameter), r.free_names.end())
        << spec << ": " << r.profile.parameter;
    EXPECT_EQ(r.profile.points.size(), 11u) << spec;
  }
}

TEST(Fitter, AParameterFixedTwiceOrATestWeightedTwiceIsRefusedWithBothValues) {
  measured::DataSet d = synthetic::compression_data(0.3, 31);
  synthetic::set_forces(d, truth_forces(d, "neo_hookean", {{"young", 30000.0}, {"poisson", 0.45}}));
  const auto message = [&](const std::string& spec, const std::vector<std::pair<std::string, double>>& fixes,
                           const std::vector<std::pair<std::string, double>>& weights) {
    try {
      (void)make_surrogate_problem(d, parse_model_spec(spec), fixes, weights);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::string m = message("neo_hookean,poisson=0.3", {{"poisson", 0.45}}, {});
  EXPECT_NE(m.find("'poisson' is fixed twice: 0.3 in --model 'neo_hookean,poisson=0.3' and 0.45 by --fix"),
            std::string::npos)
      << m;
  m = message("neo_hookean", {{"poisson", 0.45}, {"poisson", 0.4}}, {});
  EXPECT_NE(m.find("--fix poisson is given twice (0.45 and 0.4)"), std::string::npos) << m;
  m = message("neo_hookean", {}, {{"", 2.0}, {"", 3.0}});
  EXPECT_NE(m.find("--weight names test '' twice (2 and 3)"), std::string::npos) << m;
  EXPECT_EQ(message("neo_hookean,poisson=0.3", {{"young", 30000.0}}, {{"", 2.0}}), "");
}

TEST(Fitter, TwoPriorsOnOneParameterAreRefused) {
  measured::DataSet d = synthetic::compression_data(0.3, 31);
  synthetic::set_forces(d, truth_forces(d, "neo_hookean", {{"young", 30000.0}, {"poisson", 0.45}}));
  Problem pr = make_surrogate_problem(d, parse_model_spec("neo_hookean"));
  pr.noise_sigma = 0.01;
  pr.priors = {{"poisson", 0.45, 0.02}, {"young", 3e4, 1e3}};
  EXPECT_NO_THROW(check_priors(pr));
  pr.priors.push_back({"poisson", 0.4, 0.05});
  try {
    check_priors(pr);
    FAIL() << "no refusal";
  } catch (const Error& e) {
    EXPECT_NE(
        std::string(e.what()).find("two priors on 'poisson' (mean 0.45, sd 0.02 and mean 0.4, sd 0.05)"),
        std::string::npos)
        << e.what();
  }
  EXPECT_THROW(fit(pr, FitOptions{}), Error);
}

TEST(Fitter, TheLocalRunsThatRanAreCounted) {
  measured::DataSet d = synthetic::compression_data(0.3, 31);
  synthetic::set_forces(d, truth_forces(d, "neo_hookean", {{"young", 30000.0}, {"poisson", 0.45}}));
  FitOptions o;
  o.starts = 3;
  o.local_runs = 100;
  o.profile = false;
  EXPECT_EQ(fit(make_surrogate_problem(d, parse_model_spec("neo_hookean")), o).local_runs, 3);
  o.local_runs = 2;
  EXPECT_EQ(fit(make_surrogate_problem(d, parse_model_spec("neo_hookean")), o).local_runs, 2);
}

}  // namespace
}  // namespace tmlab::fit
