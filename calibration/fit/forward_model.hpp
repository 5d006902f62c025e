// A forward model of a fit: parameter values (physical units, all parameters, fixed ones included)
// -> the predicted force at every sample of the data, all tests concatenated in the data's order.
// predict() is const and must be safe to call from several threads at once (the fit runs forward
// solves of different candidates in parallel).
#pragma once

#include "calibration/fit/parameter.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tmlab::fit {

/// The measured forces a fit compares with, flattened over the tests.
struct Observations {
  std::vector<double> force;          ///< N, every sample of every test
  std::vector<std::size_t> test;      ///< the test index of each sample
  std::vector<std::string> test_ids;  ///< one per test ("" when the data has no test_id)
  std::vector<double> weights;        ///< one per test (default 1): residual_i = w (model - data)
  double peak_force = 0.0;            ///< max |force| over every sample, N
  std::size_t size() const { return force.size(); }
};

/// The solver state one prediction leaves behind (an FE model: its displacements and contact
/// multipliers at every sample), from which a prediction at nearby parameters may start its
/// iterations. Opaque to the fitter; a model's own subclass.
struct WarmStart {
  virtual ~WarmStart() = default;
};

class ForwardModel {
 public:
  virtual ~ForwardModel() = default;
  /// A short identifier ("hertz_sphere", "lee_radok_sphere", "platen_unconfined", ...).
  virtual std::string name() const = 0;
  /// One sentence on what is computed and where it is exact.
  virtual std::string description() const = 0;
  /// Forces at every sample (Observations order) for physical parameter values `x`. Throws
  /// tmlab::Error when the model cannot be evaluated there (the fit treats it as a rejected trial).
  virtual std::vector<double> predict(const std::vector<double>& x) const = 0;
  /// The relative step of the forward-difference Jacobian in the internal coordinates: small for
  /// closed forms (round-off only), larger for iterative solvers whose forces carry the solver's
  /// tolerance (the difference must stand well above it).
  virtual double jacobian_step() const { return 1e-7; }
  /// predict(x) with the solver started from `from` (the state a prediction of this model left at
  /// nearby parameters; null: started as predict does), keeping this prediction's state in *keep
  /// (when keep is not null). Only the starting iterates change, not the equations or the stopping
  /// tests: the forces agree with predict(x) to the solver's tolerance. The fitter uses it for the
  /// columns of its finite-difference Jacobians. Default: predict(x), no state kept.
  virtual std::vector<double> predict_warm(const std::vector<double>& x, const WarmStart* from,
                                           std::shared_ptr<const WarmStart>* keep) const {
    (void)from;
    if (keep) keep->reset();
    return predict(x);
  }
  /// The solver effort of every prediction so far, one line ("" when the model has none to report:
  /// closed forms).
  virtual std::string effort() const { return {}; }
};

/// A Gaussian prior on one parameter (regularisation, docs/identification.md): the residual
/// sigma (x - mean) / sd is appended to the force residuals, sigma the noise standard deviation of
/// the data (N), so that least squares minimises SSE / sigma^2 + ((x - mean) / sd)^2, the negative
/// log posterior of Gaussian noise and this prior.
struct Prior {
  std::string parameter;
  double mean = 0.0, sd = 0.0;  ///< physical units, sd > 0
};

/// Everything a fit needs: the parameters (with the SPEC's and the command line's fixed values
/// applied), the forward model and the data.
struct Problem {
  std::vector<Parameter> parameters;
  std::unique_ptr<ForwardModel> model;
  Observations data;
  /// Maps physical values to the canonical one of equivalent parameter sets (e.g. Prony terms
  /// sorted by relaxation time): exchangeable terms would otherwise be reported in whichever order
  /// the optimiser happened to find them. Empty: the identity.
  std::function<std::vector<double>(std::vector<double>)> canonical;
  /// The model of the global stage (a closed-form surrogate of `model`); null: `model` itself. The
  /// local stage and every reported number use `model`.
  std::unique_ptr<ForwardModel> global_model;
  std::vector<Prior> priors;
  /// The noise standard deviation the priors are weighed against, N; 0: estimated from the data
  /// (noise_sigma() below).
  double noise_sigma = 0.0;
};

/// The noise standard deviation of the measured forces from their second differences within each
/// test: for a smooth curve sampled densely, y_{i+1} - 2 y_i + y_{i-1} is mostly noise, of variance
/// 6 sigma^2; the median absolute value (robust against the kinks of a ramp-hold history) gives
/// sigma = median|d2| / (0.6745 sqrt 6). 0 when no test has 3 samples.
double noise_sigma(const Observations& data);

}  // namespace tmlab::fit
