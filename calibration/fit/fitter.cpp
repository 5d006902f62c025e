// The fitting engine (fitter.hpp has the method and the equations).
#include "calibration/fit/fitter.hpp"

#include "calibration/fit/model_spec.hpp"

#include "calibration/fit/parallel.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/interrupt.hpp"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_rng.h>
#include <gsl/gsl_siman.h>
#include <Eigen/Dense>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <tuple>

namespace tmlab::fit {

std::string to_string(Cost c) { return c == Cost::L1 ? "l1" : "least_squares"; }
std::string to_string(GlobalStage g) { return g == GlobalStage::Siman ? "siman" : "multistart"; }

double noise_sigma(const Observations& d) {
  std::vector<double> a;
  for (std::size_t i = 1; i + 1 < d.size(); ++i)
    if (d.test[i - 1] == d.test[i] && d.test[i + 1] == d.test[i])
      a.push_back(std::abs(d.force[i + 1] - 2.0 * d.force[i] + d.force[i - 1]));
  if (a.empty()) return 0.0;
  std::nth_element(a.begin(), a.begin() + long(a.size() / 2), a.end());
  return a[a.size() / 2] / (0.6744897501960817 * std::sqrt(6.0));
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The local stage's stop reasons when GSL reports success (converged_stop).
const char* const kStopXtol = "small step (xtol)";
const char* const kStopGtol = "small gradient (gtol)";
const char* const kStopConverged = "converged";

/// Residuals of a subset of free parameters (internal coordinates) with the others held.
struct Evaluator {
  const Problem* problem = nullptr;
  const ForwardModel* model = nullptr;  ///< the problem's model, or its global-stage surrogate
  Cost cost = Cost::LeastSquares;
  /// Priors: (parameter index, mean, sd) and the force scale sigma of their residuals.
  std::vector<std::tuple<std::size_t, double, double>> priors;
  double sigma = 0.0;
  std::vector<std::size_t> free;  ///< indices into problem->parameters
  std::vector<double> held;       ///< physical values of every parameter (the free ones overwritten)
  double delta = 0.0;             ///< L1 smoothing
  std::atomic<long>* solves = nullptr;
  bool warm = false;  ///< Jacobian columns start from the base point's solver state (FitOptions)

  std::size_t n_data() const { return problem->data.size(); }
  std::size_t n() const { return problem->data.size() + priors.size(); }
  std::size_t p() const { return free.size(); }

  std::vector<double> physical(const double* t) const {
    std::vector<double> x = held;
    for (std::size_t j = 0; j < free.size(); ++j) x[free[j]] = problem->parameters[free[j]].to_physical(t[j]);
    return x;
  }
  /// Weighted force errors w (model - data); false when the model cannot be evaluated. With `warm`,
  /// the model starts from `from` and keeps its state in *keep (ForwardModel::predict_warm).
  bool errors(const double* t, std::vector<double>& e, std::vector<double>* prediction = nullptr,
              const WarmStart* from = nullptr, std::shared_ptr<const WarmStart>* keep = nullptr) const {
    const std::vector<double> x = physical(t);
    std::vector<double> f;
    ++*solves;
    try {
      f = warm ? model->predict_warm(x, from, keep) : model->predict(x);
    } catch (const Error&) {
      return false;
    }
    const Observations& d = problem->data;
    if (f.size() != d.size()) throw Error("fit: the forward model returned the wrong number of forces");
    e.resize(n());
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (!std::isfinite(f[i])) return false;
      e[i] = d.weights[d.test[i]] * (f[i] - d.force[i]);
    }
    for (std::size_t k = 0; k < priors.size(); ++k) {
      const auto& [i, mean, sd] = priors[k];
      e[d.size() + k] = sigma * (x[i] - mean) / sd;
    }
    if (prediction) *prediction = std::move(f);
    return true;
  }
  /// The residuals the optimiser squares (e for least squares, e / sqrt(|e| + delta) for L1).
  void to_residuals(std::vector<double>& e) const {
    if (cost == Cost::L1)
      for (std::size_t i = 0; i < n_data(); ++i) e[i] = e[i] / std::sqrt(std::abs(e[i]) + delta);
  }
  double cost_of(const std::vector<double>& e) const {
    double c = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i)
      c += cost == Cost::L1 && i < n_data() ? std::abs(e[i]) : e[i] * e[i];
    return c;
  }
  /// The forward-difference step of the Jacobian in internal coordinate t.
  double jacobian_step(double t) const { return model->jacobian_step() * std::max(1.0, std::abs(t)); }
  /// The residual vector used for a failed evaluation: large, so the trial step is rejected.
  double failure_value() const { return 1e6 * (problem->data.peak_force + 1.0); }
};

struct Local {
  std::vector<double> t;
  double cost = kInf;
  int iterations = 0;
  std::string reason;
};

struct GslData {
  const Evaluator* ev = nullptr;
  int threads = 1;
  std::vector<double> last_t, last_r;
  bool last_ok = false;
  std::shared_ptr<const WarmStart> last_state;  ///< the solver state of last_t (warm Jacobian columns)
  /// The solver state of the point of the last Jacobian (the trust region's centre), from which the
  /// trial points' solves start.
  std::shared_ptr<const WarmStart> centre_state;
  const FitOptions* options = nullptr;
  bool report = false;
};

int gsl_f(const gsl_vector* x, void* params, gsl_vector* f) {
  // A stop request (SIGINT/SIGTERM) ends the GSL driver through its error path: no exception may
  // cross GSL's C frames. local_fit turns it into tmlab::Interrupted once the driver has returned.
  if (pending_interrupt() != 0) return GSL_EBADFUNC;
  auto* g = static_cast<GslData*>(params);
  const Evaluator& ev = *g->ev;
  std::vector<double> t(x->data, x->data + ev.p()), e;
  for (std::size_t j = 0; j < ev.p(); ++j) t[j] = gsl_vector_get(x, j);
  std::shared_ptr<const WarmStart> state;
  const bool ok = ev.errors(t.data(), e, nullptr, g->centre_state.get(), &state);
  if (ok) ev.to_residuals(e);
  for (std::size_t i = 0; i < ev.n(); ++i) gsl_vector_set(f, i, ok ? e[i] : ev.failure_value());
  g->last_state = ok ? std::move(state) : nullptr;
  g->last_t = t;
  g->last_r = ok ? e : std::vector<double>(ev.n(), ev.failure_value());
  g->last_ok = ok;
  return GSL_SUCCESS;
}

