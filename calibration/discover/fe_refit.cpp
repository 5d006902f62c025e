#include "calibration/discover/fe_refit.hpp"

#include "calibration/fit/discretisation.hpp"
#include "calibration/fit/rig_forward_model.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"

#include <chrono>
#include <cmath>

namespace tmlab::discover {

measured::DataSet decimated_data(const measured::DataSet& data, const Prepared& p, bool loading_only,
                                 std::size_t max_samples, std::vector<std::vector<std::size_t>>* kept) {
  // The samples of each test the rig sees: up to the first unloading sample when loading_only.
  std::vector<std::size_t> ends;
  std::size_t total = 0;
  for (const Series& s : p.series) {
    double dmax = 0.0;
    std::size_t n = 0;
    for (; n < s.t.size(); ++n) {
      if (loading_only && s.d[n] < dmax - 1e-9 * p.max_depth) break;  // the first unloading sample
      dmax = std::max(dmax, s.d[n]);
    }
    ends.push_back(n);
    total += n;
  }
  const std::size_t stride =
      std::max<std::size_t>(1, (total + max_samples - 1) / std::max<std::size_t>(1, max_samples));
  measured::DataSet d;
  d.meta = data.meta;
  if (kept) kept->clear();
  for (std::size_t k = 0; k < p.series.size(); ++k) {
    const Series& s = p.series[k];
    measured::Test t;
    t.id = s.id;
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < ends[k]; ++i) {
      if (i % stride != 0 && i + 1 != ends[k]) continue;
      idx.push_back(i);
      t.time_s.push_back(s.t[i]);
      t.displacement_m.push_back(s.d[i]);
      t.force_N.push_back(s.f[i]);
    }
    d.tests.push_back(std::move(t));
    if (kept) kept->push_back(std::move(idx));
  }
  measured::validate(d);
  return d;
}

