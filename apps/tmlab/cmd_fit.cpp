// tmlab fit DATA.csv --model SPEC: inverse identification (issue 14; docs/identification.md). Thin:
// tmlab::fit does the work; this file reads the options, writes fit.json, fit.h5, the plots and the
// manifest through the result protocol (a failed fit leaves FAILED, never a complete-looking result).
#include "commands.hpp"

#include "cli_args.hpp"
#include "fit_checkpoint.hpp"

#include "calibration/data/measured_data.hpp"
#include "calibration/data/sign_convention.hpp"
#include "calibration/fit/fe_rig.hpp"
#include "calibration/fit/fitter.hpp"
#include "calibration/fit/relaxation_bands.hpp"
#include "calibration/fit/surrogates.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/interrupt.hpp"
#include "core/base/process.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/results/json_number.hpp"
#include "core/results/run_output.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>

namespace tmlab::cli {

namespace fs = std::filesystem;

namespace {

/// "NAME=VALUE" of --fix / --weight.
std::pair<std::string, double> name_value(const std::string& option, const std::string& s) {
  const std::size_t eq = s.find('=');
  if (eq == std::string::npos || eq == 0) throw UsageError(option + " needs NAME=VALUE, got '" + s + "'");
  return {s.substr(0, eq), parse_double(option + " " + s.substr(0, eq), s.substr(eq + 1))};
}

/// When fewer local runs ran than --local-runs asked for (one per candidate start, and there were
/// fewer starts, or fewer the model could evaluate): what ran and why; "" otherwise.
std::string local_runs_note(const fit::FitResult& r, const fit::FitOptions& o) {
  if (r.local_runs >= o.local_runs) return "";
  return "--local-runs " + std::to_string(o.local_runs) + " asked for more Levenberg-Marquardt runs than " +
         "there were candidate starts to run them from: " + std::to_string(r.local_runs) + " ran (" +
         (o.global == fit::GlobalStage::Siman ? "simulated annealing gives 2 starts: its best state and the "
                                                "parameters' values"
                                              : "--starts " + std::to_string(o.starts) +
                                                    ", each run from one start the model could evaluate") +
         ")";
}

nlohmann::json to_json(const fit::FitResult& r, const fit::Problem& pr, const fit::FitOptions& o,
                       const fit::ModelSpec& spec) {
  using nlohmann::json;
  json j;
  j["model"] = {{"spec", spec.text},
                {"law", spec.law},
                {"forward_model", r.model_name},
                {"description", r.model_description}};
  j["parameters"] = json::array();
  for (const auto& p : r.parameters) {
    // Which bound the value sits on ("lower", "upper" or ""): a constrained optimum, not a free one.
    std::string at_bound;
    json bounds = {nullptr, nullptr};
    for (const auto& q : pr.parameters)
      if (q.name == p.name) {
        at_bound = fit::bound_reached(q, p.value);
        bounds = {finite_or_null(q.lower), finite_or_null(q.upper)};
      }
    j["parameters"].push_back({{"name", p.name},
                               {"value", p.value},
                               {"unit", p.unit},
                               {"fixed", p.fixed},
                               {"transform", p.transform},
                               {"standard_error", finite_or_null(p.standard_error)},
                               {"interval95", {finite_or_null(p.lower95), finite_or_null(p.upper95)}},
                               {"identifiable", p.identifiable},
                               {"bounds", bounds},
                               {"at_bound", at_bound}});
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
                       {"starts", o.global == fit::GlobalStage::Siman ? 1 : o.starts},
                       {"local_runs", r.local_runs},
                       {"local_runs_requested", o.local_runs},
                       {"seed", o.seed},
                       {"start_costs", json::array()},
                       {"surrogate_costs", json::array()}};
  if (o.global == fit::GlobalStage::Siman)
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

/// A whole number 1..10000 for option `key`, `fallback` when it is not given.
int positive_int(const Parsed& p, const std::string& key, int fallback) {
  return p.has(key) ? int(parse_whole(key, p.get(key), 1, 10000)) : fallback;
}

/// Every --prior NAME=MEAN:SD.
std::vector<fit::Prior> parse_priors(const Parsed& p) {
  std::vector<fit::Prior> priors;
  for (const auto& s : p.all("--prior")) {
    const std::size_t eq = s.find('='), colon = s.find(':', eq == std::string::npos ? 0 : eq);
    if (eq == std::string::npos || eq == 0 || colon == std::string::npos)
      throw UsageError("--prior needs NAME=MEAN:SD, got '" + s + "'");
    fit::Prior q;
    q.parameter = s.substr(0, eq);
    q.mean = parse_double("--prior " + q.parameter + " mean", s.substr(eq + 1, colon - eq - 1));
    q.sd = parse_double("--prior " + q.parameter + " sd", s.substr(colon + 1));
    if (!(q.sd > 0.0)) throw UsageError("--prior " + q.parameter + ": the sd must be positive");
    priors.push_back(q);
  }
  return priors;
}

/// --mesh CELLS,LAYERS and --substeps of the FE-rig forward model.
fit::FeRigOptions parse_fe_rig_options(const Parsed& p) {
  fit::FeRigOptions fe;
  if (p.has("--mesh")) {
    const std::string m = p.get("--mesh");
    const std::size_t comma = m.find(',');
    if (comma == std::string::npos) throw UsageError("--mesh needs CELLS,LAYERS, got '" + m + "'");
    fe.mesh.cells = int(parse_whole("--mesh CELLS", m.substr(0, comma), 2, 400));
    fe.mesh.layers = int(parse_whole("--mesh LAYERS", m.substr(comma + 1), 1, 400));
  }
  fe.substeps = positive_int(p, "--substeps", fe.substeps);
  return fe;
}

/// What the command line asks for, parsed and checked (UsageError otherwise). The choices keep the
/// words the user gave: the manifest records them.
struct FitRequest {
  fit::ModelSpec spec;
  std::vector<std::pair<std::string, double>> fixes, weights;
  std::string cost, global, forward;
  fit::FitOptions options;
  std::vector<fit::Prior> priors;
  fit::FeRigOptions fe;
  double band_floor = 0.0, band_ceiling = 0.0;  ///< --relaxation-bands (0: off)
};

FitRequest parse_fit_request(const Parsed& p) {
  FitRequest q;
  q.spec = fit::parse_model_spec(p.get("--model"));
  for (const auto& s : p.all("--fix")) q.fixes.push_back(name_value("--fix", s));
  for (const auto& s : p.all("--weight")) q.weights.push_back(name_value("--weight", s));
  fit::FitOptions& o = q.options;
  q.cost = p.get("--cost", "least_squares");
  if (q.cost == "l1")
    o.cost = fit::Cost::L1;
  else if (q.cost != "least_squares")
    throw UsageError("--cost must be least_squares or l1 (got '" + q.cost + "')");
  o.starts = positive_int(p, "--starts", o.starts);
  o.threads = positive_int(p, "--threads", 2);
  o.seed = (unsigned long)positive_int(p, "--seed", 1);
  o.geodesic = p.has("--geodesic");
  o.profile = !p.has("--no-profile");
  if (!p.has("--quiet"))
    o.progress = [](const std::string& line) { std::cout << line << "\n" << std::flush; };
  o.local_runs = positive_int(p, "--local-runs", o.local_runs);
  o.siman_evaluations = positive_int(p, "--siman-evaluations", o.siman_evaluations);
  q.global = p.get("--global", "multistart");
  if (q.global == "siman")
    o.global = fit::GlobalStage::Siman;
  else if (q.global != "multistart")
    throw UsageError("--global must be multistart or siman (got '" + q.global + "')");
  q.priors = parse_priors(p);
  q.fe = parse_fe_rig_options(p);
  // closed_form by default: an FE-rig fit can take minutes, so it is asked for, not fallen into.
  q.forward = p.get("--forward", "closed_form");
  if (q.forward != "auto" && q.forward != "closed_form" && q.forward != "fe_rig")
    throw UsageError("--forward must be auto, closed_form or fe_rig (got '" + q.forward + "')");
  if (p.has("--relaxation-bands")) {
    const std::string v = p.get("--relaxation-bands");
    const auto comma = v.find(',');
    if (comma == std::string::npos)
      throw UsageError("--relaxation-bands needs FLOOR,CEILING (e.g. 0.5,1), got '" + v + "'");
    q.band_floor = parse_double("--relaxation-bands", v.substr(0, comma));
    q.band_ceiling = parse_double("--relaxation-bands", v.substr(comma + 1));
    if (!(q.band_floor > 0.0 && q.band_ceiling > 0.0))
      throw UsageError("--relaxation-bands: FLOOR and CEILING must be positive, got '" + v + "'");
    if (q.spec.prony_terms == 0)
      throw UsageError("--relaxation-bands needs Prony terms in --model (e.g. " + q.spec.law + "+prony:2)");
  }
  return q;
}

/// The problem with the asked forward model, the priors and --noise; `why_closed_form` says why
/// the closed form does not apply when the FE rig was chosen for that reason.
fit::Problem build_problem(const Parsed& p, const measured::DataSet& data, const FitRequest& q,
                           std::string& why_closed_form) {
  fit::Problem problem;
  if (q.forward == "closed_form") {
    problem = fit::make_surrogate_problem(data, q.spec, q.fixes, q.weights);
  } else if (q.forward == "fe_rig") {
    problem = fit::make_fe_rig_problem(data, q.spec, q.fixes, q.weights, q.fe, &why_closed_form);
  } else {
    // auto: the closed form when it covers the data and the law, else the FE rig.
    try {
      problem = fit::make_surrogate_problem(data, q.spec, q.fixes, q.weights);
    } catch (const Error& e) {
      why_closed_form = e.what();
      problem = fit::make_fe_rig_problem(data, q.spec, q.fixes, q.weights, q.fe);
      std::cout << "no closed form (" << why_closed_form << "): the FE rig forward model\n";
    }
  }
  problem.priors = q.priors;
  fit::check_priors(problem);  // a parameter given two priors, or a fixed one, refused before computing
  if (q.band_floor > 0.0)      // tau_j in ordered bands of [floor x sampling interval, ceiling x duration]
    fit::band_relaxation_times(problem.parameters, q.spec,
                               fit::relaxation_range(data, q.band_floor, q.band_ceiling));
  if (p.has("--noise")) {
    problem.noise_sigma = parse_double("--noise", p.get("--noise"));
    if (!(problem.noise_sigma > 0.0)) throw UsageError("--noise must be positive (N)");
  }
  return problem;
}

/// --out, or results/fit/<data>-<law tag> (a name checked for the results folder).
fs::path result_dir(const Parsed& p, const measured::DataSet& data, const fit::ModelSpec& spec) {
  std::string law_tag = spec.law + (spec.law == "ogden" ? std::to_string(spec.ogden_terms) : "") +
                        (spec.prony_terms ? "-prony" + std::to_string(spec.prony_terms) : "");
  const fs::path dir = p.has("--out")
                           ? fs::path(p.get("--out"))
                           : fs::path(tmlab_root()) / "results" / "fit" / (data.meta.name + "-" + law_tag);
  if (!p.has("--out")) {
    const std::string why = result_name_problem(data.meta.name + "-" + law_tag);
    if (!why.empty()) throw Error("fit: result name: " + why);
  }
  return dir;
}

void print_fit_plan(const measured::DataSet& data, const FitRequest& q, const fit::Problem& problem,
                    const std::string& why_closed_form) {
  std::cout << "fit " << data.meta.name << " with " << q.spec.text << " (" << problem.model->description()
            << ")\n";
  if (problem.global_model)
    std::cout << "global stage (" << q.global
              << ") on the closed form: " << problem.global_model->description()
              << "; local stage and every reported number: " << problem.model->name() << "\n";
  else if (q.forward == "fe_rig" && !why_closed_form.empty())
    std::cout << "global stage on the FE rig itself (no closed form: " << why_closed_form << ")\n";
}

/// The manifest's config block: the request as the user wrote it.
nlohmann::json manifest_config(const Parsed& p, const FitRequest& q) {
  const fit::FitOptions& o = q.options;
  return {{"model", q.spec.text},
          {"cost", q.cost},
          {"starts", o.starts},
          {"threads", o.threads},
          {"seed", o.seed},
          {"geodesic", o.geodesic},
          {"profile", o.profile},
          {"fix", p.all("--fix")},
          {"weight", p.all("--weight")},
          {"forward", q.forward},
          {"global", q.global},
          {"prior", p.all("--prior")},
          {"mesh", {q.fe.mesh.cells, q.fe.mesh.layers}},
          {"substeps", q.fe.substeps},
          {"relaxation_bands", p.get("--relaxation-bands", "")}};
}

/// What --resume must match: everything that changes the result (the data files' contents, the
/// request, every option of the engine), not what only changes where or how it is shown.
nlohmann::json fit_fingerprint(const Parsed& p, const FitRequest& q, const fs::path& csv) {
  nlohmann::json j = manifest_config(p, q);
  const fit::FitOptions& o = q.options;
  j["local_runs"] = o.local_runs;
  j["siman_evaluations"] = o.siman_evaluations;
  j["max_iterations"] = o.max_iterations;
  j["noise"] = p.get("--noise", "");
  j["data"] = {{"csv", file_hash(csv)}, {"metadata", file_hash(measured::metadata_path(csv))}};
  return j;
}

/// --checkpoint-every (default: every 60 s of wall time, and always at a stop request).
CheckpointSchedule checkpoint_schedule(const Parsed& p) {
  try {
    return p.has("--checkpoint-every") ? CheckpointSchedule::parse(p.get("--checkpoint-every"))
                                       : CheckpointSchedule{};
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

/// fit.h5: per test the data, the model's force and the residual; the profile; the correlation.
void write_fit_h5(const fs::path& path, const measured::DataSet& data, const fit::FitResult& r) {
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

/// The plots (calibration/fit/python/tmlab_fit_plot.py) into the staging folder: "ok", "failed
/// (why)" or "skipped (--no-plots)" for the summary.
std::string make_fit_plots(const Parsed& p, const RunOutput& out, const measured::DataSet& data,
                           const fit::ModelSpec& spec, const fit::FitResult& r) {
  if (p.has("--no-plots")) return "skipped (--no-plots)";
  const ProcessStatus ps =
      run_python(fs::path(tmlab_root()) / "calibration" / "fit" / "python" / "tmlab_fit_plot.py",
                 {out.staging_dir().string(), data.meta.name + ": " + spec.text + " (" + r.model_name + ")"},
                 ProcessOutput::discard());
  const std::string plots = ps.ok() ? "ok" : "failed (" + ps.describe() + ")";
  if (!ps.ok()) std::cerr << "tmlab fit: plots " << plots << "\n";
  return plots;
}

/// The parameter table, the cost and its forward model, the profile, the confounded pairs and notes.
void print_fit_report(const fit::FitResult& r, const fit::Problem& problem, const fit::FitOptions& o) {
  std::cout << std::left << std::setw(10) << "parameter" << std::right << std::setw(14) << "value"
            << std::setw(6) << "unit" << std::setw(14) << "std error" << std::setw(30) << "95 % interval"
            << "\n";
  for (const auto& q : r.parameters)
    std::cout << std::left << std::setw(10) << q.name << std::right << std::setw(14)
              << significant(q.value, 6) << std::setw(6) << q.unit << std::setw(14)
              << (q.fixed                           ? "fixed"
                  : std::isfinite(q.standard_error) ? significant(q.standard_error, 3)
                                                    : "inf")
              << std::setw(30)
              << (q.fixed ? "" : "[" + significant(q.lower95, 5) + ", " + significant(q.upper95, 5) + "]")
              << "\n";
  std::cout << "cost (" << r.cost_name << ") " << significant(r.cost, 6) << "; residual RMS "
            << significant(r.rms, 4) << " N = " << significant(r.rms_percent_peak, 3) << " % of peak "
            << significant(problem.data.peak_force, 5) << " N; AIC " << significant(r.aic, 7) << ", BIC "
            << significant(r.bic, 7) << "\n"
            << r.forward_solves << " forward solves (" << r.model_name << ")"
            << (r.global_solves ? " + " + std::to_string(r.global_solves) + " (" + r.global_model_name +
                                      ", " + r.global_stage + " global stage)"
                                : std::string(" (") + r.global_stage + " global stage)")
            << " on " << r.threads << " threads in " << significant(r.wall_seconds, 3) << " s\n"
            << "the numbers above are from the forward model '" << r.model_name << "'\n";
  if (!r.profile.parameter.empty())
    std::cout << "profile likelihood of " << r.profile.parameter << ": 95 % interval ["
              << (r.profile.lower_found ? significant(r.profile.lower95, 5) : std::string("beyond grid"))
              << ", "
              << (r.profile.upper_found ? significant(r.profile.upper95, 5) : std::string("beyond grid"))
              << "]\n";
  for (const auto& c : r.confounded)
    std::cout << "confounded: " << c.a << " and " << c.b << " (correlation " << significant(c.correlation, 4)
              << "): " << c.note << "\n";
  for (const auto& n : r.notes) std::cout << "note: " << n << "\n";
  if (const std::string n = local_runs_note(r, o); !n.empty()) std::cout << "note: " << n << "\n";
}

}  // namespace

int cmd_fit(const std::vector<std::string>& args, const std::string& command_line) {
  const Parsed p = parse(args,
                         {"--model", "--out", "--fix", "--weight", "--cost", "--starts", "--threads",
                          "--seed", "--forward", "--global", "--prior", "--noise", "--mesh", "--substeps",
                          "--local-runs", "--siman-evaluations", "--checkpoint-every", "--relaxation-bands"},
                         {"--geodesic", "--no-plots", "--no-profile", "--quiet", "--resume"});
  if (p.positional.size() != 1) throw UsageError("fit needs exactly one DATA.csv");
  if (!p.has("--model")) throw UsageError("fit needs --model SPEC (e.g. neo_hookean, ogden:2,poisson=0.49)");
  const fs::path csv = p.positional[0];
  const measured::DataSet data = measured::read_data_set(csv);
  const FitRequest q = parse_fit_request(p);
  measured::check_force_sign(data, csv.string());
  std::string why_closed_form;
  const fit::Problem problem = build_problem(p, data, q, why_closed_form);
  const fs::path dir = result_dir(p, data, q.spec);
  // Checkpoints after the global stage, each local run and each profile point (docs/robustness.md);
  // --resume reads the checkpoint before the result directory is touched, so a refused resume
  // leaves the interrupted fit as it was.
  fit::FitUnits restored, latest;
  UnitCheckpoint ck(dir / RunOutput::kStaging / "checkpoint.h5", "fit", fit_fingerprint(p, q, csv),
                    checkpoint_schedule(p), [&latest] {
                      CheckpointData d;
                      put_fit_units(d, latest);
                      return d;
                    });
  fit::FitOptions options = q.options;
  if (p.has("--resume")) {
    refuse_resume_of_complete(dir, "fit");
    restored = get_fit_units(ck.read());
    ck.resumed_from(describe(restored));
    options.resume.restored = &restored;
    std::cout << "tmlab fit: resuming from " << ck.path().string() << ": " << describe(restored)
              << " taken from it, the rest runs\n";
  }
  options.resume.unit_finished = [&](const fit::FitUnits& u) {
    latest = u;
    ck.unit_finished(describe(u));
  };
  print_fit_plan(data, q, problem, why_closed_form);
  RunOutput out(dir, &std::cerr,
                p.has("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  try {
    ManifestInput mi;
    mi.command_line = split_words(command_line);
    mi.config = manifest_config(p, q);
    mi.input_files = {csv, measured::metadata_path(csv)};
    out.write_json("manifest.json", make_manifest(mi));
    const fit::FitResult r = fit::fit(problem, options);
    out.write_json("fit.json", to_json(r, problem, q.options, q.spec));
    write_fit_h5(out.file("fit.h5"), data, r);
    const std::string plots = make_fit_plots(p, out, data, q.spec, r);
    print_fit_report(r, problem, q.options);
    nlohmann::json summary = {{"model", q.spec.text},
                              {"forward_model", r.model_name},
                              {"residual_rms_percent_of_peak", r.rms_percent_peak},
                              {"aic", r.aic},
                              {"bic", r.bic},
                              {"forward_solves", r.forward_solves},
                              {"global_stage", r.global_stage},
                              {"surrogate_solves", r.global_solves},
                              {"wall_seconds", r.wall_seconds},
                              {"plots", plots}};
    ck.remove();  // a complete result holds no checkpoint
    out.finalize(summary);
    std::cout << "written: " << out.dir().string() << "/ (fit.json, fit.h5, manifest.json, summary.json"
              << (plots == "ok" ? ", fit_*.png" : "") << ")\n";
  } catch (const Interrupted& e) {
    const Interrupted stopped = ck.stopped(e);
    out.abandon(stopped);
    throw stopped;
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
  return 0;
}

}  // namespace tmlab::cli
