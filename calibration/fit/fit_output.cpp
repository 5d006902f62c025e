// What a fit writes and says: see fit_output.hpp.
#include "calibration/fit/fit_output.hpp"

#include "calibration/fit/relaxation_bands.hpp"
#include "calibration/fit/surrogates.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/process.hpp"
#include "core/constitutive/law_catalogue.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/results/json_number.hpp"

#include <cmath>
#include <cstdio>
#include <iomanip>

namespace tmlab::fit {

namespace fs = std::filesystem;

nlohmann::json parameter_json(const ParameterResult& p, const Parameter* bounds) {
  using nlohmann::json;
  return {{"name", p.name},
          {"value", p.value},
          {"unit", p.unit},
          {"fixed", p.fixed},
          {"transform", p.transform},
          {"standard_error", finite_or_null(p.standard_error)},
          {"interval95", {finite_or_null(p.lower95), finite_or_null(p.upper95)}},
          {"identifiable", p.identifiable},
          {"bounds", bounds ? json{finite_or_null(bounds->lower), finite_or_null(bounds->upper)}
                            : json{nullptr, nullptr}},
          {"at_bound", bounds ? bound_reached(*bounds, p.value) : std::string()}};
}

std::string local_runs_note(const FitResult& r, const FitOptions& o) {
  if (r.local_runs >= o.local_runs) return "";
  return "--local-runs " + std::to_string(o.local_runs) + " asked for more Levenberg-Marquardt runs than " +
         "there were candidate starts to run them from: " + std::to_string(r.local_runs) + " ran (" +
         (o.global == GlobalStage::Siman ? "simulated annealing gives 2 starts: its best state and the "
                                           "parameters' values"
                                         : "--starts " + std::to_string(o.starts) +
                                               ", each run from one start the model could evaluate") +
         ")";
}

nlohmann::json to_json(const FitResult& r, const Problem& pr, const FitOptions& o, const ModelSpec& spec,
                       const DiscretisationReport* disc) {
  using nlohmann::json;
  json j;
  j["model"] = {{"spec", spec.text},
                {"law", to_string(spec.law)},
                {"forward_model", r.model_name},
                {"description", r.model_description}};
  j["parameters"] = json::array();
  for (const auto& p : r.parameters) {
    const Parameter* bounds = nullptr;
    for (const auto& q : pr.parameters)
      if (q.name == p.name) bounds = &q;
    j["parameters"].push_back(parameter_json(p, bounds));
    if (disc)
      for (const ParameterShift& s : disc->parameters)
        if (s.name == p.name)
          j["parameters"].back()["discretisation"] = parameter_discretisation_json(s, *disc);
  }
  j["correlation"] = {{"parameters", r.free_names}, {"matrix", r.correlation}};
  j["cost"] = {{"kind", r.cost_name}, {"value", r.cost}};
  j["residual_rms_N"] = r.rms;
  j["residual_rms_percent_of_peak"] = r.rms_percent_peak;
  j["peak_force_N"] = pr.data.peak_force;
  j["sse_N2"] = r.sse;
  j["samples"] = r.n;
  j["free_parameters"] = r.k;
  j["aic"] = r.aic;
  j["bic"] = r.bic;
  j["forward_solves"] = r.forward_solves;
  j["wall_seconds"] = r.wall_seconds;
  j["threads"] = r.threads;
  j["local_iterations"] = r.iterations;
  j["stop_reason"] = r.stop_reason;
  j["global_stage"] = {{"kind", r.global_stage},
                       {"model", r.global_model_name},
                       {"surrogate_solves", r.global_solves},
                       {"starts", o.global == GlobalStage::Siman ? 1 : o.starts},
                       {"local_runs", r.local_runs},
                       {"local_runs_requested", o.local_runs},
                       {"seed", o.seed},
                       {"start_costs", json::array()},
                       {"surrogate_costs", json::array()}};
  if (o.global == GlobalStage::Siman)
    j["global_stage"]["siman"] = {{"evaluations", o.siman_evaluations},
                                  {"iters_per_temperature", o.siman_iters_per_temperature},
                                  {"step", o.siman_step},
                                  {"t_initial", o.siman_t_initial},
                                  {"t_min", o.siman_t_min},
                                  {"energy", "ln(cost)"}};
  for (const double c : r.start_costs) j["global_stage"]["start_costs"].push_back(finite_or_null(c));
  for (const double c : r.global_costs) j["global_stage"]["surrogate_costs"].push_back(finite_or_null(c));
  j["priors"] = json::array();
  for (const auto& q : pr.priors)
    j["priors"].push_back({{"parameter", q.parameter}, {"mean", q.mean}, {"sd", q.sd}});
  if (!pr.priors.empty()) {
    j["noise_sigma_N"] = r.noise_sigma;
    j["prior_cost_N2"] = r.prior_cost;
  }
  j["geodesic_acceleration"] = o.geodesic;
  j["confounded"] = json::array();
  for (const auto& c : r.confounded)
    j["confounded"].push_back({{"a", c.a}, {"b", c.b}, {"correlation", c.correlation}, {"note", c.note}});
  j["notes"] = r.notes;
  if (const std::string n = local_runs_note(r, o); !n.empty()) j["notes"].push_back(n);
  if (disc) {
    j["discretisation"] = discretisation_json(*disc);
    for (const std::string& w : disc->warnings) j["notes"].push_back("WARNING: " + w);
  }
  if (!r.profile.parameter.empty()) {
    json pts = json::array();
    for (const auto& q : r.profile.points)
      pts.push_back({{"value", q.value}, {"sse_N2", finite_or_null(q.sse)}});
    j["profile"] = {{"parameter", r.profile.parameter},
                    {"points", pts},
                    {"interval95",
                     {r.profile.lower_found ? finite_or_null(r.profile.lower95) : json(nullptr),
                      r.profile.upper_found ? finite_or_null(r.profile.upper95) : json(nullptr)}},
                    {"criterion", "n ln(SSE/SSE_min) <= chi2_1(0.95); null: beyond the grid"}};
  }
  j["tests"] = json::array();
  for (std::size_t k = 0; k < pr.data.test_ids.size(); ++k)
    j["tests"].push_back({{"id", pr.data.test_ids[k]}, {"weight", pr.data.weights[k]}});
  return j;
}

void write_fit_h5(const fs::path& path, const measured::DataSet& data, const FitResult& r) {
  H5File h5 = H5File::create(path.string());
  std::size_t offset = 0;
  for (std::size_t k = 0; k < data.tests.size(); ++k) {
    const measured::Test& t = data.tests[k];
    char g[32];
    std::snprintf(g, sizeof g, "/tests/%03zu", k);
    std::vector<double> model(r.prediction.begin() + long(offset),
                              r.prediction.begin() + long(offset + t.size()));
    std::vector<double> res(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) res[i] = model[i] - t.force_N[i];
    h5.write(std::string(g) + "/time_s", t.time_s, {t.size()});
    h5.write(std::string(g) + "/displacement_m", t.displacement_m, {t.size()});
    h5.write(std::string(g) + "/force_N", t.force_N, {t.size()});
    h5.write(std::string(g) + "/model_force_N", model, {t.size()});
    h5.write(std::string(g) + "/residual_N", res, {t.size()});
    h5.set_attribute(g, "id", t.id);
    offset += t.size();
  }
  if (!r.profile.points.empty()) {
    std::vector<double> v, s;
    for (const auto& q : r.profile.points) {
      v.push_back(q.value);
      s.push_back(q.sse);
    }
    h5.write("/profile/value", v, {v.size()});
    h5.write("/profile/sse_N2", s, {s.size()});
    h5.set_attribute("/profile", "parameter", r.profile.parameter);
  }
  std::vector<double> corr;
  for (const auto& row : r.correlation) corr.insert(corr.end(), row.begin(), row.end());
  if (!corr.empty()) h5.write("/correlation", corr, {r.correlation.size(), r.correlation.size()});
  h5.close();
}

void print_fit_report(std::ostream& os, const FitResult& r, const Problem& problem, const FitOptions& o,
                      const DiscretisationReport* disc) {
  os << std::left << std::setw(10) << "parameter" << std::right << std::setw(14) << "value" << std::setw(6)
     << "unit" << std::setw(14) << "std error" << std::setw(30) << "95 % interval";
  if (disc) os << std::setw(24) << "discretisation shift";
  os << "\n";
  for (std::size_t i = 0; i < r.parameters.size(); ++i) {
    const ParameterResult& q = r.parameters[i];
    os << std::left << std::setw(10) << q.name << std::right << std::setw(14) << significant(q.value, 6)
       << std::setw(6) << q.unit << std::setw(14)
       << (q.fixed                           ? "fixed"
           : std::isfinite(q.standard_error) ? significant(q.standard_error, 3)
                                             : "inf")
       << std::setw(30)
       << (q.fixed ? "" : "[" + significant(q.lower95, 5) + ", " + significant(q.upper95, 5) + "]");
    if (disc && i < disc->parameters.size()) {
      const ParameterShift& s = disc->parameters[i];
      os << std::setw(24)
         << (s.known ? significant(s.shift, 3) + " (" + significant(100.0 * s.shift_relative, 2) + " %, " +
                           significant(s.shift_per_se, 2) + " SE)"
                     : std::string(q.fixed ? "" : "n/a"));
    }
    os << "\n";
  }
  if (disc) {
    os << "discretisation shift: the linearised move of each parameter on the rig refined "
       << significant(disc->refine_ratio, 3) << "x in h (" << discretisation_option_text(*disc)
       << "); force change at the optimum RMS " << significant(disc->change_rms, 4) << " N\n";
    for (const std::string& w : disc->warnings) os << "WARNING: " << w << "\n";
  }
  os << "cost (" << r.cost_name << ") " << significant(r.cost, 6) << "; residual RMS "
     << significant(r.rms, 4) << " N = " << significant(r.rms_percent_peak, 3) << " % of peak "
     << significant(problem.data.peak_force, 5) << " N; AIC " << significant(r.aic, 7) << ", BIC "
     << significant(r.bic, 7) << "\n"
     << r.forward_solves << " forward solves (" << r.model_name << ")"
     << (r.global_solves ? " + " + std::to_string(r.global_solves) + " (" + r.global_model_name + ", " +
                               r.global_stage + " global stage)"
                         : std::string(" (") + r.global_stage + " global stage)")
     << " on " << r.threads << " threads in " << significant(r.wall_seconds, 3) << " s\n"
     << "the numbers above are from the forward model '" << r.model_name << "'\n";
  if (!r.profile.parameter.empty())
    os << "profile likelihood of " << r.profile.parameter << ": 95 % interval ["
       << (r.profile.lower_found ? significant(r.profile.lower95, 5) : std::string("beyond grid")) << ", "
       << (r.profile.upper_found ? significant(r.profile.upper95, 5) : std::string("beyond grid")) << "]\n";
  for (const auto& c : r.confounded)
    os << "confounded: " << c.a << " and " << c.b << " (correlation " << significant(c.correlation, 4)
       << "): " << c.note << "\n";
  for (const auto& n : r.notes) os << "note: " << n << "\n";
  if (const std::string n = local_runs_note(r, o); !n.empty()) os << "note: " << n << "\n";
}

void print_fit_plan(std::ostream& os, const std::string& data_name, const ModelSpec& spec,
                    const std::string& global, const std::string& which, const Problem& problem,
                    const std::string& why_no_closed_form) {
  os << "fit " << data_name << " with " << spec.text << " (" << problem.model->description() << ")\n";
  if (problem.global_model)
    os << "global stage (" << global << ") on the closed form: " << problem.global_model->description()
       << "; local stage and every reported number: " << problem.model->name() << "\n";
  else if (which == "fe_rig" && !why_no_closed_form.empty())
    os << "global stage on the FE rig itself (no closed form: " << why_no_closed_form << ")\n";
}

std::string result_name(const std::string& data_name, const ModelSpec& spec) {
  return data_name + "-" + to_string(spec.law) +
         (law_descriptor(spec.law).has_terms() ? std::to_string(spec.ogden_terms) : "") +
         (spec.prony_terms ? "-prony" + std::to_string(spec.prony_terms) : "");
}

nlohmann::json summary_json(const FitResult& r, const ModelSpec& spec, const std::string& plots) {
  return {{"model", spec.text},
          {"forward_model", r.model_name},
          {"residual_rms_percent_of_peak", r.rms_percent_peak},
          {"aic", r.aic},
          {"bic", r.bic},
          {"forward_solves", r.forward_solves},
          {"global_stage", r.global_stage},
          {"surrogate_solves", r.global_solves},
          {"wall_seconds", r.wall_seconds},
          {"plots", plots}};
}

std::string write_fit_plots(const fs::path& dir, const fs::path& tmlab_root, const std::string& title) {
  const ProcessStatus ps = run_python(tmlab_root / "calibration" / "fit" / "python" / "tmlab_fit_plot.py",
                                      {dir.string(), title}, ProcessOutput::discard());
  return ps.ok() ? "ok" : "failed (" + ps.describe() + ")";
}

Problem make_problem(const measured::DataSet& data, const ModelSpec& spec,
                     const std::vector<std::pair<std::string, double>>& fixes,
                     const std::vector<std::pair<std::string, double>>& weights, const std::string& which,
                     const RigForwardModelOptions& fe, std::string& why_no_closed_form) {
  if (which == "closed_form") return make_surrogate_problem(data, spec, fixes, weights);
  if (which == "fe_rig") return make_rig_forward_problem(data, spec, fixes, weights, fe, &why_no_closed_form);
  if (which != "auto") throw Error("forward model must be auto, closed_form or fe_rig (got '" + which + "')");
  // auto: the closed form when it covers the data and the law, else the FE rig.
  try {
    return make_surrogate_problem(data, spec, fixes, weights);
  } catch (const Error& e) {
    why_no_closed_form = e.what();
  }
  return make_rig_forward_problem(data, spec, fixes, weights, fe);
}

}  // namespace tmlab::fit