/// Forward-difference Jacobian in the internal coordinates, one column per forward solve, the
/// columns in parallel, each started from the base point's solver state (warm: a step of 1e-6 moves
/// the solution little, so the column's solve needs a few iterations instead of a cold start's).
int gsl_df(const gsl_vector* x, void* params, gsl_matrix* J) {
  if (pending_interrupt() != 0) return GSL_EBADFUNC;  // as gsl_f
  auto* g = static_cast<GslData*>(params);
  const Evaluator& ev = *g->ev;
  std::vector<double> t(ev.p());
  for (std::size_t j = 0; j < ev.p(); ++j) t[j] = gsl_vector_get(x, j);
  if (t != g->last_t) {
    gsl_vector* f = gsl_vector_alloc(ev.n());
    gsl_f(x, params, f);
    gsl_vector_free(f);
  }
  const std::vector<double> r0 = g->last_r;
  g->centre_state = g->last_state;
  const WarmStart* base = g->last_state.get();
  std::vector<std::vector<double>> cols(ev.p());
  parallel_for(ev.p(), g->threads, [&](std::size_t j) {
    std::vector<double> tj = t, e;
    double h = ev.jacobian_step(t[j]);
    tj[j] += h;
    if (!ev.errors(tj.data(), e, nullptr, base)) {
      tj[j] = t[j] - h;
      h = -h;
      if (!ev.errors(tj.data(), e, nullptr, base)) {
        cols[j].assign(ev.n(), 0.0);
        return;
      }
    }
    ev.to_residuals(e);
    cols[j].resize(ev.n());
    for (std::size_t i = 0; i < ev.n(); ++i) cols[j][i] = (e[i] - r0[i]) / h;
  });
  for (std::size_t j = 0; j < ev.p(); ++j)
    for (std::size_t i = 0; i < ev.n(); ++i) gsl_matrix_set(J, i, j, cols[j][i]);
  return GSL_SUCCESS;
}

/// Standard errors (physical) from J (n x p, internal) and the residuals: s^2 (J^T J)^{-1}.
std::vector<double> quick_standard_errors(const Evaluator& ev, const gsl_matrix* J, const gsl_vector* f,
                                          const std::vector<double>& t) {
  const std::size_t n = J->size1, p = J->size2;
  std::vector<double> se(p, kInf);
  if (n <= p) return se;
  gsl_matrix* cov = gsl_matrix_alloc(p, p);
  gsl_multifit_nlinear_covar(J, 0.0, cov);
  double ss = 0.0;
  for (std::size_t i = 0; i < n; ++i) ss += gsl_vector_get(f, i) * gsl_vector_get(f, i);
  const double s2 = ss / double(n - p);
  for (std::size_t j = 0; j < p; ++j) {
    const double v = gsl_matrix_get(cov, j, j) * s2;
    se[j] = v >= 0 ? std::sqrt(v) * std::abs(ev.problem->parameters[ev.free[j]].derivative(t[j])) : kInf;
  }
  gsl_matrix_free(cov);
  return se;
}

void gsl_callback(const size_t iter, void* params, const gsl_multifit_nlinear_workspace* w) {
  auto* g = static_cast<GslData*>(params);
  if (!g->report || !g->options->progress) return;
  const Evaluator& ev = *g->ev;
  const gsl_vector* x = gsl_multifit_nlinear_position(w);
  std::vector<double> t;
  for (std::size_t j = 0; j < ev.p(); ++j) t.push_back(gsl_vector_get(x, j));
  const gsl_vector* f = gsl_multifit_nlinear_residual(w);
  double c = 0.0;
  for (std::size_t i = 0; i < ev.n(); ++i) c += gsl_vector_get(f, i) * gsl_vector_get(f, i);
  const std::vector<double> se = quick_standard_errors(ev, gsl_multifit_nlinear_jac(w), f, t);
  const std::vector<double> xp = ev.physical(t.data());
  std::string line = "  iter " + std::to_string(iter) + "  cost " + significant(c, 5) + "  SE:";
  for (std::size_t j = 0; j < ev.p(); ++j) {
    const double v = xp[ev.free[j]];
    line += " " + ev.problem->parameters[ev.free[j]].name + " " +
            (std::isfinite(se[j]) && v != 0.0 ? significant(100.0 * se[j] / std::abs(v), 3) + "%" : "inf");
  }
  g->options->progress(line);
}

Local local_fit(const Evaluator& ev, const std::vector<double>& t0, const FitOptions& opt, bool report) {
  GslData g;
  g.ev = &ev;
  g.threads = opt.threads;
  g.options = &opt;
  g.report = report;
  gsl_multifit_nlinear_fdf fdf;
  fdf.f = gsl_f;
  fdf.df = gsl_df;
  fdf.fvv = nullptr;  // geodesic acceleration: GSL's finite-difference second directional derivative
  fdf.n = ev.n();
  fdf.p = ev.p();
  fdf.params = &g;
  gsl_multifit_nlinear_parameters params = gsl_multifit_nlinear_default_parameters();
  params.trs = opt.geodesic ? gsl_multifit_nlinear_trs_lmaccel : gsl_multifit_nlinear_trs_lm;
  params.scale = gsl_multifit_nlinear_scale_more;
  gsl_multifit_nlinear_workspace* w =
      gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &params, ev.n(), ev.p());
  gsl_vector* x = gsl_vector_alloc(ev.p());
  for (std::size_t j = 0; j < ev.p(); ++j) gsl_vector_set(x, j, t0[j]);
  gsl_multifit_nlinear_init(x, &fdf, w);
  int info = 0;
  const int status = gsl_multifit_nlinear_driver(std::size_t(opt.max_iterations), opt.xtol, 1e-9, 1e-12,
                                                 gsl_callback, &g, &info, w);
  if (pending_interrupt() != 0) {
    const std::string at = std::to_string(gsl_multifit_nlinear_niter(w));
    gsl_vector_free(x);
    gsl_multifit_nlinear_free(w);
    check_interrupt("during a local fit (after " + at + " iterations)");
  }
  Local out;
  const gsl_vector* xf = gsl_multifit_nlinear_position(w);
  for (std::size_t j = 0; j < ev.p(); ++j) out.t.push_back(gsl_vector_get(xf, j));
  out.iterations = int(gsl_multifit_nlinear_niter(w));
  out.reason = status == GSL_SUCCESS ? (info == 1   ? kStopXtol
                                        : info == 2 ? kStopGtol
                                                    : kStopConverged)
                                     : std::string(gsl_strerror(status));
  gsl_vector_free(x);
  gsl_multifit_nlinear_free(w);
  std::vector<double> e;
  if (ev.errors(out.t.data(), e)) out.cost = ev.cost_of(e);
  return out;
}

