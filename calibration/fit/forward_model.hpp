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
};

}  // namespace tmlab::fit
