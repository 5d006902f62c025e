// How wrong are the Prony recursions? (issue 5, `tmlab hereditary`; docs/hereditary.md)
//
// The history variable of one Prony term, h(t) = int_0^t exp(-(t-s)/tau) X_e'(s) ds, advanced by
// ViscoelasticStVK's recursions h^{n+1} = a h^n + c (X_e^{n+1} - X_e^n) with (a, c) from
// recursion_factors() (the model's own code), is compared with the exact hereditary integral for
// prescribed driver histories X_e(t):
//
//   X_e(t) = p(eps(t)),   p(eps) = (1 + eps)(eps + eps^2/2)
//
// the nominal stress of a 1-D St Venant-Kirchhoff bar at strain eps, normalised by E_inf (the
// nonlinearity of the model is present; DriverLaw::Linear uses X_e = eps for closed-form checks).
// Strain histories eps(t) (all start at eps(0) = 0, so there is no jump at t = 0):
//   ramp_hold: eps0 min(t/T_r, 1)                      (a kink at T_r)
//   sine:      eps0 sin(omega t)
//   random:    eps0 sum_k w_k [sin(omega_k t + phi_k) - sin(phi_k)] / sum_k w_k  (seeded; omega_k
//              log-uniform in [omega_min, omega_max], phi_k uniform, w_k uniform in [0.5, 1])
//
// Exact reference at the step times t_n = n dt: the semigroup form
//   h(t_{n+1}) = exp(-dt/tau) h(t_n) + int_{t_n}^{t_{n+1}} exp(-(t_{n+1}-s)/tau) X_e'(s) ds
// with each step integral by convolve_rate (hereditary_integral.hpp, 8-point Gauss-Legendre on
// panels no wider than min(tau, 1/omega_max, dt)/4 and split at kinks); exact up to round-off and a
// quadrature error that exact_history(..., refine = 2) bounds.
//
// Error of a run: max_n |X_rec(t_n) - X(t_n)| / max_n |X(t_n)|, X = X_e + alpha h (one Prony term).
//
// The liver relaxation (paper_experiments.hpp fig6): the coupled quasi-static solve (StaticSolver +
// ViscoelasticStVK) per recursion and dt, the reaction force of the pushed node against a Richardson-
// extrapolated fine exact_linear reference (checked against the midpoint one), and the recursion error
// isolated along the reference path (the X_e of the tets at the pushed node recorded from the finest
// run and convolved exactly with StoredHistory).
#pragma once

#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace tmlab::tm {

enum class DriverLaw { Stvk1d, Linear };

class DriverHistory {
 public:
  enum class Kind { RampHold, Sine, Random };
  /// eps0 min(t/ramp_time, 1) on [0, t_end]. Throws tmlab::Error for ramp_time <= 0 or t_end <= 0.
  static DriverHistory ramp_hold(std::string name, double strain, double ramp_time, double t_end,
                                 DriverLaw law = DriverLaw::Stvk1d);
  /// eps0 sin(omega t). Throws for omega <= 0.
  static DriverHistory sine(std::string name, double strain, double omega, double t_end,
                            DriverLaw law = DriverLaw::Stvk1d);
  /// A seeded sum of `terms` sinusoids (see the file comment). Throws for terms < 1 or a bad range.
  static DriverHistory random(std::string name, double strain, std::uint64_t seed, int terms,
                              double omega_min, double omega_max, double t_end,
                              DriverLaw law = DriverLaw::Stvk1d);

  const std::string& name() const { return name_; }
  Kind kind() const { return kind_; }
  double t_end() const { return t_end_; }
  double strain(double t) const;
  double strain_rate(double t) const;
  double value(double t) const;  ///< X_e(t)
  double rate(double t) const;   ///< X_e'(t) (the right derivative at a kink)
  /// Times in (0, t_end] where X_e' jumps (the end of the ramp).
  const std::vector<double>& kinks() const { return kinks_; }
  /// The fastest angular frequency of the history (0 for ramp_hold).
  double max_frequency() const { return omega_max_; }
  /// Kind, parameters, seed and the drawn coefficients (stored in the output).
  nlohmann::json describe() const;

 private:
  DriverHistory(std::string name, Kind kind, DriverLaw law, double strain, double t_end);
  std::string name_;
  Kind kind_ = Kind::RampHold;
  DriverLaw law_ = DriverLaw::Stvk1d;
  double strain_ = 0.0, ramp_ = 1.0, t_end_ = 1.0, omega_max_ = 0.0;
  std::uint64_t seed_ = 0;
  std::vector<double> omega_, phase_, weight_;
  std::vector<double> kinks_;
};

/// Number of steps of size dt that cover [0, x.t_end()]: ceil(t_end/dt) (>= 1).
int steps_to_cover(const DriverHistory& x, double dt);

/// Exact h(t_n), n = 0..steps (t_n = n dt), one term of relaxation time tau. `refine` multiplies the
/// number of quadrature panels (refine = 2 gives the quadrature check).
std::vector<double> exact_history(const DriverHistory& x, double tau, double dt, int steps, int refine = 1);
/// h^n of ViscoelasticStVK's recursion (recursion_factors) from h^0 = 0, X_e^0 = X_e(0).
std::vector<double> recursion_history(const DriverHistory& x, ViscoelasticOptions::Integration scheme,
                                      double tau, double dt, int steps);