double chi2_95() { return gsl_cdf_chisq_Pinv(0.95, 1.0); }

// Simulated annealing (GSL gsl_siman) in the internal coordinates. The energy is ln(cost), so the
// temperature is a ratio of costs whatever their units (T = 1: a step that multiplies the cost by e
// is accepted with probability 1/e); a step moves every free coordinate by step_size times its start
// range times a uniform number in [-1, 1]. The state is a fixed-size, trivially copyable struct
// (gsl_siman copies it with memcpy) that carries a pointer to its context, since gsl_siman's
// callbacks get no user data.
constexpr std::size_t kSimanMax = 64;
struct SimanContext {
  const Evaluator* ev = nullptr;
  std::vector<double> width;  ///< start range per free coordinate (internal)
  double failure_energy = 0.0;
};
struct SimanState {
  const SimanContext* ctx;
  double t[kSimanMax];
};

double siman_energy(void* xp) {
  const auto* s = static_cast<const SimanState*>(xp);
  // A stop request: no forward solve; gsl_siman runs out its remaining (now cheap) steps and
  // global_stage raises tmlab::Interrupted after it.
  if (pending_interrupt() != 0) return s->ctx->failure_energy;
  std::vector<double> e;
  if (!s->ctx->ev->errors(s->t, e)) return s->ctx->failure_energy;
  return std::log(std::max(s->ctx->ev->cost_of(e), 1e-300));
}
void siman_step(const gsl_rng* r, void* xp, double step_size) {
  auto* s = static_cast<SimanState*>(xp);
  for (std::size_t j = 0; j < s->ctx->ev->p(); ++j)
    s->t[j] += step_size * s->ctx->width[j] * (2.0 * gsl_rng_uniform(r) - 1.0);
}
double siman_distance(void* a, void* b) {
  const auto* x = static_cast<const SimanState*>(a);
  const auto* y = static_cast<const SimanState*>(b);
  double d = 0.0;
  for (std::size_t j = 0; j < x->ctx->ev->p(); ++j) d += (x->t[j] - y->t[j]) * (x->t[j] - y->t[j]);
  return std::sqrt(d);
}

/// Anneals from `t0`; returns the best state gsl_siman visited. Serial (one forward solve per
/// trial), reproducible for a seed: gsl_rng_mt19937 seeded with options.seed.
std::vector<double> anneal(const Problem& pr, const FitOptions& opt, const Evaluator& ev,
                           const std::vector<double>& t0) {
  const std::size_t p = ev.p();
  if (p > kSimanMax) throw Error("fit: --global siman handles at most 64 free parameters");
  SimanContext ctx;
  ctx.ev = &ev;
  for (std::size_t j = 0; j < p; ++j) {
    const Parameter& q = pr.parameters[ev.free[j]];
    ctx.width.push_back(std::max(std::abs(q.to_internal(q.start_high) - q.to_internal(q.start_low)), 1e-3));
  }
  std::vector<double> e;
  const double e0 = ev.errors(t0.data(), e) ? std::log(std::max(ev.cost_of(e), 1e-300)) : 0.0;
  ctx.failure_energy = e0 + 50.0;  // far above any evaluated state near the start
  SimanState st{};
  st.ctx = &ctx;
  std::copy(t0.begin(), t0.end(), st.t);
  // Temperatures T_k = t_initial / mu^k down to t_min, iters_fixed_T trials at each: the budget of
  // opt.siman_evaluations trials fixes mu.
  gsl_siman_params_t sp;
  sp.n_tries = 1;  // unused by gsl_siman_solve
  sp.iters_fixed_T = std::max(1, opt.siman_iters_per_temperature);
  sp.step_size = opt.siman_step;
  sp.k = 1.0;
  sp.t_initial = opt.siman_t_initial;
  sp.t_min = opt.siman_t_min;
  const double temperatures = std::max(2.0, double(opt.siman_evaluations) / sp.iters_fixed_T);
  sp.mu_t = std::exp(std::log(sp.t_initial / sp.t_min) / temperatures);
  gsl_rng* rng = gsl_rng_alloc(gsl_rng_mt19937);
  gsl_rng_set(rng, opt.seed);
  gsl_siman_solve(rng, &st, siman_energy, siman_step, siman_distance, nullptr, nullptr, nullptr, nullptr,
                  sizeof(SimanState), sp);
  gsl_rng_free(rng);
  return std::vector<double>(st.t, st.t + p);
}

// The units of this fit (FitUnits): those restored from an interrupted fit and those finished since,
// with the solve counters they move; finished() hands every unit so far to the caller's hook.
struct UnitLog {
  const FitResume* hook = nullptr;
  FitUnits done;
  std::atomic<long>* solves = nullptr;
  std::atomic<long>* global_solves = nullptr;

  const FitUnits* restored() const { return hook ? hook->restored : nullptr; }
  void finished() const {
    if (hook && hook->unit_finished) hook->unit_finished(done);
  }
};