namespace {

double rms_of(const std::vector<double>& model, const fit::Observations& obs) {
  double s = 0.0;
  for (std::size_t i = 0; i < obs.size(); ++i) s += (model[i] - obs.force[i]) * (model[i] - obs.force[i]);
  return obs.size() ? std::sqrt(s / double(obs.size())) : 0.0;
}

FeRefit refit_one(const measured::DataSet& dec, const std::vector<std::vector<std::size_t>>& kept,
                  const std::string& which, const Fitted& f, const Options& o, const FeRefitOptions& fo) {
  const auto t0 = std::chrono::steady_clock::now();
  FeRefit r;
  r.which = which;
  r.model = f.structure.label();
  // The closed form on the samples the FE rig sees (indentation: loading and hold only).
  double sse = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < dec.tests.size(); ++k)
    for (std::size_t i = 0; i < dec.tests[k].size(); ++i, ++n)
      sse += std::pow(f.prediction[k][kept[k][i]] - dec.tests[k].force_N[i], 2);
  r.closed_form_rms = n ? std::sqrt(sse / double(n)) : 0.0;
  if (!f.structure.effects.empty()) {
    std::string list;
    for (const auto& e : f.structure.effects) list += (list.empty() ? "" : ", ") + e;
    r.why_not = "the FE rig models the law and the Prony terms only; " + list +
                " changes the closed-form forward model only";
    return r;
  }
  const fit::ModelSpec spec = model_spec(f.structure);
  std::vector<std::pair<std::string, double>> fixes;
  for (std::size_t i = 0; i < f.parameters.size(); ++i)
    if (f.parameters[i].fixed) fixes.emplace_back(f.parameters[i].name, f.x[i]);
  fit::RigForwardModelOptions feo;
  feo.mesh = fo.mesh;
  feo.substeps = fo.substeps;
  fit::Problem pr;
  try {
    pr = fit::make_rig_forward_problem(dec, spec, fixes, {}, feo);
  } catch (const Error& e) {
    r.why_not = std::string("the FE rig cannot be built: ") + e.what();
    return r;
  }
  // Start at the closed-form optimum (same parameter names: both come from fit::law_parameters).
  std::vector<double> x(pr.parameters.size());
  for (std::size_t i = 0; i < pr.parameters.size(); ++i) {
    fit::Parameter& q = pr.parameters[i];
    const std::size_t j = fit::index_of(f.parameters, q.name);
    const double v = f.x[j];
    if (!(v > q.lower && v < q.upper))
      throw Error("discover --forward fe_rig: " + q.name + " = " + significant(v, 6) +
                  " from the closed form lies outside the FE fit's bounds");
    q.value = v;
    q.start_low = q.start_high = v;
    x[i] = v;
  }
  try {
    r.fe_rms_at_closed_form = rms_of(pr.model->predict(x), pr.data);
  } catch (const Error& e) {
    r.why_not = std::string("the FE rig fails at the closed-form optimum: ") + e.what();
    return r;
  }
  fit::FitOptions opt;
  opt.starts = 1;
  opt.local_runs = 1;
  opt.threads = o.threads;
  opt.seed = o.seed;
  opt.max_iterations = fo.max_iterations;
  opt.profile = false;
  opt.progress = o.progress;
  r.fit = fit_logged(pr, opt, o);  // a unit of the checkpoint (tmlab discover --resume)
  std::vector<double> xf;
  for (const auto& q : r.fit.parameters) xf.push_back(q.value);
  const std::vector<double> pred = pr.model->predict(xf);
  std::size_t idx = 0;
  for (const auto& t : dec.tests) {
    r.prediction.emplace_back(pred.begin() + long(idx), pred.begin() + long(idx + t.size()));
    idx += t.size();
  }
  r.samples = pred.size();
  r.done = true;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace

DiscretisationGate baseline_discretisation(const measured::DataSet& data, const Prepared& p, const Fitted& f,
                                           const FeRefitOptions& fo, double refine_ratio, double factor) {
  DiscretisationGate g;
  g.factor = factor;
  g.refine_ratio = refine_ratio;
  if (!f.structure.effects.empty()) {
    g.note = "the baseline has effects the FE rig does not model";
    return g;
  }
  const bool indentation = p.rig == Rig::sphere || p.rig == Rig::punch;
  try {
    const measured::DataSet dec = decimated_data(data, p, indentation, fo.max_samples, nullptr);
    const fit::ModelSpec spec = model_spec(f.structure);
    fit::RigForwardModelOptions feo;
    feo.mesh = fo.mesh;
    feo.substeps = fo.substeps;
    const fit::Problem pr = fit::make_rig_forward_problem(dec, spec, {}, {}, feo);
    std::vector<double> x;
    for (const fit::Parameter& q : pr.parameters) x.push_back(f.x[fit::index_of(f.parameters, q.name)]);
    const auto fine = fit::make_rig_forward_model(dec, spec, fit::refined_rig(feo, refine_ratio));
    const auto text = [](const fit::RigForwardModelSize& s) {
      return std::to_string(s.mesh.cells) + "," + std::to_string(s.mesh.layers) + " (" +
             std::to_string(s.tets) + " tets)";
    };
    g.rig = text(fit::rig_forward_model_size(*pr.model));
    g.refined_rig = text(fit::rig_forward_model_size(*fine));
    const std::vector<double> fc = pr.model->predict(x), ff = fine->predict(x);
    double ss = 0.0;
    for (std::size_t i = 0; i < fc.size(); ++i) ss += (ff[i] - fc[i]) * (ff[i] - fc[i]);
    g.samples = fc.size();
    g.change_rms = fc.empty() ? 0.0 : std::sqrt(ss / double(fc.size()));
    g.applied = std::isfinite(g.change_rms);
    if (!g.applied) g.note = "the rigs' forces are not finite at the baseline's optimum";
  } catch (const Error& e) {
    g.note =
        std::string("the FE rig or its refined rig cannot be built or solved at the baseline's optimum: ") +
        e.what();
  }
  return g;
}

std::vector<FeRefit> fe_rig_refit(const measured::DataSet& data, const Report& r, const Options& o,
                                  const FeRefitOptions& fo) {
  const bool indentation = r.data.rig == Rig::sphere || r.data.rig == Rig::punch;
  std::vector<std::vector<std::size_t>> kept;
  const measured::DataSet dec = decimated_data(data, r.data, indentation, fo.max_samples, &kept);
  std::vector<FeRefit> out;
  if (o.progress) o.progress("FE rig: refitting the baseline " + r.baseline.structure.label());
  out.push_back(refit_one(dec, kept, "baseline", r.baseline, o, fo));
  if (r.final.structure.label() != r.baseline.structure.label()) {
    if (o.progress) o.progress("FE rig: refitting the final model " + r.final.structure.label());
    out.push_back(refit_one(dec, kept, "final", r.final, o, fo));
  }
  for (const auto& f : out)
    if (o.progress)
      o.progress("FE rig " + f.which + ": " +
                 (f.done ? "RMS at the closed-form optimum " + significant(f.fe_rms_at_closed_form, 4) +
                               " N, refitted " + significant(f.fit.rms, 4) + " N (closed form " +
                               significant(f.closed_form_rms, 4) + " N)"
                         : "not refitted: " + f.why_not));
  return out;
}

nlohmann::json to_json(const std::vector<FeRefit>& v, double peak, const FeRefitOptions& fo) {
  using nlohmann::json;
  json j;
  j["description"] =
      "the baseline and the final model refitted on the FE rig of tmlab fit --forward fe_rig (tensor-mass St "
      "VK "
      "or the F-based element, Prony terms, the rig of the data's JSON), Levenberg-Marquardt from the "
      "closed-form optimum";
  j["mesh"] = {{"cells", fo.mesh.cells}, {"layers", fo.mesh.layers}, {"grading", fo.mesh.grading}};
  j["substeps"] = fo.substeps;
  j["max_samples"] = fo.max_samples;
  j["max_iterations"] = fo.max_iterations;
  j["models"] = json::array();
  for (const auto& f : v) {
    json m = {{"which", f.which}, {"model", f.model}, {"refitted", f.done}};
    if (!f.done) {
      m["why_not"] = f.why_not;
    } else {
      m["forward_model"] = f.fit.model_description;
      m["samples"] = f.samples;
      m["closed_form_rms_N"] = f.closed_form_rms;
      m["fe_rms_at_closed_form_optimum_N"] = f.fe_rms_at_closed_form;
      m["rms_N"] = f.fit.rms;
      m["rel_rms"] = f.fit.rms / peak;
      m["bic"] = f.fit.bic;
      m["iterations"] = f.fit.iterations;
      m["forward_solves"] = f.fit.forward_solves;
      m["stop_reason"] = f.fit.stop_reason;
      m["wall_seconds"] = f.seconds;
      m["parameters"] = json::array();
      for (const auto& q : f.fit.parameters)
        m["parameters"].push_back(
            {{"name", q.name},
             {"value", q.value},
             {"unit", q.unit},
             {"fixed", q.fixed},
             {"standard_error", std::isfinite(q.standard_error) ? json(q.standard_error) : json(nullptr)}});
    }
    j["models"].push_back(m);
  }
  return j;
}

}  // namespace tmlab::discover
