// A case file -> a run of the fast model -> a result directory: the named steps of one run
// (docs/architecture.md, "Flow of one run"), each in its own file of runner/: the problem
// (problem.hpp, model_factory.hpp), the stepping (stepping.hpp, contact_stepping.hpp) with the
// recorder (step_recorder.hpp), progress (run_progress.hpp) and checkpoint (run_checkpoint.hpp), and
// here the inputs, plots and summary, run under the result protocol (core/results/run_protocol.hpp).
#include "runner/case_runner.hpp"

#include "core/base/process.hpp"
#include "core/config/element_kind.hpp"
#include "core/mesh/mesh_quality.hpp"
#include "core/results/recorder.hpp"
#include "core/results/run_output.hpp"
#include "core/results/run_protocol.hpp"
#include "core/results/series_names.hpp"
#include "runner/linear_solve_log.hpp"
#include "runner/problem.hpp"
#include "runner/run_checkpoint.hpp"
#include "runner/step_recorder.hpp"
#include "runner/stepping.hpp"

#include <chrono>
#include <filesystem>

namespace tmlab::tm {

namespace fs = std::filesystem;

namespace {

using runner::Problem;
using runner::RunCheckpoint;
using runner::StepRecorder;

/// manifest.json's inputs (written by run_with_protocol) and mesh_report.json.
ManifestInput manifest_input(const Problem& p, const RunOptions& opt) {
  ManifestInput mi;
  mi.command_line = opt.command_line;
  mi.config = effective_case_json(p.cfg);
  mi.input_files.push_back(p.cfg.mesh.file);
  if (fs::exists(p.cfg.file)) mi.input_files.push_back(p.cfg.file);
  return mi;
}

/// plots.json, and the PNGs through matplotlib when asked (a missing python3/matplotlib is reported,
/// not fatal). Returns the summary's "plots" status.
std::string plot(const Problem& p, const RunOptions& opt, const RunOutput& out, const Recorder& rec) {
  out.write_json("plots.json", rec.plots(p.cfg.name));
  if (!opt.plots || !p.cfg.output.plots) return "skipped";
  const fs::path script = fs::path(opt.tmlab_root) / "core" / "results" / "python" / "tmlab_plot.py";
  const ProcessStatus ps =
      run_python(script, {out.staging_dir().string()}, ProcessOutput::to_file(out.file("plots.log")));
  if (ps.ok()) return "ok";
  if (opt.log) *opt.log << "  warning: plotting failed (see plots.log); the numbers are in timeseries.h5\n";
  return "failed (see plots.log)";
}

/// summary.json's material block: the law, its parameters as the case file gives them (the manifest's
/// effective configuration), the density, and the small-strain E, nu, lambda, mu of the law.
nlohmann::json material_summary(const Problem& p) {
  nlohmann::json m = effective_case_json(p.cfg)["material"];
  m.erase("viscoelastic");
  const LameConstants l = p.law.small_strain();
  m["E"] = p.cfg.material.young;
  m["nu"] = p.cfg.material.poisson;
  m["lambda"] = l.lambda;
  m["mu"] = l.mu;
  return m;
}

/// summary.json: the case, mesh, material, solver, the recorder's common blocks, the energy balance
/// (work in = stored + kinetic + dissipated) and the viscoelastic settings.
nlohmann::json summarise(const Problem& p, const StepRecorder& rec, const nlohmann::json& solver_info,
                         const std::string& plot_status, double wall) {
  const CaseConfig& cfg = p.cfg;
  nlohmann::json summary = {{"case", cfg.name},
                            {"description", cfg.description},
                            {"model", to_string(cfg.model)},
                            {"mesh",
                             {{"file", cfg.mesh.file},
                              {"element", to_string(cfg.mesh.element)},
                              {"nodes", p.num_nodes()},
                              {"points", p.mesh.num_points()},
                              {"tets", p.mesh.num_tets()},
                              {"volume_m3", p.report.total_volume},
                              {"orientation_repaired", p.repaired}}},
                            {"material", material_summary(p)},
                            {"solver", solver_info},
                            {"plots", plot_status},
                            {"run_seconds", wall}};
  summary.update(rec.recorder().summary_blocks());
  if (summary["solver"].contains("contact")) {  // the contact block at the top level
    summary["contact"] = summary["solver"]["contact"];
    summary["solver"].erase("contact");
  }
  const SeriesTable& table = rec.recorder().table();
  const double stored = table.last(series_names::kElasticEnergy);
  const double kinetic = table.last(series_names::kKineticEnergy);
  const double dissipated = p.visco ? p.visco->total_dissipation() : 0.0;
  const double work = rec.external_work();
  summary["energy"] = {{"external_work_J", work},
                       {"stored_J", stored},
                       {"kinetic_J", kinetic},
                       {"total_dissipation_J", dissipated},
                       {"balance_residual_J", work - stored - kinetic - dissipated}};
  if (p.visco) {
    const ViscoelasticSpec& vs = cfg.material.viscoelastic;
    summary["viscoelastic"] = {{"history", to_string(vs.history)},
                               {"integration", to_string(vs.integration)},
                               {"relaxation", to_string(vs.relaxation)},
                               {"prony_long_term", p.visco->prony().to_json()}};
  }
  return summary;
}

}  // namespace

NewtonOptions newton_options(const SolverSpec& s) {
  NewtonOptions o;
  o.max_iterations = s.max_iterations;
  o.rtol = s.rtol;
  o.atol = s.atol;
  o.line_search = s.line_search;
  o.linear_solver = runner::newton_linear_solver(s.linear);
  return o;
}

RunResult run_case(const CaseConfig& cfg, const RunOptions& opt) {
  const auto wall0 = std::chrono::steady_clock::now();
  const Problem p(cfg);
  // --resume: the checkpoint is read and checked before the result directory is touched, so a
  // refused resume leaves the interrupted run as it was.
  const fs::path dir = fs::path(opt.results_root) / cfg.name;
  RunCheckpoint ck(p, dir, opt);
  // The result directory is staged; summary.json only when everything succeeded.
  RunOutput out(dir, opt.log,
                opt.resume ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  nlohmann::json summary;
  // The protocol writes manifest.json, runs this, removes the checkpoint and finalises with the
  // summary; a stop becomes INTERRUPTED with where the checkpoint is, any other error FAILED. The
  // checkpoint goes once the plots are written too, so a stop while plotting can still resume.
  const auto compute = [&]() -> nlohmann::json {
    out.write_json("mesh_report.json", mesh_report_json(p.report));
    StepRecorder rec(p, out);
    const nlohmann::json solver_info = runner::step(p, rec, opt.log, ck);
    rec.close();
    const std::string plot_status = plot(p, opt, out, rec.recorder());
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    summary = summarise(p, rec, solver_info, plot_status, wall);
    return summary;
  };
  const ProtocolCheckpoint protocol{
      [&ck] { ck.remove(); },
      [&ck](const Interrupted& e) { return Interrupted(e.signal(), e.what() + ck.where()); }};
  run_with_protocol(out, manifest_input(p, opt), compute, protocol);
  return {out.dir().string(), summary};
}

}  // namespace tmlab::tm
