// tmlab demo / tmlab run: one case with one model, and the printed summary.
#include "commands.hpp"

#include "cli_args.hpp"
#include "command_specs.hpp"
#include "demo_case.hpp"

#include "core/base/error.hpp"
#include "core/config/case_config.hpp"
#include "core/config/element_kind.hpp"
#include "runner/case_runner.hpp"

#ifdef TMLAB_HAVE_REFERENCE
#include "reference_fem/dealii/reference_runner.hpp"
#endif

#include <filesystem>
#include <iomanip>
#include <iostream>

namespace tmlab::cli {

namespace fs = std::filesystem;

tmlab::RunResult run_model(const CaseConfig& cfg, const tmlab::RunOptions& opt, const std::string& model,
                           int degree, const std::string& time_integration) {
  if (model == "reference") {
#ifdef TMLAB_HAVE_REFERENCE
    ref::ReferenceOptions ro;
    ro.degree = degree;
    ro.time_integration = ref::parse_time_integration(time_integration, "--time-integration");
    return ref::run_reference_case(cfg, opt, ro);
#else
    (void)degree;
    (void)time_integration;
    throw Error(
        "this tmlab was built without the deal.II reference (reference_fem/): install libdeal.ii-dev and "
        "rebuild");
#endif
  }
  return tm::run_case(cfg, opt);
}

namespace {

/// One line about the solver: its type and the numbers that say how hard it worked (the per-step
/// history stays in summary.json).
std::string solver_line(const nlohmann::json& solver) {
  nlohmann::json brief = nlohmann::json::object();
  for (auto it = solver.begin(); it != solver.end(); ++it)
    if (!it.value().is_object() && !it.value().is_array()) brief[it.key()] = it.value();
  if (solver.contains("newton")) {
    const auto& n = solver["newton"];
    for (const char* k : {"line_search", "max_iterations_in_a_step", "steps_at_roundoff"})
      if (n.contains(k)) brief[std::string("newton_") + k] = n[k];
  }
  return brief.dump();
}

void print_summary(const tmlab::RunResult& r, bool plots) {
  const auto& s = r.summary;
  std::cout << "case        " << s.value("case", "") << " (" << s.value("model", "") << ")\n"
            << "mesh        " << s["mesh"]["points"] << " nodes, " << s["mesh"]["tets"] << " tets, volume "
            << std::setprecision(4) << s["mesh"]["volume_m3"].get<double>() * 1e6 << " cm^3\n"
            << "solver      " << solver_line(s["solver"]) << "\n"
            << "final time  " << s["final_time"].get<double>() << " s\n"
            << "max |u|     " << s["max_displacement_m"].get<double>() * 1e3 << " mm\n"
            << "energy      " << s["elastic_energy_J"].get<double>() << " J\n";
  for (auto it = s["final_reactions_N"].begin(); it != s["final_reactions_N"].end(); ++it) {
    const auto& v = it.value();
    std::cout << "reaction    " << it.key() << ": (" << v[0].get<double>() << ", " << v[1].get<double>()
              << ", " << v[2].get<double>() << ") N\n";
  }
  std::cout << "min J       " << s["min_volume_ratio"].get<double>()
            << " (smallest deformed/rest volume ratio over all recorded steps, t = 0 included)\n"
            << "wall time   " << s["run_seconds"].get<double>() << " s\n"
            << "results     " << r.dir << "/ (summary.json, timeseries.h5";
  if (s.value("field_frames", 0) > 0) std::cout << ", fields.xdmf, result.pvd";
  if (plots && s.value("plots", std::string()) == "ok") std::cout << ", *.png";
  std::cout << ")\n";
}

int run_config(const CaseConfig& cfg, const ParsedOptions& p, const std::string& command_line) {
  tmlab::RunOptions opt;
  opt.tmlab_root = tmlab_root();
  opt.results_root = results_root(p);
  opt.command_line = split_words(command_line);
  opt.plots = !p.flag("--no-plots");
  opt.log = &std::cerr;
  // demo's table has no --model, --degree, --time-integration, --checkpoint-every or --resume.
  const auto has = [&p](const char* name) { return p.spec().find(name) != nullptr && p.given(name); };
  const std::string model = has("--model") ? p.text("--model") : to_string(cfg.model);
  // Checkpoints and --resume (docs/robustness.md): the tensor-mass runner's.
  opt.resume = has("--resume");
  if (has("--checkpoint-every")) opt.checkpoints = checkpoint_schedule(p);
  if ((opt.resume || has("--checkpoint-every")) && model == "reference")
    throw UsageError(
        "--resume and --checkpoint-every are for the tensor-mass models (tensor_mass, tl_oracle); "
        "the deal.II reference has no checkpoints");
  // The reference's degree follows the case's element (P2 for p2 and p2_mean_dilatation) unless given.
  int degree = is_quadratic(cfg.mesh.element) ? 2 : 1;
  if (has("--degree")) {
    if (model != "reference")
      throw UsageError("--degree applies to the deal.II reference only (add --model reference); the " +
                       model + " model's element is mesh.element (or --element)");
    degree = p.text("--degree") == "2" ? 2 : 1;
    if (degree == 1 && is_quadratic(cfg.mesh.element))
      throw UsageError("--degree 1 contradicts the case's mesh.element '" + to_string(cfg.mesh.element) +
                       "' (a quadratic element): drop --degree, or run --element p1");
  }
  const std::string time_integration =
      has("--time-integration") ? p.text("--time-integration") : "fixed_step";
  if (time_integration == "ida" && model != "reference")
    throw UsageError("--time-integration ida needs --model reference");
  std::cerr << "tmlab: running '" << cfg.name << "' (" << model << ")\n";
  const tmlab::RunResult r = run_model(cfg, opt, model, degree, time_integration);
  print_summary(r, opt.plots);
  return 0;
}

}  // namespace

int cmd_demo(const std::vector<std::string>& args, const std::string& command_line) {
  const ParsedOptions p = parse(demo_spec(), args);
  if (!p.positional.empty()) throw UsageError("demo takes no positional arguments");
  const nlohmann::json doc = nlohmann::json::parse(kDemoCase);
  const CaseConfig cfg = parse_case(doc, "<embedded demo case>", {tmlab_root()});
  return run_config(cfg, p, command_line);
}

int cmd_run(const std::vector<std::string>& args, const std::string& command_line) {
  const ParsedOptions p = parse(run_spec(), args);
  if (p.positional.size() != 1) throw UsageError("run needs exactly one case name or case file");
  CaseConfig cfg = load_case(resolve_case(p.positional[0]), tmlab_root());
  if (const std::optional<CaseModel> fast = case_model_from_string(p.text("--model")); fast)
    cfg.model = *fast;
  if (p.given("--element")) cfg.mesh.element = *element_kind_from_string(p.text("--element"));
  return run_config(cfg, p, command_line);
}

}  // namespace tmlab::cli
