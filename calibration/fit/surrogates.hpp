// The closed-form forward models of a fit (fast surrogates; docs/identification.md):
//   indentation, sphere:  Hertz (elastic) or Lee-Radok (with Prony terms), times the Dimitriadis
//                         finite-layer factor when the sample is a layer (bonded or frictionless
//                         bottom) rather than a half-space. Exact for shallow indentation only
//                         (linear elasticity: the law's small-strain modulus is all it sees).
//   indentation, flat punch: Sneddon / Lee-Radok punch (half-space).
//   unconfined / confined compression, uniaxial tension: the homogeneous platen state of the
//                         hyperelastic law (closed_forms::platen_state); exact for frictionless
//                         platens, a bound for bonded ones.
// The data's JSON names the rig; make_surrogate_problem() checks that the data can be fitted by the
// surrogate and refuses, with a message naming the data set and test, what it cannot.
#pragma once

#include "calibration/data/measured_data.hpp"
#include "calibration/fit/forward_model.hpp"
#include "calibration/fit/model_spec.hpp"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace tmlab::fit {

/// The problem of `data` and `spec` without a forward model: the observations (with per-test
/// `weights`, test id -> weight, default 1), the law's parameters with start values from a modulus
/// estimate of the data, the SPEC's fixed values and then `fixes` applied. tmlab::Error for data
/// that cannot be fitted (a force against the sign convention, measured::check_force_sign; no
/// tests, zero force, non-finite samples, fewer samples than parameters), for a parameter fixed
/// twice (in the SPEC and by `fixes`, or twice in `fixes`) and a test weighted twice.
Problem make_data_problem(const measured::DataSet& data, const ModelSpec& spec,
                          const std::vector<std::pair<std::string, double>>& fixes = {},
                          const std::vector<std::pair<std::string, double>>& weights = {});

/// The closed-form surrogate of the data's rig; tmlab::Error naming what it cannot do (a law other
/// than stvk/neo_hookean on indentation, Prony terms on platen data, unloading under Lee-Radok ...).
std::unique_ptr<ForwardModel> make_surrogate_model(const measured::DataSet& data, const ModelSpec& spec);

/// Builds the problem for `data` and `spec`: the observations (with per-test `weights`, test id ->
/// weight, default 1), the law's parameters with the SPEC's fixed values and then `fixes` applied,
/// and the surrogate forward model of the data's rig. tmlab::Error for data or a model it cannot fit.
Problem make_surrogate_problem(const measured::DataSet& data, const ModelSpec& spec,
                               const std::vector<std::pair<std::string, double>>& fixes = {},
                               const std::vector<std::pair<std::string, double>>& weights = {});

}  // namespace tmlab::fit