// Global stage: `starts` candidates in the internal coordinates (the given values first, then
// uniform in each parameter's start range), their costs evaluated in parallel. Returns the
// candidates; res.start_costs gets their costs and `order` the candidates sorted by cost.
std::vector<std::vector<double>> global_stage(const Problem& pr, const FitOptions& opt, const Evaluator& ev,
                                              FitResult& res, std::vector<std::size_t>& order) {
  const std::size_t p = ev.p();
  std::size_t starts = opt.global == GlobalStage::Siman ? 1 : std::size_t(std::max(1, opt.starts));
  std::vector<std::vector<double>> cand(starts, std::vector<double>(p));
  std::mt19937_64 rng(opt.seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t c = 0; c < starts; ++c)
    for (std::size_t j = 0; j < p; ++j) {
      const Parameter& q = pr.parameters[ev.free[j]];
      if (c == 0) {
        cand[c][j] = q.to_internal(q.value);
      } else {
        const double a = q.to_internal(q.start_low), b = q.to_internal(q.start_high);
        cand[c][j] = a + (b - a) * u(rng);
      }
    }
  if (opt.global == GlobalStage::Siman) {
    // Annealing from the parameters' values; the local stage then starts from its best state and
    // from the values themselves.
    cand.resize(2);
    cand[1] = cand[0];
    cand[0] = anneal(pr, opt, ev, cand[1]);
    check_interrupt("during simulated annealing");
    starts = cand.size();
  }
  res.start_costs.assign(starts, kInf);
  parallel_for(starts, opt.threads, [&](std::size_t c) {
    std::vector<double> e;
    if (ev.errors(cand[c].data(), e)) res.start_costs[c] = ev.cost_of(e);
  });
  check_interrupt("during the global stage of the fit");
  order.assign(starts, 0);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return res.start_costs[a] < res.start_costs[b]; });
  if (!std::isfinite(res.start_costs[order[0]]))
    throw Error("fit: the forward model '" + res.model_name + "' cannot be evaluated at any of the " +
                std::to_string(starts) +
                " starting points (check the data's geometry and the SPEC's fixed values)");
  if (opt.progress)
    opt.progress("global stage (" + to_string(opt.global) + ", " + ev.model->name() +
                 "): " + std::to_string(starts) + " candidates, best cost " +
                 significant(res.start_costs[order[0]], 5) + " (start " + std::to_string(order[0]) + ")");

  return cand;
}

// Local stage: Levenberg-Marquardt from the best candidates; the best run, its terms put in the
// problem's canonical order. A run restored from the checkpoint of an interrupted fit is taken as
// it ended, with the solve counter as it was after it; every other run is reported to the hook.
Local local_stage(const Problem& pr, const FitOptions& opt, const Evaluator& ev,
                  const std::vector<std::vector<double>>& cand, const std::vector<std::size_t>& order,
                  FitResult& res, UnitLog& log) {
  const std::size_t starts = cand.size(), p = ev.p();
  const FitUnits* restored = log.restored();
  Local best;
  const std::size_t runs = std::min<std::size_t>(starts, std::size_t(std::max(1, opt.local_runs)));
  for (std::size_t r = 0; r < runs; ++r) {
    if (!std::isfinite(res.start_costs[order[r]])) break;
    Local l;
    if (restored && r < restored->local_runs.size()) {
      const FitUnits::LocalRun& u = restored->local_runs[r];
      if (u.t.size() != p) throw Error("fit: a restored local run has the wrong number of parameters");
      l.t = u.t;
      l.cost = u.cost;
      l.iterations = u.iterations;
      l.reason = u.reason;
      *log.solves = u.solves;
      log.done.local_runs.push_back(u);
      if (opt.progress)
        opt.progress("local stage from start " + std::to_string(order[r]) +
                     ": from the checkpoint of the interrupted fit (cost " + significant(l.cost, 5) + ", " +
                     std::to_string(l.iterations) + " iterations)");
    } else {
      check_interrupt("before local fit " + std::to_string(r + 1) + " of " + std::to_string(runs));
      if (opt.progress) opt.progress("local stage from start " + std::to_string(order[r]) + ":");
      l = local_fit(ev, cand[order[r]], opt, true);
      log.done.local_runs.push_back({l.t, l.cost, l.iterations, l.reason, log.solves->load()});
      log.finished();
    }
    res.iterations += l.iterations;
    ++res.local_runs;
    if (l.cost < best.cost) best = std::move(l);
  }
  if (!std::isfinite(best.cost))
    throw Error("fit: every local run ended where the model cannot be evaluated");
  res.stop_reason = best.reason;
  if (pr.canonical) {
    // Exchangeable terms in their canonical order (the cost is the same; the reported order is not).
    const std::vector<double> xc = pr.canonical(ev.physical(best.t.data()));
    for (std::size_t j = 0; j < p; ++j) best.t[j] = pr.parameters[ev.free[j]].to_internal(xc[ev.free[j]]);
  }

  return best;
}

// The optimum's residuals, cost, RMS and information criteria; returns the force errors.
std::vector<double> optimum_stats(const Problem& pr, const Evaluator& ev, const std::vector<double>& t,
                                  FitResult& res, std::shared_ptr<const WarmStart>& state) {
  const std::size_t p = ev.p(), n = ev.n_data();
  std::vector<double> e0;
  ev.errors(t.data(), e0, &res.prediction, nullptr, &state);
  res.cost = ev.cost_of(e0);
  res.n = n;
  res.k = p;
  for (std::size_t i = 0; i < n; ++i) res.sse += e0[i] * e0[i];
  for (std::size_t i = n; i < e0.size(); ++i) res.prior_cost += e0[i] * e0[i];
  res.rms = std::sqrt(res.sse / double(n));
  res.rms_percent_peak = 100.0 * res.rms / pr.data.peak_force;
  const double ssen = std::max(res.sse, 1e-300) / double(n);
  res.aic = double(n) * std::log(ssen) + 2.0 * double(p);
  res.bic = double(n) * std::log(ssen) + double(p) * std::log(double(n));

  return e0;
}

// The covariance of the internal coordinates from a central-difference Jacobian of the force
// errors: Cs (column-scaled, for correlations), Ct (scaled by the residual variance), the t quantile
// of the 95 % interval and which directions the data determine.
struct Covariance {
  Eigen::MatrixXd Cs, Ct;
  double tq = kInf;
  std::vector<bool> identifiable;
  std::vector<double> data_only_variance;  ///< internal, per free parameter, without the prior rows
  Eigen::MatrixXd J;                       ///< the central-difference Jacobian (every row)
  Eigen::MatrixXd normal_inverse;          ///< (J^T J)^{-1} as Ct = s^2 normal_inverse uses it
};