/// One run: error of a recursion against the exact integral.
struct RecursionError {
  double dt = 0.0, dt_over_tau = 0.0;
  double error = 0.0;       ///< max_n |X_rec - X| / max_n |X|
  double quadrature = 0.0;  ///< max_n |h_exact(refine 1) - h_exact(refine 2)| / max_n |X| (reference check)
  int steps = 0;
};
RecursionError recursion_error(const DriverHistory& x, ViscoelasticOptions::Integration scheme, double alpha,
                               double tau, double dt, bool quadrature_check = false);

/// Least-squares slope of log(error) against log(dt) over the points with dt_over_tau <= max_dt_over_tau
/// and error > floor; NaN when fewer than 3 points qualify.
double fitted_order(const std::vector<RecursionError>& runs, double max_dt_over_tau, double floor = 1e-13);
/// The smallest dt/tau at which the error first reaches `level` scanning upwards (log-linear
/// interpolation between neighbours); +inf when it never does, 0 when the first point already does.
double breakdown_dt_over_tau(const std::vector<RecursionError>& runs, double level);

/// Per history and scheme: the sweep, fitted order and breakdown thresholds.
struct SweepResult {
  std::string history, scheme;
  std::vector<RecursionError> runs;
  double order = 0.0;
  double fit_max_dt_over_tau = 0.0;  ///< the asymptotic window of the fit
  double breakdown_1pct = 0.0, breakdown_10pct = 0.0;
};

struct StudyOptions {
  double alpha = 1.0;               ///< Prony weight of the single term (long-term normalised)
  double tau = 1.0;                 ///< s; the scalar histories are defined in units of tau
  std::vector<double> dt_over_tau;  ///< the sweep (default: 10^(k/4), k = -12..4)
  std::uint64_t seed = 20111101;    ///< random history
  bool quick = false;               ///< coarser sweep and shorter histories (tests, smoke runs)
};

/// The histories of the study (names: ramp_hold, ramp_hold_fast, sine_w0.1, sine_w1, sine_w10,
/// random), filtered by the groups in `groups` ("ramp_hold" selects both ramps, "sine" all three
/// sines, "random"). Throws tmlab::Error naming an unknown group.
std::vector<DriverHistory> study_histories(const std::vector<std::string>& groups,
                                           const StudyOptions& options);
/// Default sweep of dt/tau (quick: 10^(k/2), k = -6..2).
std::vector<double> default_sweep(bool quick);
/// Runs the sweep for one history and scheme; `progress` (may be empty) is called per run.
SweepResult sweep(const DriverHistory& x, ViscoelasticOptions::Integration scheme,
                  const StudyOptions& options, const std::function<void(const std::string&)>& progress = {});

/// A time history X(t_n) of one run next to the exact X at the same times (the oscillation plot).
struct TimeHistory {
  std::vector<double> t, x_rec, x_exact, h_rec, h_exact;
};
TimeHistory time_history(const DriverHistory& x, ViscoelasticOptions::Integration scheme, double alpha,
                         double tau, double dt);
/// Number of sign changes of h^{n+1} - h^n over the steps after t_from (an oscillating recursion
/// shows many; a monotone decay none).
int sign_changes(const TimeHistory& th, double t_from);

// ---------------------------------------------------------------------------------- liver

struct LiverStudyOptions {
  int node = 2;  ///< fig6 node (1-based) pushed
  std::vector<double> dts = {0.2, 0.1, 0.05, 0.025};
  std::vector<double> reference_dts = {0.0125, 0.00625};  ///< Richardson pair (ratio 2)
  /// nodal_force (the seed's form, the paper's experiment) or pk2 (objective; the isolated error and
  /// the path checks need the nodal elastic forces and are NaN for pk2).
  std::string history = "nodal_force";
};

struct LiverRun {
  std::string scheme;
  double dt = 0.0;
  double error = 0.0;           ///< coupled: max_t |F - F_ref| / max |F_ref| at t = k dt_max
  double isolated_error = 0.0;  ///< recursion alone along the reference path (same norm)
  /// max_t |y_run - y_ref| / max |F_ref|, y the elastic part of the reaction (sum over the pushed
  /// node's tets of X_e at the node): how much the recursion changed the displacement path.
  double path_deviation = 0.0;
  double seconds = 0.0;
  std::vector<double> t, force;  ///< reaction of the pushed node, N (pushing direction positive)
};

struct LiverStudy {
  std::vector<LiverRun> runs;
  std::vector<double> t_ref, force_ref;  ///< Richardson exact_linear reference at the coarsest times
  double reference_check = 0.0;          ///< max |F_ref(exact_linear) - F_ref(midpoint)| / max |F_ref|
  double richardson_correction = 0.0;    ///< max |F_ref - F_finest| / max |F_ref|
  double path_check = 0.0;               ///< reaction from the exact history along the finest path vs F_ref
  double path_quadrature = 0.0;          ///< the exact path history with half the samples vs all of them
  double peak_force = 0.0;
  int num_tets = 0, num_nodes = 0, node_tets = 0;
  double seconds = 0.0;
  nlohmann::json describe;
};

/// Runs the liver relaxation study from the paper parameter document (`where` names it in errors).
LiverStudy liver_study(const nlohmann::json& params, const std::string& where, const std::string& tmlab_root,
                       const LiverStudyOptions& options,
                       const std::function<void(const std::string&)>& progress = {});

}  // namespace tmlab::tm
