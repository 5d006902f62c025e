// tmlab fit DATA.csv --model SPEC: inverse identification (issue 14; docs/identification.md). Thin:
// tmlab::fit does the work; this file reads the options, writes fit.json, fit.h5, the plots and the
// manifest through the result protocol (a failed fit leaves FAILED, never a complete-looking result).
#include "commands.hpp"

#include "cli_args.hpp"
#include "command_specs.hpp"
#include "fit_request.hpp"

#include "calibration/data/measured_data.hpp"
#include "calibration/data/sign_convention.hpp"
#include "calibration/fit/discretisation.hpp"
#include "calibration/fit/fit_checkpoint.hpp"
#include "calibration/fit/fit_output.hpp"
#include "calibration/fit/relaxation_bands.hpp"
#include "calibration/fit/rig_forward_model.hpp"
#include "core/base/error.hpp"
#include "core/results/run_output.hpp"
#include "core/results/run_protocol.hpp"
#include "core/results/unit_checkpoint.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

namespace tmlab::cli {

namespace fs = std::filesystem;

namespace {

/// The problem with the asked forward model, the priors and --noise; `why_closed_form` says why
/// the closed form does not apply when the FE rig was chosen for that reason.
fit::Problem build_problem(const ParsedOptions& p, const measured::DataSet& data, const FitRequest& q,
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
  if (p.given("--noise")) problem.noise_sigma = p.decimal("--noise");
  return problem;
}

/// --out, or results/fit/<data>-<law tag> (a name checked for the results folder).
fs::path result_dir(const ParsedOptions& p, const measured::DataSet& data, const fit::ModelSpec& spec) {
  if (p.given("--out")) return p.text("--out");
  const std::string name = fit::result_name(data.meta.name, spec);
  if (const std::string why = result_name_problem(name); !why.empty())
    throw Error("fit: result name: " + why);
  return fs::path(tmlab_root()) / "results" / "fit" / name;
}

/// The refined rig's model of the discretisation check (issue 28; docs/identification.md
/// "Discretisation shift"), or null when there is none: on by default for an FE-rig forward model;
/// --discretisation-check on or --refine-ratio with a closed form, or --refine-ratio with the check
/// off, refused (UsageError), as a ratio that rounds to the same mesh; built before the result
/// folder exists, so a refined rig that cannot be built (too large) leaves none.
std::unique_ptr<fit::ForwardModel> refined_model(const ParsedOptions& p, const measured::DataSet& data,
                                                 const FitRequest& q, const fit::Problem& problem,
                                                 double& ratio) {
  const bool fe = problem.model->name() == "fe_rig";
  const bool asked_on = p.given("--discretisation-check") && p.text("--discretisation-check") == "on";
  const bool off = p.given("--discretisation-check") && p.text("--discretisation-check") == "off";
  if (!fe && (asked_on || p.given("--refine-ratio")))
    throw UsageError(std::string(asked_on ? "--discretisation-check on" : "--refine-ratio") +
                     " is for the FE rig forward model (--forward fe_rig): this fit's forward model is the "
                     "closed form '" +
                     problem.model->name() + "', which has no mesh to refine");
  if (off && p.given("--refine-ratio"))
    throw UsageError(
        "--refine-ratio sets the discretisation check's refined rig: not with --discretisation-check off");
  if (!fe || off) return nullptr;
  ratio = p.given("--refine-ratio") ? p.decimal("--refine-ratio") : fit::kDefaultRefineRatio;
  fit::RigForwardModelOptions fine;
  try {
    fine = fit::refined_rig(q.fe, ratio);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  return fit::make_rig_forward_model(data, q.spec, fine);
}

}  // namespace

int cmd_fit(const std::vector<std::string>& args, const std::string& command_line) {
  const ParsedOptions p = parse(fit_spec(), args);
  if (p.positional.size() != 1) throw UsageError("fit needs exactly one DATA.csv");
  if (!p.given("--model"))
    throw UsageError("fit needs --model SPEC (e.g. neo_hookean, ogden:2,poisson=0.49)");
  const fs::path csv = p.positional[0];
  const measured::DataSet data = measured::read_data_set(csv);
  const FitRequest q = parse_fit_request(p);
  measured::check_force_sign(data, csv.string());
  std::string why_closed_form;
  const fit::Problem problem = build_problem(p, data, q, why_closed_form);
  double refine_ratio = fit::kDefaultRefineRatio;
  const std::unique_ptr<fit::ForwardModel> fine = refined_model(p, data, q, problem, refine_ratio);
  const fs::path dir = result_dir(p, data, q.spec);
  // Checkpoints after the global stage, each local run and each profile point (docs/robustness.md);
  // --resume reads the checkpoint before the result directory is touched, so a refused resume
  // leaves the interrupted fit as it was.
  fit::FitOptions options = q.options;
  fit::FitCheckpoint ck(dir, fit_fingerprint(p, q, csv), checkpoint_schedule(p));
  if (p.flag("--resume")) {
    refuse_resume_of_complete(dir, "fit");
    ck.restore(options, std::cout);
  }
  ck.record(options);
  fit::print_fit_plan(std::cout, data.meta.name, q.spec, q.global, q.forward, problem, why_closed_form);
  RunOutput out(dir, &std::cerr,
                p.flag("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  ManifestInput mi;
  mi.command_line = split_words(command_line);
  mi.config = p.config(kManifest);
  mi.input_files = {csv, measured::metadata_path(csv)};
  std::string plots = "skipped (--no-plots)";
  run_with_protocol(
      out, mi,
      [&] {
        const fit::FitResult r = fit::fit(problem, options);
        std::optional<fit::DiscretisationReport> disc;
        if (fine) disc = fit::discretisation_report(r, problem, *fine, refine_ratio, q.options.progress);
        const fit::DiscretisationReport* dp = disc ? &*disc : nullptr;
        out.write_json("fit.json", fit::to_json(r, problem, q.options, q.spec, dp));
        fit::write_fit_h5(out.file("fit.h5"), data, r);
        if (!p.flag("--no-plots")) {
          plots = fit::write_fit_plots(out.staging_dir(), tmlab_root(),
                                       data.meta.name + ": " + q.spec.text + " (" + r.model_name + ")");
          if (plots != "ok") std::cerr << "tmlab fit: plots " << plots << "\n";
        }
        fit::print_fit_report(std::cout, r, problem, q.options, dp);
        return fit::summary_json(r, q.spec, plots);
      },
      protocol_checkpoint(ck.file()));
  std::cout << "written: " << out.dir().string() << "/ (fit.json, fit.h5, manifest.json, summary.json"
            << (plots == "ok" ? ", fit_*.png" : "") << ")\n";
  return 0;
}

}  // namespace tmlab::cli