Covariance covariance(const FitOptions& opt, const Evaluator& ev, const std::vector<double>& t,
                      const std::vector<double>& e0, const FitResult& res, const WarmStart* base) {
  const std::size_t p = ev.p(), n = ev.n(), nd = ev.n_data();
  Eigen::MatrixXd J(n, p);
  parallel_for(p, opt.threads, [&](std::size_t j) {
    const double h = std::max(1e-5, 10.0 * ev.model->jacobian_step()) * std::max(1.0, std::abs(t[j]));
    std::vector<double> tp = t, tm = t, ep, em;
    tp[j] += h;
    tm[j] -= h;
    const bool okp = ev.errors(tp.data(), ep, nullptr, base), okm = ev.errors(tm.data(), em, nullptr, base);
    for (std::size_t i = 0; i < n; ++i)
      J(Eigen::Index(i), Eigen::Index(j)) = okp && okm ? (ep[i] - em[i]) / (2 * h)
                                            : okp      ? (ep[i] - e0[i]) / h
                                            : okm      ? (e0[i] - em[i]) / h
                                                       : 0.0;
  });
  const double s2 = nd > p ? res.sse / double(nd - p) : kInf;
  // Column scaling makes the SVD's rank test independent of units; singular values below 1e-8 of
  // the largest mark directions the data do not determine.
  Eigen::VectorXd scale = J.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < scale.size(); ++j)
    if (!(scale(j) > 0.0)) scale(j) = 1.0;
  const Eigen::MatrixXd Js = J * scale.cwiseInverse().asDiagonal();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js, Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  const Eigen::MatrixXd V = svd.matrixV();
  Eigen::VectorXd inv2(sv.size());
  Covariance c;
  c.identifiable.assign(p, true);
  for (Eigen::Index k = 0; k < sv.size(); ++k) {
    const double floor = 1e-8 * sv(0);
    inv2(k) = 1.0 / std::pow(std::max(sv(k), floor), 2);
    if (sv(k) < floor)
      for (std::size_t j = 0; j < p; ++j)
        if (std::abs(V(Eigen::Index(j), k)) > 0.1) c.identifiable[j] = false;
  }
  c.Cs = V * inv2.asDiagonal() * V.transpose();
  c.Ct = s2 * scale.cwiseInverse().asDiagonal() * c.Cs * scale.cwiseInverse().asDiagonal();
  c.normal_inverse = scale.cwiseInverse().asDiagonal() * c.Cs * scale.cwiseInverse().asDiagonal();
  c.tq = nd > p ? gsl_cdf_tdist_Pinv(0.975, double(nd - p)) : kInf;
  if (n > nd) {
    // The data alone (the prior rows dropped): what the priors changed in the standard errors.
    const Eigen::MatrixXd Jd = J.topRows(Eigen::Index(nd));
    const Eigen::MatrixXd A = Jd.transpose() * Jd;
    Eigen::JacobiSVD<Eigen::MatrixXd> sd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::VectorXd w = sd.singularValues();
    Eigen::VectorXd wi(w.size());
    for (Eigen::Index k = 0; k < w.size(); ++k) wi(k) = w(k) > 1e-14 * w(0) ? 1.0 / w(k) : kInf;
    c.data_only_variance.assign(p, kInf);
    for (std::size_t j = 0; j < p; ++j) {
      double v = 0.0;
      for (Eigen::Index k = 0; k < w.size(); ++k) {
        const double vk = sd.matrixV()(Eigen::Index(j), k);
        if (vk != 0.0) v += vk * vk * wi(k);
      }
      c.data_only_variance[j] = s2 * v;
    }
  }

  c.J = std::move(J);
  return c;
}

// The fit linearised at the optimum (FitResult::linearisation) from the covariance's Jacobian.
Linearisation linearisation(const Problem& pr, const Evaluator& ev, const std::vector<double>& t,
                            const Covariance& c) {
  Linearisation l;
  const std::size_t p = ev.p(), nd = ev.n_data();
  l.free = ev.free;
  l.t = t;
  l.n_data = nd;
  for (std::size_t j = 0; j < p; ++j) l.dxdt.push_back(pr.parameters[ev.free[j]].derivative(t[j]));
  l.jacobian.resize(nd * p);
  for (std::size_t i = 0; i < nd; ++i)
    for (std::size_t j = 0; j < p; ++j) l.jacobian[i * p + j] = c.J(Eigen::Index(i), Eigen::Index(j));
  l.normal_inverse.resize(p * p);
  for (std::size_t a = 0; a < p; ++a)
    for (std::size_t b = 0; b < p; ++b)
      l.normal_inverse[a * p + b] = c.normal_inverse(Eigen::Index(a), Eigen::Index(b));
  return l;
}

// The parameters in physical units (delta method through each transform, Wald intervals clipped to
// the bounds) and their correlation matrix.
void parameter_results(const Problem& pr, const Evaluator& ev, const std::vector<double>& t,
                       const Covariance& c, FitResult& res) {
  const std::size_t p = ev.p();
  const Eigen::MatrixXd& Cs = c.Cs;
  const Eigen::MatrixXd& Ct = c.Ct;
  const double tq = c.tq;
  const std::vector<bool>& identifiable = c.identifiable;
  std::vector<double> x = ev.physical(t.data());
  std::size_t jfree = 0;
  for (std::size_t i = 0; i < pr.parameters.size(); ++i) {
    const Parameter& q = pr.parameters[i];
    ParameterResult r;
    r.name = q.name;
    r.unit = q.unit;
    r.value = x[i];
    r.fixed = q.fixed;
    r.transform = to_string(q.transform());
    if (q.fixed) {
      r.standard_error = 0.0;
      r.lower95 = r.upper95 = x[i];
    } else {
      const std::size_t j = jfree++;
      const double d = std::abs(q.derivative(t[j]));
      r.identifiable = identifiable[j];
      r.standard_error =
          identifiable[j] ? d * std::sqrt(std::max(Ct(Eigen::Index(j), Eigen::Index(j)), 0.0)) : kInf;
      // Wald interval in physical units, clipped to the bounds (a bound is a hard constraint).
      r.lower95 = std::max(q.lower, x[i] - tq * r.standard_error);
      r.upper95 = std::min(q.upper, x[i] + tq * r.standard_error);
      res.free_names.push_back(q.name);
    }
    res.parameters.push_back(r);
  }
  res.correlation.assign(p, std::vector<double>(p, 0.0));
  for (std::size_t a = 0; a < p; ++a)
    for (std::size_t b = 0; b < p; ++b) {
      const double den =
          std::sqrt(Cs(Eigen::Index(a), Eigen::Index(a)) * Cs(Eigen::Index(b), Eigen::Index(b)));
      res.correlation[a][b] = den > 0 ? Cs(Eigen::Index(a), Eigen::Index(b)) / den : (a == b ? 1.0 : 0.0);
    }
}

