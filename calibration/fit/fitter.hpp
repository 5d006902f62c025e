// The fitting engine (issue 14; docs/identification.md): a global stage (multi-start: candidate
// starting points sampled in the transformed space, their costs computed in parallel, the best
// refined) and a local stage (GSL gsl_multifit_nlinear, Levenberg-Marquardt with optional geodesic
// acceleration; the Jacobian by forward differences of the forward model in the transformed space,
// its columns computed in parallel), then the uncertainty at the optimum:
//   covariance  C = s^2 (J^T J)^{-1},  s^2 = SSE / (n - k)  (J by central differences),
//   physical    C_x = D C D,  D = diag(dx/dt)  (delta method through the transforms),
//   95 % interval  x +- t_{0.975, n-k} SE,  correlations C_ij / sqrt(C_ii C_jj),
//   a profile likelihood of the worst-determined parameter (largest SE / |x|): the others re-fitted
//   at fixed values of it, the interval where n ln(SSE / SSE_min) <= chi2_1(0.95) = 3.84,
//   AIC = n ln(SSE/n) + 2k, BIC = n ln(SSE/n) + k ln n,
//   and a confounding report: every pair with |correlation| > 0.9 named, with what was done.
// Costs: least squares on force (weighted per test), or the L1 error of Xu et al. (2011, eq. 23),
// sum |F_model - F_data|, minimised by the same engine on the smoothed residuals
// r = e / sqrt(|e| + delta) (r^2 -> |e| for |e| >> delta = 1e-6 peak force).
#pragma once

#include "calibration/fit/forward_model.hpp"

#include <functional>
#include <string>
#include <vector>

