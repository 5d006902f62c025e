// The discretisation shift of an FE-rig fit (discretisation.hpp has the method).
#include "calibration/fit/discretisation.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/results/json_number.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace tmlab::fit {

RigForwardModelOptions refined_rig(const RigForwardModelOptions& coarse, double ratio) {
  if (!(ratio > 1.0) || !std::isfinite(ratio))
    throw Error("discretisation check: the refinement ratio must be > 1 (got " + significant(ratio, 6) + ")");
  RigForwardModelOptions fine = coarse;
  fine.mesh.cells = int(std::lround(double(coarse.mesh.cells) * ratio));
  fine.mesh.layers = int(std::lround(double(coarse.mesh.layers) * ratio));
  if (fine.mesh.cells <= coarse.mesh.cells || fine.mesh.layers <= coarse.mesh.layers)
    throw Error("discretisation check: --refine-ratio " + significant(ratio, 6) + " leaves the rig's mesh " +
                std::to_string(coarse.mesh.cells) + "," + std::to_string(coarse.mesh.layers) +
                " unrefined after rounding (" + std::to_string(fine.mesh.cells) + "," +
                std::to_string(fine.mesh.layers) + "): give a larger ratio");
  return fine;
}

std::vector<double> linearised_shift(const Linearisation& lin, const Observations& data,
                                     const std::vector<double>& f_coarse, const std::vector<double>& f_fine) {
  const std::size_t p = lin.free.size(), n = lin.n_data;
  if (p == 0) throw Error("discretisation check: the fit has no linearisation at its optimum");
  if (n != data.size() || f_coarse.size() != n || f_fine.size() != n || lin.jacobian.size() != n * p ||
      lin.normal_inverse.size() != p * p)
    throw Error("discretisation check: the forces and the fit's Jacobian have different sizes");
  // g = J^T W delta, then dt = -(J^T J)^{-1} g.
  std::vector<double> g(p, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double d = data.weights[data.test[i]] * (f_fine[i] - f_coarse[i]);
    for (std::size_t j = 0; j < p; ++j) g[j] += lin.jacobian[i * p + j] * d;
  }
  std::vector<double> dt(p, 0.0);
  for (std::size_t a = 0; a < p; ++a)
    for (std::size_t b = 0; b < p; ++b) dt[a] -= lin.normal_inverse[a * p + b] * g[b];
  return dt;
}

DiscretisationReport discretisation_report(const FitResult& r, const Problem& pr, const ForwardModel& fine,
                                           double ratio,
                                           const std::function<void(const std::string&)>& progress) {
  DiscretisationReport d;
  d.refine_ratio = ratio;
  d.coarse = rig_forward_model_size(*pr.model);
  d.fine = rig_forward_model_size(fine);
  d.peak_force = pr.data.peak_force;
  const Linearisation& lin = r.linearisation;
  if (lin.empty()) throw Error("discretisation check: the fit has no linearisation at its optimum");
  std::vector<double> x;
  for (const ParameterResult& q : r.parameters) x.push_back(q.value);
  const auto rig = [](const RigForwardModelSize& s) {
    return std::to_string(s.mesh.cells) + "," + std::to_string(s.mesh.layers) + " (" +
           std::to_string(s.tets) + " tets)";
  };
  if (progress)
    progress("discretisation check: one solve on the refined rig " + rig(d.fine) + " at the optimum, " +
             significant(double(d.fine.tets) / double(std::max<std::size_t>(1, d.coarse.tets)), 3) +
             " x the tets of the fit's rig " + rig(d.coarse) + " (it takes longer than one fit evaluation)");
  const auto t0 = std::chrono::steady_clock::now();
  try {
    d.fine_force = fine.predict(x);
  } catch (const Error& e) {
    throw Error(std::string("discretisation check: the refined rig cannot be solved at the optimum: ") +
                e.what());
  }
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::vector<double>& fc = r.prediction;
  const std::vector<double> dt = linearised_shift(lin, pr.data, fc, d.fine_force);
  double ss = 0.0;
  for (std::size_t i = 0; i < fc.size(); ++i) {
    const double c = d.fine_force[i] - fc[i];
    ss += c * c;
    d.change_max = std::max(d.change_max, std::abs(c));
  }
  d.change_rms = fc.empty() ? 0.0 : std::sqrt(ss / double(fc.size()));
  for (std::size_t i = 0; i < r.parameters.size(); ++i) {
    const ParameterResult& q = r.parameters[i];
    ParameterShift s;
    s.name = q.name;
    s.unit = q.unit;
    s.fixed = q.fixed;
    s.value = q.value;
    s.standard_error = q.standard_error;
    s.lower = q.lower95;
    s.upper = q.upper95;
    const auto at = std::find(lin.free.begin(), lin.free.end(), i);
    if (!q.fixed && q.identifiable && at != lin.free.end()) {
      const std::size_t j = std::size_t(at - lin.free.begin());
      s.known = true;
      s.shift = lin.dxdt[j] * dt[j];
      s.shift_relative = q.value != 0.0 ? s.shift / std::abs(q.value) : 0.0;
      s.shift_per_se =
          std::isfinite(q.standard_error) && q.standard_error > 0.0 ? s.shift / q.standard_error : 0.0;
      const Parameter& b = pr.parameters[i];
      s.lower = std::max(b.lower, q.lower95 + std::min(0.0, s.shift));
      s.upper = std::min(b.upper, q.upper95 + std::max(0.0, s.shift));
      s.warning = std::isfinite(q.standard_error) && std::abs(s.shift) > q.standard_error;
      if (s.warning)
        d.warnings.push_back(
            "the discretisation shift of " + q.name + " (" + significant(s.shift, 3) + " " + q.unit + ", " +
            significant(100.0 * s.shift_relative, 3) + " %) exceeds its statistical standard error (" +
            significant(q.standard_error, 3) + " " + q.unit + ") " +
            significant(std::abs(s.shift_per_se), 3) + " times: the rig's mesh, not the data, limits " +
            q.name + " (refine the rig: --mesh)");
    }
    d.parameters.push_back(s);
  }
  if (progress)
    progress("discretisation check: refined solve in " + significant(d.seconds, 3) +
             " s; force change at the optimum RMS " + significant(d.change_rms, 4) + " N (" +
             significant(100.0 * d.change_rms / std::max(d.peak_force, 1e-300), 3) + " % of peak), max " +
             significant(d.change_max, 4) + " N");
  return d;
}