// The notes: fixed parameters, confounded pairs (|correlation| > 0.9) with what they mean, and
// directions the data do not determine.
void confounding_report(const Problem& pr, const std::vector<bool>& identifiable, FitResult& res) {
  const std::size_t p = res.free_names.size();
  std::string fixed_list;
  for (const auto& q : pr.parameters)
    if (q.fixed) fixed_list += (fixed_list.empty() ? "" : ", ") + q.name + " = " + significant(q.value, 6);
  if (!fixed_list.empty())
    res.notes.push_back("fixed (not fitted; their uncertainty is not propagated): " + fixed_list);
  const bool indentation = res.model_description.find("indentation") != std::string::npos ||
                           res.model_name.find("hertz") != std::string::npos ||
                           res.model_name.find("sneddon") != std::string::npos ||
                           res.model_name.find("lee_radok") != std::string::npos;
  for (std::size_t a = 0; a < p; ++a)
    for (std::size_t b = a + 1; b < p; ++b) {
      const double c = res.correlation[a][b];
      if (!(std::abs(c) > 0.9)) continue;
      Confounding cf{res.free_names[a], res.free_names[b], c, ""};
      const auto is = [&](const char* n1, const char* n2) {
        return (cf.a == n1 && cf.b == n2) || (cf.a == n2 && cf.b == n1);
      };
      if (is("young", "poisson") && indentation)
        cf.note =
            "indentation force depends on E and nu almost only through E/(1 - nu^2): force data alone "
            "cannot separate them. The fit did nothing about it: fix poisson (--fix poisson=...), or add "
            "a second test type (unconfined compression) to the data";
      else if ((cf.a == "young" && cf.b[0] == 'e') || (cf.b == "young" && cf.a[0] == 'e'))
        cf.note =
            "the long-term modulus E_inf trades against a Prony weight: the hold is too short to see the "
            "relaxation end. The fit did nothing about it: lengthen the hold, fix the relaxation time, or "
            "fit fewer Prony terms";
      else
        cf.note =
            "the data determine only a combination of these two. The fit did nothing about it: fix one "
            "(--fix) or add a test that separates them";
      for (const Prior& q : pr.priors)
        if (q.parameter == cf.a || q.parameter == cf.b) {
          const std::size_t at = cf.note.find("The fit did nothing about it");
          const std::string did = "The fit regularised it with the prior on " + q.parameter + " (mean " +
                                  significant(q.mean, 6) + ", sd " + significant(q.sd, 4) +
                                  "): the reported value of " + q.parameter + " rests on that prior";
          cf.note = at == std::string::npos ? cf.note + ". " + did : cf.note.substr(0, at) + did;
          break;
        }
      res.confounded.push_back(cf);
    }
  for (std::size_t j = 0; j < p; ++j)
    if (!identifiable[j])
      res.notes.push_back(
          "'" + res.free_names[j] +
          "' is not identifiable from these data (J^T J singular in its direction): standard error "
          "reported as infinite");
}

