// tmlab discover DATA.csv | --benchmark: model discovery from measured data (issue 15;
// docs/discover.md). Thin: tmlab::discover does the work; this file reads the options, writes
// report.json, discover.h5, the plots, index.html and the manifest through the result protocol
// (a failed run leaves FAILED), and prints progress on standard error.
#include "commands.hpp"

#include "cli_args.hpp"
#include "command_specs.hpp"

#include "calibration/data/measured_data.hpp"
#include "calibration/data/sign_convention.hpp"
#include "calibration/discover/benchmark.hpp"
#include "calibration/discover/discover.hpp"
#include "calibration/discover/discover_checkpoint.hpp"
#include "calibration/discover/discover_output.hpp"
#include "calibration/discover/fe_refit.hpp"
#include "core/base/error.hpp"
#include "core/results/run_output.hpp"
#include "core/results/run_protocol.hpp"
#include "core/results/unit_checkpoint.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>
#include <tuple>

namespace tmlab::cli {

namespace fs = std::filesystem;

namespace {

int run_benchmark_command(const ParsedOptions& p, const discover::Options& o,
                          const std::string& command_line) {
  const bool quick = p.flag("--quick");
  const fs::path dir = p.given("--out") ? fs::path(p.text("--out"))
                                        : fs::path(tmlab_root()) / "results" / "discover" /
                                              (quick ? "benchmark-quick" : "benchmark");
  // A checkpoint after every finished set (docs/robustness.md); --resume reads it before the result
  // directory is touched.
  nlohmann::json fingerprint = p.config(kFingerprint);
  fingerprint["engine"] = discover::options_fingerprint(o);  // the options as the engine holds them
  discover::BenchmarkLog log;
  UnitListCheckpoint<discover::BenchmarkEntry> units(dir, "discover-benchmark", fingerprint,
                                                     checkpoint_schedule(p), discover::put_benchmark_entries,
                                                     "benchmark set(s)");
  if (p.flag("--resume")) {
    refuse_resume_of_complete(dir, "benchmark");
    log.restored = units.restore(discover::get_benchmark_entries, std::cerr, "tmlab discover");
  }
  log.finished = [&units](const discover::BenchmarkEntry& e) { units.finished(e); };
  RunOutput out(dir, &std::cerr,
                p.flag("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  ManifestInput mi;
  mi.command_line = split_words(command_line);
  mi.config = p.config(kManifest);
  mi.config["engine"] = discover::options_fingerprint(o);
  run_with_protocol(
      out, mi,
      [&] {
        auto sets = discover::benchmark_sets(quick);
        // Only the sets of the rigs named (e.g. to rerun the indentation sets alone), then only
        // those whose truth is named (e.g. to rerun one effect's sets).
        if (p.given("--rig") && (sets = discover::select_sets(std::move(sets), p.text("--rig"), "")).empty())
          throw UsageError(
              "--rig: no benchmark set on '" + p.text("--rig") +
              "' (unconfined_compression, sphere_indentation, uniaxial_tension, confined_compression)");
        if (p.given("--only") &&
            (sets = discover::select_sets(std::move(sets), "", p.text("--only"))).empty())
          throw UsageError("--only: no benchmark set has the truth '" + p.text("--only") + "'");
        if (p.flag("--write-sets"))
          // Each set in the interchange format, so that `tmlab discover sets/NAME.csv` reruns one alone.
          for (const auto& s : sets) measured::write_data_set(s.data, out.staging_dir() / "sets");
        const discover::BenchmarkResult b = discover::run_benchmark(sets, o, &log);
        out.write_json("benchmark.json", discover::to_json(b));
        discover::write_confusion_csv(out.file("confusion_matrix.csv"), b);
        discover::print_benchmark_report(std::cout, b);
        return discover::summary_json(b);
      },
      protocol_checkpoint(units.file()));
  std::cout << "written: " << out.dir().string() << "/ (benchmark.json, confusion_matrix.csv)\n";
  return 0;
}

/// tmlab discover DATA.csv: the loop, its FE refits (--forward fe_rig), report.json, discover.h5,
/// the plots and index.html.
int run_discover_command(const ParsedOptions& p, discover::Options o, const discover::FeRefitOptions& fe,
                         const std::string& command_line) {
  const std::string forward = p.text("--forward");
  const fs::path csv = p.positional[0];
  const measured::DataSet data = measured::read_data_set(csv);
  measured::check_force_sign(data, csv.string());  // the check tmlab fit makes (one rule)
  const fs::path dir = p.given("--out") ? fs::path(p.text("--out"))
                                        : fs::path(tmlab_root()) / "results" / "discover" / data.meta.name;
  if (!p.given("--out")) {
    const std::string why = result_name_problem(data.meta.name);
    if (!why.empty()) throw Error("discover: result name: " + why);
  }
  // A checkpoint after every fit of the loop (and of the FE refits) (docs/robustness.md); --resume
  // reads it before the result directory is touched.
  nlohmann::json fingerprint = p.config(kFingerprint);
  fingerprint["engine"] = discover::options_fingerprint(o);  // the options as the engine holds them
  fingerprint["data"] = {{"csv", file_hash(csv)}, {"metadata", file_hash(measured::metadata_path(csv))}};
  discover::FitLog log;
  UnitListCheckpoint<discover::FitOutcome> units(dir, "discover", fingerprint, checkpoint_schedule(p),
                                                 discover::put_fit_outcomes, "fit(s)");
  if (p.flag("--resume")) {
    refuse_resume_of_complete(dir, "discovery");
    log.restored = units.restore(discover::get_fit_outcomes, std::cerr, "tmlab discover");
  }
  log.finished = [&units](const discover::FitOutcome& f) { units.finished(f); };
  o.fit_log = &log;
  if (forward == "fe_rig")  // effects that only stand in for the rig's discretisation error are refused
    o.discretisation = [&data, &fe](const discover::Prepared& prep, const discover::Fitted& baseline) {
      return discover::baseline_discretisation(data, prep, baseline, fe);
    };
  RunOutput out(dir, &std::cerr,
                p.flag("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  ManifestInput mi;
  mi.command_line = split_words(command_line);
  mi.config = p.config(kManifest);
  mi.config["engine"] = discover::options_fingerprint(o);
  mi.input_files = {csv, measured::metadata_path(csv)};
  std::string plots = "skipped (--no-plots)";
  run_with_protocol(
      out, mi,
      [&] {
        const discover::Report r = discover::run(data, o);
        nlohmann::json j = discover::to_json(r);
        std::vector<discover::FeRefit> fe_refits;
        if (forward == "fe_rig") {
          fe_refits = discover::fe_rig_refit(data, r, o, fe);
          j["fe_rig"] = discover::to_json(fe_refits, r.data.peak_force, fe);
        }
        out.write_json("report.json", j);
        discover::write_discover_h5(out.file("discover.h5"), r, fe_refits);
        if (!p.flag("--no-plots")) {
          plots = discover::write_discover_plots(out.staging_dir(), tmlab_root());
          if (plots != "ok") std::cerr << "tmlab discover: plots " << plots << "\n";
        }
        discover::write_report_html(out.file("index.html"), j, plots == "ok");
        discover::print_discover_report(std::cout, r, fe_refits);
        return discover::summary_json(r, plots);
      },
      protocol_checkpoint(units.file()));
  std::cout << "written: " << out.dir().string()
            << "/ (index.html, report.json, discover.h5, manifest.json, summary.json"
            << (plots == "ok" ? ", discover_*.png" : "") << ")\n";
  return 0;
}

}  // namespace

int cmd_discover(const std::vector<std::string>& args, const std::string& command_line) {
  const ParsedOptions p = parse(discover_spec(), args);
  discover::Options o;
  o.max_samples = std::size_t(p.whole("--max-samples"));
  o.max_rounds = int(p.whole("--rounds"));
  o.starts = int(p.whole("--starts"));
  o.threads = int(p.whole("--threads"));
  o.seed = (unsigned long)p.whole("--seed");
  o.baseline_prony = int(p.whole("--baseline-prony"));
  o.poisson = p.decimal("--poisson");
  o.fix_poisson = !p.flag("--free-poisson");
  o.test_control = !p.flag("--no-test-control");
  for (const std::string& e : p.text_list("--effects")) {
    discover::effect_info(e);  // tmlab::Error naming the known effects
    o.effects.push_back(e);
  }
  const bool fe_rig = p.text("--forward") == "fe_rig";
  discover::FeRefitOptions fe;
  std::tie(fe.mesh.cells, fe.mesh.layers) = parse_cells_layers(p.text("--mesh"));
  fe.substeps = int(p.whole("--substeps"));
  fe.max_iterations = int(p.whole("--fe-iterations"));
  fe.max_samples = std::size_t(p.whole("--fe-max-samples"));
  if (!fe_rig && (p.given("--mesh") || p.given("--substeps") || p.given("--fe-iterations") ||
                  p.given("--fe-max-samples")))
    throw UsageError("--mesh, --substeps, --fe-iterations and --fe-max-samples are for --forward fe_rig");
  if (!p.flag("--quiet"))
    o.progress = [](const std::string& line) { std::cerr << line << "\n" << std::flush; };
  if (p.flag("--benchmark")) {
    if (!p.positional.empty()) throw UsageError("discover --benchmark takes no DATA.csv");
    if (fe_rig) throw UsageError("--forward fe_rig is for one DATA.csv, not --benchmark");
    return run_benchmark_command(p, o, command_line);
  }
  if (p.flag("--quick") || p.given("--rig") || p.given("--only") || p.flag("--write-sets"))
    throw UsageError("--quick, --rig, --only and --write-sets are for --benchmark");
  if (p.positional.size() != 1) throw UsageError("discover needs exactly one DATA.csv (or --benchmark)");
  return run_discover_command(p, o, fe, command_line);
}

}  // namespace tmlab::cli