namespace tmlab::fit {

enum class Cost { LeastSquares, L1 };
std::string to_string(Cost c);
/// The global stage: multi-start (candidates sampled uniformly in the start ranges, costed in
/// parallel) or simulated annealing (GSL gsl_siman from the parameters' values, serial).
enum class GlobalStage { MultiStart, Siman };
std::string to_string(GlobalStage g);

/// The finished units of one fit, what `tmlab fit --resume` takes from a checkpoint instead of
/// computing them again: the global stage (with a surrogate, including the final model's costs of
/// its best candidates), each finished Levenberg-Marquardt run, each finished profile-likelihood
/// point. A unit interrupted half-way is not here: it runs again from its start, which is what
/// keeps a resumed fit identical bit for bit to an uninterrupted one. The solve counters are kept
/// as they were after each unit, so forward_solves agrees too.
struct FitUnits {
  struct LocalRun {
    std::vector<double> t;  ///< the optimum, internal (transformed) coordinates
    double cost = 0.0;
    int iterations = 0;
    std::string reason;
    long solves = 0;  ///< the fit's forward-solve counter after this run
  };
  struct ProfileUnit {
    double sse = 0.0;  ///< the point's re-fitted SSE (as FitResult::profile reports it)
    long solves = 0;
  };
  bool global_done = false;
  std::vector<std::vector<double>> candidates;  ///< the local stage's starts, internal coordinates
  std::vector<std::size_t> order;               ///< the candidates by cost
  std::vector<double> start_costs, global_costs;
  long solves = 0, global_solves = 0;  ///< the counters after the global stage
  std::vector<LocalRun> local_runs;    ///< in the order they ran
  std::vector<ProfileUnit> profile;    ///< the grid points computed so far, in grid order (the
                                       ///< optimum itself is not a unit)
};

/// The resume hook of fit(): the engine does no file I/O; the caller (the CLI) owns the checkpoint.
struct FitResume {
  const FitUnits* restored = nullptr;  ///< units of an interrupted fit, taken instead of computed
  /// Called after each unit finishes (restored ones excepted) with every unit so far.
  std::function<void(const FitUnits&)> unit_finished;
};

struct FitOptions {
  Cost cost = Cost::LeastSquares;
  int starts = 12;        ///< candidate starts of the global stage (the first is the parameters' values)
  int local_runs = 3;     ///< best candidates refined by Levenberg-Marquardt
  bool geodesic = false;  ///< geodesic acceleration (gsl_multifit_nlinear_trs_lmaccel)
  int threads = 2;        ///< forward solves in parallel
  unsigned long seed = 1;
  GlobalStage global = GlobalStage::MultiStart;
  // Simulated annealing (GlobalStage::Siman): energy ln(cost), temperatures from t_initial down to
  // t_min geometrically, iters_per_temperature trials at each, about `siman_evaluations` trials.
  int siman_evaluations = 3000;
  int siman_iters_per_temperature = 20;
  double siman_step = 0.2;  ///< step, as a fraction of each parameter's start range (internal)
  double siman_t_initial = 1.0, siman_t_min = 1e-3;
  int max_iterations = 200;
  /// Levenberg-Marquardt's step test: stop when every internal coordinate moves by less than
  /// xtol (|t| + xtol) (GSL's xtol). A model whose forces carry a solver tolerance cannot resolve
  /// steps much below that tolerance over its sensitivity; a smaller xtol then only spends
  /// iterations on noise (docs/identification.md).
  double xtol = 1e-9;
  bool profile = true;  ///< profile likelihood of the worst-determined parameter
  /// Levenberg-Marquardt's forward solves (trial points, Jacobian columns, the covariance's
  /// columns) start from the solver state at the current point (ForwardModel::predict_warm): the
  /// same equations and stopping tests, fewer iterations. Deterministic (the states come from the
  /// serial sequence of points).
  bool warm_start = true;
  /// Called with one line of progress (iteration, cost, current standard errors); may be empty.
  std::function<void(const std::string&)> progress;
  FitResume resume;  ///< checkpoints (tmlab fit --resume); empty: none
};

struct ParameterResult {
  std::string name, unit;
  double value = 0.0;
  bool fixed = false;
  std::string transform;        ///< identity, log, logit
  double standard_error = 0.0;  ///< physical units; +inf when not identifiable
  double lower95 = 0.0, upper95 = 0.0;
  bool identifiable = true;  ///< false: J^T J is singular in this parameter's direction
};

struct ProfilePoint {
  double value = 0.0;  ///< the profiled parameter, physical
  double sse = 0.0;    ///< the re-fitted SSE with it fixed there
};

struct Profile {
  std::string parameter;  ///< empty when no profile was computed
  std::vector<ProfilePoint> points;
  double lower95 = 0.0, upper95 = 0.0;
  bool lower_found = false, upper_found = false;  ///< false: the threshold lies beyond the grid
};

struct Confounding {
  std::string a, b;
  double correlation = 0.0;
  std::string note;
};

/// The fit linearised at its optimum, as its covariance sees it: what a caller needs to carry a
/// perturbation of the model's forces into the parameters (calibration/fit/discretisation.hpp)
/// without another forward solve. Internal (transformed) coordinates of the free parameters.
struct Linearisation {
  std::vector<std::size_t> free;  ///< indices into the problem's parameters
  std::vector<double> t;          ///< the optimum, internal coordinates
  std::vector<double> dxdt;       ///< dx/dt at the optimum per free parameter (the transforms)
  /// d e_i / d t_j of the weighted force errors e_i = w (F_i - data_i) (the data rows of the
  /// covariance's central-difference Jacobian), row-major, n_data x p.
  std::vector<double> jacobian;
  /// (J^T J)^{-1} of the covariance (every row of J, the priors' included; singular directions
  /// floored as the covariance floors them), p x p row-major: the covariance is s^2 times it.
  std::vector<double> normal_inverse;
  std::size_t n_data = 0;
  bool empty() const { return free.empty(); }
};

struct FitResult {
  std::string model_name, model_description;
  std::string cost_name;
  std::vector<ParameterResult> parameters;
  std::vector<std::string> free_names;           ///< order of the correlation matrix
  std::vector<std::vector<double>> correlation;  ///< free parameters
  double cost = 0.0;  ///< the minimised cost: SSE (+ prior terms) (N^2) or sum |e| (N)
  double sse = 0.0;   ///< weighted sum of squared force residuals, N^2
  double rms = 0.0;   ///< residual RMS, N
  double rms_percent_peak = 0.0;
  std::size_t n = 0, k = 0;
  double aic = 0.0, bic = 0.0;
  long forward_solves = 0;           ///< solves of the model of the final numbers (model_name)
  std::string model_effort;          ///< ForwardModel::effort() after the fit (solver iterations)
  std::string global_stage;          ///< "multistart" or "siman"
  std::string global_model_name;     ///< the global stage's model (the surrogate, or model_name)
  long global_solves = 0;            ///< solves of the surrogate (0 without one)
  std::vector<double> global_costs;  ///< the surrogate's costs of the global candidates (with a surrogate)
  double prior_cost = 0.0;           ///< the priors' share of the least-squares cost, N^2
  double noise_sigma = 0.0;          ///< the noise level the priors were weighed against, N (0: no priors)
  double wall_seconds = 0.0;
  int threads = 1;
  int iterations = 0;
  /// Levenberg-Marquardt runs of the local stage that ran (restored ones included): at most
  /// FitOptions::local_runs, fewer when there were fewer candidate starts (or fewer that the model
  /// could evaluate).
  int local_runs = 0;
  std::string stop_reason;
  /// The costs of the local stage's candidate starts, in candidate order (the global stage's, or,
  /// with a surrogate, the final model's costs of the surrogate's best candidates).
  std::vector<double> start_costs;
  std::vector<double> prediction;  ///< the model's force at the optimum, Observations order
  Profile profile;
  std::vector<Confounding> confounded;
  std::vector<std::string> notes;  ///< what was fixed, what is not identifiable
  Linearisation linearisation;     ///< at the optimum (not kept by checkpoints: empty when restored)
};

/// True when `stop_reason` (FitResult::stop_reason) is one of the local stage's convergence tests
/// (the step, xtol, or the gradient, gtol), false for the iteration limit or a GSL error.
bool converged_stop(const std::string& stop_reason);

/// Checks the problem's priors: each names a free parameter, has a finite mean and a positive sd,
/// and no parameter has two (tmlab::Error naming both). fit() calls it; a caller may call it first
/// to refuse before computing.
void check_priors(const Problem& problem);

/// Fits `problem`. Deterministic for a given seed, independent of options.threads.
/// Throws tmlab::Error when no candidate start can be evaluated.
FitResult fit(const Problem& problem, const FitOptions& options);

}  // namespace tmlab::fit
