// tmlab fit DATA.csv --model SPEC: inverse identification (issue 14; docs/identification.md). Thin:
// tmlab::fit does the work; this file reads the options, writes fit.json, fit.h5, the plots and the
// manifest through the result protocol (a failed fit leaves FAILED, never a complete-looking result).
#include "commands.hpp"

#include "cli_args.hpp"

#include "calibration/data/measured_data.hpp"
#include "calibration/data/sign_convention.hpp"
#include "calibration/fit/fe_rig.hpp"
#include "calibration/fit/fit_checkpoint.hpp"
#include "calibration/fit/fit_output.hpp"
#include "calibration/fit/fitter.hpp"
#include "calibration/fit/relaxation_bands.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/interrupt.hpp"
#include "core/base/process.hpp"
#include "core/results/run_output.hpp"
#include "core/results/run_protocol.hpp"
#include "core/results/unit_checkpoint.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
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
  fit::Problem problem =
      fit::make_problem(data, q.spec, q.fixes, q.weights, q.forward, q.fe, why_closed_form);
  if (q.forward == "auto" && !why_closed_form.empty())
    std::cout << "no closed form (" << why_closed_form << "): the FE rig forward model\n";
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
                      fit::put_fit_units(d, latest);
                      return d;
                    });
  fit::FitOptions options = q.options;
  if (p.has("--resume")) {
    refuse_resume_of_complete(dir, "fit");
    restored = fit::get_fit_units(ck.read());
    ck.resumed_from(fit::describe(restored));
    options.resume.restored = &restored;
    std::cout << "tmlab fit: resuming from " << ck.path().string() << ": " << fit::describe(restored)
              << " taken from it, the rest runs\n";
  }
  options.resume.unit_finished = [&](const fit::FitUnits& u) {
    latest = u;
    ck.unit_finished(fit::describe(u));
  };
  print_fit_plan(data, q, problem, why_closed_form);
  RunOutput out(dir, &std::cerr,
                p.has("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  ManifestInput mi;
  mi.command_line = split_words(command_line);
  mi.config = manifest_config(p, q);
  mi.input_files = {csv, measured::metadata_path(csv)};
  std::string plots;
  run_with_protocol(
      out, mi,
      [&]() -> nlohmann::json {
        const fit::FitResult r = fit::fit(problem, options);
        out.write_json("fit.json", fit::to_json(r, problem, q.options, q.spec));
        fit::write_fit_h5(out.file("fit.h5"), data, r);
        plots = make_fit_plots(p, out, data, q.spec, r);
        fit::print_fit_report(std::cout, r, problem, q.options);
        return {{"model", q.spec.text},
                {"forward_model", r.model_name},
                {"residual_rms_percent_of_peak", r.rms_percent_peak},
                {"aic", r.aic},
                {"bic", r.bic},
                {"forward_solves", r.forward_solves},
                {"global_stage", r.global_stage},
                {"surrogate_solves", r.global_solves},
                {"wall_seconds", r.wall_seconds},
                {"plots", plots}};
      },
      protocol_checkpoint(ck));
  std::cout << "written: " << out.dir().string() << "/ (fit.json, fit.h5, manifest.json, summary.json"
            << (plots == "ok" ? ", fit_*.png" : "") << ")\n";
  return 0;
}

}  // namespace tmlab::cli