std::string discretisation_option_text(const DiscretisationReport& d) {
  return "--mesh " + std::to_string(d.coarse.mesh.cells) + "," + std::to_string(d.coarse.mesh.layers) +
         " --refine-ratio " + significant(d.refine_ratio, 6) + " (refined rig " +
         std::to_string(d.fine.mesh.cells) + "," + std::to_string(d.fine.mesh.layers) +
         "; --discretisation-check off skips it)";
}

namespace {

nlohmann::json mesh_json(const RigForwardModelSize& s) {
  return {{"cells", s.mesh.cells}, {"layers", s.mesh.layers}, {"grading", s.mesh.grading},
          {"tets", s.tets},        {"nodes", s.nodes},        {"tests", s.tests}};
}

}  // namespace

nlohmann::json discretisation_json(const DiscretisationReport& d) {
  using nlohmann::json;
  return {
      {"method",
       "one forward solve on the refined rig at the optimum; shift = -(J^T J)^-1 J^T W (F_fine - F_coarse) "
       "in the fit's internal coordinates (J, W and (J^T J)^-1 of the fit's covariance), times dx/dt; "
       "value + shift is the refined rig's linearised estimate"},
      {"refine_ratio", d.refine_ratio},
      {"option", discretisation_option_text(d)},
      {"rig", mesh_json(d.coarse)},
      {"refined_rig", mesh_json(d.fine)},
      {"force_change_rms_N", d.change_rms},
      {"force_change_max_N", d.change_max},
      {"force_change_rms_percent_of_peak", 100.0 * d.change_rms / std::max(d.peak_force, 1e-300)},
      {"refined_solve_seconds", d.seconds},
      {"warning_rule", "|shift| > statistical standard error"},
      {"warnings", d.warnings}};
}

nlohmann::json parameter_discretisation_json(const ParameterShift& s, const DiscretisationReport& d) {
  using nlohmann::json;
  const auto known = [&](double v) { return s.known ? finite_or_null(v) : json(nullptr); };
  return {
      {"shift", known(s.shift)},
      {"shift_relative", known(s.shift_relative)},
      {"shift_per_standard_error", known(s.shift_per_se)},
      {"interval95_with_discretisation", {known(s.lower), known(s.upper)}},
      {"warning", s.warning},
      {"refined_mesh", {{"cells", d.fine.mesh.cells}, {"layers", d.fine.mesh.layers}, {"tets", d.fine.tets}}},
      {"option", discretisation_option_text(d)}};
}

}  // namespace tmlab::fit