// The profile likelihood of the worst-determined parameter: the least-squares cost re-minimised over
// the others on a grid of +-3 standard errors, and where it crosses the chi^2(1) 95 % threshold.
void profile_likelihood(const Problem& pr, const FitOptions& opt, const Evaluator& ev,
                        const std::vector<double>& t, const Covariance& c, FitResult& res, UnitLog& log) {
  const std::size_t p = ev.p(), n = ev.n_data();
  const Eigen::MatrixXd& Ct = c.Ct;
  const std::vector<double> x = ev.physical(t.data());
  const double smin = res.sse + res.prior_cost;  // the least-squares objective at the optimum
  std::size_t worst = p;
  double worst_rel = -1.0;
  for (std::size_t j = 0; j < p; ++j) {
    const ParameterResult& r = res.parameters[ev.free[j]];
    double rel = r.identifiable ? r.standard_error / std::max(std::abs(r.value), 1e-300) : kInf;
    // A NaN standard error (a covariance that is NaN: a degenerate optimum) determines nothing: the
    // worst, not a value every comparison skips (which left `worst` one past the end).
    if (std::isnan(rel)) rel = kInf;
    if (rel > worst_rel) {
      worst_rel = rel;
      worst = j;
    }
  }
  if (worst == p) return;  // no free parameter
  const std::size_t i = ev.free[worst];
  const Parameter& q = pr.parameters[i];
  res.profile.parameter = q.name;
  // The grid in the internal coordinate: the optimum +- c SE_t (SE_t capped so the grid stays finite).
  double se_t = std::sqrt(std::max(Ct(Eigen::Index(worst), Eigen::Index(worst)), 0.0));
  // In log/logit coordinates +-3 x 5 spans any physical range; an identity coordinate keeps its
  // units, so a non-identifiable one gets a grid of +-3 |x| instead.
  if (q.transform() != Transform::Identity && (!std::isfinite(se_t) || se_t > 5.0)) se_t = 5.0;
  if (q.transform() == Transform::Identity && !std::isfinite(se_t)) se_t = std::max(std::abs(t[worst]), 1.0);
  if (se_t < 1e-12 * std::max(1.0, std::abs(t[worst]))) se_t = 1e-12 * std::max(1.0, std::abs(t[worst]));
  const std::vector<double> cs = {-3, -2, -1.5, -1, -0.5, 0, 0.5, 1, 1.5, 2, 3};
  Evaluator sub = ev;
  sub.free.clear();
  std::vector<double> tsub;
  for (std::size_t j = 0; j < p; ++j)
    if (j != worst) {
      sub.free.push_back(ev.free[j]);
      tsub.push_back(t[j]);
    }
  std::vector<ProfilePoint> pts(cs.size());
  const FitUnits* restored = log.restored();
  std::size_t unit = 0;  // the grid points besides the optimum, each a unit of the checkpoint
  for (std::size_t k = 0; k < cs.size(); ++k) {
    const double tk = t[worst] + cs[k] * se_t;
    Evaluator sk = sub;
    sk.held = x;
    sk.held[i] = q.to_physical(tk);
    sk.cost = Cost::LeastSquares;
    pts[k].value = sk.held[i];
    if (cs[k] == 0.0) {
      pts[k].sse = smin;
      continue;
    }
    if (restored && unit < restored->profile.size()) {
      pts[k].sse = restored->profile[unit].sse;
      *log.solves = restored->profile[unit].solves;
      log.done.profile.push_back(restored->profile[unit++]);
      continue;
    }
    check_interrupt("before profile-likelihood point " + std::to_string(unit + 1) + " of " +
                    std::to_string(cs.size() - 1));
    std::vector<double> e;
    if (sk.p() == 0) {
      pts[k].sse = sk.errors(nullptr, e) ? sk.cost_of(e) : kInf;
    } else {
      FitOptions po = opt;
      po.progress = nullptr;
      const Local l = local_fit(sk, tsub, po, false);
      pts[k].sse = std::max(l.cost, smin);  // the optimum is the minimum (round-off)
    }
    log.done.profile.push_back({pts[k].sse, log.solves->load()});
    ++unit;
    log.finished();
  }
  res.profile.points = pts;
  const double thr = chi2_95();
  const auto stat = [&](double s) { return double(n) * std::log(s / smin); };
  const std::size_t mid = 5;
  res.profile.lower95 = pts.front().value;
  res.profile.upper95 = pts.back().value;
  for (std::size_t k = mid; k + 1 < pts.size(); ++k)
    if (stat(pts[k + 1].sse) > thr) {
      const double a = stat(pts[k].sse), b = stat(pts[k + 1].sse);
      const double f = std::isfinite(b) ? (thr - a) / (b - a) : 0.0;
      res.profile.upper95 = pts[k].value + f * (pts[k + 1].value - pts[k].value);
      res.profile.upper_found = true;
      break;
    }
  for (std::size_t k = mid; k > 0; --k)
    if (stat(pts[k - 1].sse) > thr) {
      const double a = stat(pts[k].sse), b = stat(pts[k - 1].sse);
      const double f = std::isfinite(b) ? (thr - a) / (b - a) : 0.0;
      res.profile.lower95 = pts[k].value + f * (pts[k - 1].value - pts[k].value);
      res.profile.lower_found = true;
      break;
    }
}

// What each prior did: its share of the cost, and the standard error with the prior beside the
// one the data alone give.
void prior_notes(const Problem& pr, const Evaluator& ev, const Covariance& c, FitResult& res) {
  for (std::size_t k = 0; k < pr.priors.size(); ++k) {
    const Prior& q = pr.priors[k];
    const std::size_t i = std::get<0>(ev.priors[k]);
    const std::size_t j = std::size_t(std::find(ev.free.begin(), ev.free.end(), i) - ev.free.begin());
    const ParameterResult& r = res.parameters[i];
    double without = kInf;
    if (j < c.data_only_variance.size() && std::isfinite(c.data_only_variance[j]))
      without = std::sqrt(std::max(c.data_only_variance[j], 0.0)) *
                std::abs(pr.parameters[i].derivative(pr.parameters[i].to_internal(r.value)));
    const double z = (r.value - q.mean) / q.sd;
    res.notes.push_back(
        "prior on " + r.name + ": Gaussian, mean " + significant(q.mean, 6) + ", sd " + significant(q.sd, 4) +
        " " + r.unit + " (weighed against the noise sigma " + significant(ev.sigma, 4) +
        " N); the estimate lies " + significant(z, 3) + " sd from the mean; standard error " +
        significant(r.standard_error, 3) + " with the prior, " +
        (std::isfinite(without) ? significant(without, 3) : std::string("inf")) + " from the data alone" +
        (!std::isfinite(without) || r.standard_error < 0.5 * without
             ? ": the prior, not the data, determines this parameter"
             : ""));
  }
}

// With a surrogate: its costs rank the candidates; the local stage's starts are re-costed with the
// final model (a candidate it cannot evaluate is skipped).
void recost_with_final_model(const FitOptions& opt, const Evaluator& ev,
                             std::vector<std::vector<double>>& cand, std::vector<std::size_t>& order,
                             FitResult& res) {
  const std::size_t runs = std::min<std::size_t>(cand.size(), std::size_t(std::max(1, opt.local_runs)));
  std::vector<std::vector<double>> best;
  std::vector<double> costs;
  for (std::size_t r = 0; r < runs; ++r) best.push_back(cand[order[r]]);
  costs.assign(best.size(), kInf);
  parallel_for(best.size(), opt.threads, [&](std::size_t c) {
    std::vector<double> e;
    if (ev.errors(best[c].data(), e)) costs[c] = ev.cost_of(e);
  });
  res.global_costs = res.start_costs;
  res.start_costs = costs;
  cand = best;
  order.assign(cand.size(), 0);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return costs[a] < costs[b]; });
  if (!std::isfinite(costs[order[0]]))
    throw Error("fit: the forward model '" + res.model_name +
                "' cannot be evaluated at the global stage's best candidates");
}

