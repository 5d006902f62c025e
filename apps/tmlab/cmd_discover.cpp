// tmlab discover DATA.csv | --benchmark: model discovery from measured data (issue 15;
// docs/discover.md). Thin: tmlab::discover does the work; this file reads the options, writes
// report.json, discover.h5, the plots, index.html and the manifest through the result protocol
// (a failed run leaves FAILED), and prints progress on standard error.
#include "commands.hpp"

#include "cli_args.hpp"

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

int run_benchmark_command(const Parsed& p, const discover::Options& o, const std::string& command_line) {
  const bool quick = p.has("--quick");
  const fs::path dir = p.has("--out") ? fs::path(p.get("--out"))
                                      : fs::path(tmlab_root()) / "results" / "discover" /
                                            (quick ? "benchmark-quick" : "benchmark");
  // A checkpoint after every finished set (docs/robustness.md); --resume reads it before the result
  // directory is touched.
  const nlohmann::json selection = {{"quick", quick},
                                    {"rig", p.has("--rig") ? p.get("--rig") : "all"},
                                    {"only", p.has("--only") ? p.get("--only") : "all"}};
  nlohmann::json fingerprint = discover::options_fingerprint(o);
  fingerprint["benchmark"] = selection;
  discover::BenchmarkLog log;
  UnitListCheckpoint<discover::BenchmarkEntry> units(dir, "discover-benchmark", fingerprint,
                                                     checkpoint_schedule(p), discover::put_benchmark_entries,
                                                     "benchmark set(s)");
  if (p.has("--resume")) {
    refuse_resume_of_complete(dir, "benchmark");
    log.restored = units.restore(discover::get_benchmark_entries, std::cerr, "tmlab discover");
  }
  log.finished = [&units](const discover::BenchmarkEntry& e) { units.finished(e); };
  RunOutput out(dir, &std::cerr,
                p.has("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  ManifestInput mi;
  mi.command_line = split_words(command_line);
  mi.config = selection;
  mi.config.update({{"seed", o.seed}, {"starts", o.starts}, {"threads", o.threads}});
  run_with_protocol(
      out, mi,
      [&] {
        auto sets = discover::benchmark_sets(quick);
        // Only the sets of the rigs named (e.g. to rerun the indentation sets alone), then only
        // those whose truth is named (e.g. to rerun one effect's sets).
        if (p.has("--rig") && (sets = discover::select_sets(std::move(sets), p.get("--rig"), "")).empty())
          throw UsageError(
              "--rig: no benchmark set on '" + p.get("--rig") +
              "' (unconfined_compression, sphere_indentation, uniaxial_tension, confined_compression)");
        if (p.has("--only") && (sets = discover::select_sets(std::move(sets), "", p.get("--only"))).empty())
          throw UsageError("--only: no benchmark set has the truth '" + p.get("--only") + "'");
        if (p.has("--write-sets"))
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
int run_discover_command(const Parsed& p, discover::Options o, const std::string& forward,
                         const discover::FeRefitOptions& fe, const std::string& command_line) {
  const fs::path csv = p.positional[0];
  const measured::DataSet data = measured::read_data_set(csv);
  measured::check_force_sign(data, csv.string());  // the check tmlab fit makes (one rule)
  const fs::path dir = p.has("--out") ? fs::path(p.get("--out"))
                                      : fs::path(tmlab_root()) / "results" / "discover" / data.meta.name;
  if (!p.has("--out")) {
    const std::string why = result_name_problem(data.meta.name);
    if (!why.empty()) throw Error("discover: result name: " + why);
  }
  // A checkpoint after every fit of the loop (and of the FE refits) (docs/robustness.md); --resume
  // reads it before the result directory is touched.
  nlohmann::json fingerprint = discover::discovery_fingerprint(o, forward, fe);
  fingerprint["data"] = {{"csv", file_hash(csv)}, {"metadata", file_hash(measured::metadata_path(csv))}};
  discover::FitLog log;
  UnitListCheckpoint<discover::FitOutcome> units(dir, "discover", fingerprint, checkpoint_schedule(p),
                                                 discover::put_fit_outcomes, "fit(s)");
  if (p.has("--resume")) {
    refuse_resume_of_complete(dir, "discovery");
    log.restored = units.restore(discover::get_fit_outcomes, std::cerr, "tmlab discover");
  }
  log.finished = [&units](const discover::FitOutcome& f) { units.finished(f); };
  o.fit_log = &log;
  RunOutput out(dir, &std::cerr,
                p.has("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  ManifestInput mi;
  mi.command_line = split_words(command_line);
  mi.config = discover::manifest_config(o, forward);
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
        if (!p.has("--no-plots")) {
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
  const Parsed p = parse(args,
                         {"--out", "--poisson", "--max-samples", "--rounds", "--starts", "--threads",
                          "--seed", "--effects", "--baseline-prony", "--rig", "--only", "--forward", "--mesh",
                          "--substeps", "--fe-iterations", "--fe-max-samples", "--checkpoint-every"},
                         {"--benchmark", "--quick", "--write-sets", "--free-poisson", "--no-plots", "--quiet",
                          "--resume", "--no-test-control"});
  discover::Options o;
  auto whole = [&](const std::string& key, int fallback, int lo, int hi) {
    return p.has(key) ? int(parse_whole(key, p.get(key), lo, hi)) : fallback;
  };
  o.max_samples = std::size_t(whole("--max-samples", int(o.max_samples), 50, 1000000));
  o.max_rounds = whole("--rounds", o.max_rounds, 1, 20);
  o.starts = whole("--starts", o.starts, 1, 1000);
  o.threads = whole("--threads", 2, 1, 64);
  o.seed = (unsigned long)whole("--seed", 1, 1, 1000000);
  o.baseline_prony = whole("--baseline-prony", o.baseline_prony, 0, 4);
  if (p.has("--poisson")) {
    o.poisson = parse_double("--poisson", p.get("--poisson"));
    if (!(o.poisson > 0.0 && o.poisson < 0.4999)) throw UsageError("--poisson must lie in (0, 0.4999)");
  }
  o.fix_poisson = !p.has("--free-poisson");
  o.test_control = !p.has("--no-test-control");
  if (p.has("--effects")) {
    std::string s = p.get("--effects");
    std::size_t a = 0;
    for (;;) {
      const std::size_t b = s.find(',', a);
      const std::string e = s.substr(a, b == std::string::npos ? std::string::npos : b - a);
      discover::effect_info(e);  // tmlab::Error naming the known effects
      o.effects.push_back(e);
      if (b == std::string::npos) break;
      a = b + 1;
    }
  }
  const std::string forward = p.get("--forward", "closed_form");
  if (forward != "closed_form" && forward != "fe_rig")
    throw UsageError("--forward must be closed_form or fe_rig (got '" + forward + "')");
  discover::FeRefitOptions fe;
  if (p.has("--mesh")) std::tie(fe.mesh.cells, fe.mesh.layers) = parse_cells_layers(p.get("--mesh"));
  fe.substeps = whole("--substeps", fe.substeps, 1, 100);
  fe.max_iterations = whole("--fe-iterations", fe.max_iterations, 1, 200);
  fe.max_samples = std::size_t(whole("--fe-max-samples", int(fe.max_samples), 20, 1000000));
  if (forward != "fe_rig" &&
      (p.has("--mesh") || p.has("--substeps") || p.has("--fe-iterations") || p.has("--fe-max-samples")))
    throw UsageError("--mesh, --substeps, --fe-iterations and --fe-max-samples are for --forward fe_rig");
  if (!p.has("--quiet"))
    o.progress = [](const std::string& line) { std::cerr << line << "\n" << std::flush; };
  if (p.has("--benchmark")) {
    if (!p.positional.empty()) throw UsageError("discover --benchmark takes no DATA.csv");
    if (forward != "closed_form") throw UsageError("--forward fe_rig is for one DATA.csv, not --benchmark");
    return run_benchmark_command(p, o, command_line);
  }
  if (p.has("--quick") || p.has("--rig") || p.has("--only") || p.has("--write-sets"))
    throw UsageError("--quick, --rig, --only and --write-sets are for --benchmark");
  if (p.positional.size() != 1) throw UsageError("discover needs exactly one DATA.csv (or --benchmark)");
  return run_discover_command(p, o, forward, fe, command_line);
}

}  // namespace tmlab::cli