// The global stage as a unit: taken from the checkpoint of an interrupted fit when it holds it,
// else run (global_stage, and the re-costing with a surrogate) and reported to the hook.
std::vector<std::vector<double>> global_units(const Problem& pr, const FitOptions& opt, const Evaluator& ev,
                                              const Evaluator& gev, FitResult& res,
                                              std::vector<std::size_t>& order, UnitLog& log) {
  FitUnits& d = log.done;
  const FitUnits* restored = log.restored();
  if (restored && restored->global_done) {
    d.global_done = true;
    d.candidates = restored->candidates;
    d.order = restored->order;
    d.start_costs = restored->start_costs;
    d.global_costs = restored->global_costs;
    d.solves = restored->solves;
    d.global_solves = restored->global_solves;
    bool ok = !d.candidates.empty() && d.order.size() == d.candidates.size() &&
              d.start_costs.size() == d.candidates.size();
    for (const auto& c : d.candidates) ok = ok && c.size() == ev.p();
    for (const std::size_t o : d.order) ok = ok && o < d.candidates.size();
    if (!ok) throw Error("fit: the restored global stage does not fit this problem");
    order = d.order;
    res.start_costs = d.start_costs;
    res.global_costs = d.global_costs;
    *log.solves = d.solves;
    *log.global_solves = d.global_solves;
    if (opt.progress)
      opt.progress("global stage (" + to_string(opt.global) + ", " + gev.model->name() +
                   "): from the checkpoint of the interrupted fit (" + std::to_string(d.candidates.size()) +
                   " starts, best cost " + significant(res.start_costs[order[0]], 5) + ")");
    return d.candidates;
  }
  std::vector<std::vector<double>> cand = global_stage(pr, opt, gev, res, order);
  if (pr.global_model) recost_with_final_model(opt, ev, cand, order, res);
  d.global_done = true;
  d.candidates = cand;
  d.order = order;
  d.start_costs = res.start_costs;
  d.global_costs = res.global_costs;
  d.solves = log.solves->load();
  d.global_solves = log.global_solves->load();
  log.finished();
  return cand;
}

}  // namespace

void check_priors(const Problem& pr) {
  for (std::size_t k = 0; k < pr.priors.size(); ++k) {
    const Prior& q = pr.priors[k];
    const std::size_t i = index_of(pr.parameters, q.parameter);
    if (pr.parameters[i].fixed) throw Error("fit: a prior on '" + q.parameter + "', which is fixed");
    if (!(q.sd > 0.0) || !std::isfinite(q.sd) || !std::isfinite(q.mean))
      throw Error("fit: the prior on '" + q.parameter + "' needs a finite mean and a positive sd");
    for (std::size_t j = 0; j < k; ++j)
      if (pr.priors[j].parameter == q.parameter)
        throw Error("fit: two priors on '" + q.parameter + "' (mean " + shortest(pr.priors[j].mean) +
                    ", sd " + shortest(pr.priors[j].sd) + " and mean " + shortest(q.mean) + ", sd " +
                    shortest(q.sd) + "): give one");
  }
}

bool converged_stop(const std::string& stop_reason) {
  return stop_reason == kStopXtol || stop_reason == kStopGtol || stop_reason == kStopConverged;
}

FitResult fit(const Problem& pr, const FitOptions& opt) {
  gsl_set_error_handler_off();  // GSL reports through status codes; its default handler aborts
  const auto started = std::chrono::steady_clock::now();
  std::atomic<long> solves{0};
  FitResult res;
  res.model_name = pr.model->name();
  res.model_description = pr.model->description();
  res.cost_name = to_string(opt.cost);
  res.threads = opt.threads;

  Evaluator ev;
  ev.problem = &pr;
  ev.model = pr.model.get();
  ev.cost = opt.cost;
  ev.delta = 1e-6 * pr.data.peak_force;
  ev.solves = &solves;
  ev.warm = opt.warm_start;
  for (std::size_t i = 0; i < pr.parameters.size(); ++i) {
    ev.held.push_back(pr.parameters[i].value);
    if (!pr.parameters[i].fixed) ev.free.push_back(i);
  }
  if (ev.p() == 0) throw Error("fit: every parameter is fixed");
  if (!pr.priors.empty()) {
    if (opt.cost != Cost::LeastSquares) throw Error("fit: priors need the least-squares cost");
    ev.sigma = pr.noise_sigma > 0.0 ? pr.noise_sigma : noise_sigma(pr.data);
    if (!(ev.sigma > 0.0))
      throw Error(
          "fit: a prior needs the noise level of the data, which cannot be estimated from these "
          "samples (give it: --noise SIGMA_N)");
    check_priors(pr);
    for (const Prior& q : pr.priors)
      ev.priors.emplace_back(index_of(pr.parameters, q.parameter), q.mean, q.sd);
    res.noise_sigma = ev.sigma;
  }
  res.global_stage = to_string(opt.global);
  std::atomic<long> global_solves{0};
  Evaluator gev = ev;  // the global stage's evaluator: the surrogate when the problem has one
  if (pr.global_model) {
    gev.model = pr.global_model.get();
    gev.solves = &global_solves;
  }
  res.global_model_name = gev.model->name();

  UnitLog log;
  log.hook = &opt.resume;
  log.solves = &solves;
  log.global_solves = &global_solves;
  std::vector<std::size_t> order;
  const std::vector<std::vector<double>> cand = global_units(pr, opt, ev, gev, res, order, log);
  const std::vector<double> t = local_stage(pr, opt, ev, cand, order, res, log).t;
  std::shared_ptr<const WarmStart> optimum_state;
  const std::vector<double> e0 = optimum_stats(pr, ev, t, res, optimum_state);
  const Covariance c = covariance(opt, ev, t, e0, res, optimum_state.get());
  parameter_results(pr, ev, t, c, res);
  res.linearisation = linearisation(pr, ev, t, c);
  confounding_report(pr, c.identifiable, res);
  check_interrupt("after the local stage of the fit");
  if (opt.profile && ev.n_data() > ev.p()) profile_likelihood(pr, opt, ev, t, c, res, log);
  check_interrupt("during the profile likelihood");
  res.forward_solves = solves.load();
  res.model_effort = pr.model->effort();
  res.global_solves = pr.global_model ? global_solves.load() : 0;
  if (!pr.priors.empty()) prior_notes(pr, ev, c, res);
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return res;
}

}  // namespace tmlab::fit
