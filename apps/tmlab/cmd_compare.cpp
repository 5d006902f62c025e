// tmlab compare: a case with the tensor-mass model and a reference, and their differences.
#include "commands.hpp"

#include "cli_args.hpp"
#include "command_specs.hpp"

#include "core/base/error.hpp"
#include "core/base/process.hpp"
#include "core/config/case_config.hpp"
#include "core/config/element_kind.hpp"
#include "core/config/fast_model.hpp"
#include "core/results/recorder.hpp"
#include "core/results/result_compare.hpp"
#include "core/results/run_output.hpp"
#include "runner/case_runner.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace tmlab::cli {

namespace fs = std::filesystem;

namespace {

/// The per-step differences as series (no units: they are ratios); `floor` > 0 floors the
/// differences for a log-scale plot (round-off zeros).
SeriesTable comparison_table(const ComparisonSeries& s, double floor) {
  SeriesTable t;
  for (double v : s.time) t.add("time", "", v);
  for (double v : s.step_time) t.add("step_time", "", v);
  for (double v : s.rel_displacement) t.add("rel_diff_displacement", "", std::max(v, floor));
  for (double v : s.rel_reaction) t.add("rel_diff_reaction", "", std::max(v, floor));
  for (double v : s.rel_energy) t.add("rel_diff_energy", "", std::max(v, floor));
  for (double v : s.rel_contact_force) t.add("rel_diff_contact_force", "", std::max(v, floor));
  for (double v : s.rel_contact_area) t.add("rel_diff_contact_area", "", std::max(v, floor));
  return t;
}

/// The comparison's result directory: <case>-compare (against the reference), <case>-compare-<against>.
std::string compare_dir_name(const std::string& case_name, const std::string& against) {
  return case_name + "-compare" + (against == "reference" ? "" : "-" + against);
}

}  // namespace

int cmd_compare(const std::vector<std::string>& args, const std::string& command_line) {
  const ParsedOptions p = parse(compare_spec(), args);
  if (p.positional.size() != 1) throw UsageError("compare needs exactly one case name or case file");
  const CaseConfig cfg = load_case(resolve_case(p.positional[0]), tmlab_root());
  const std::string against = p.text("--against");
  // The reference's degree: --degree, else the case's element's (2 for p2 and p2_mean_dilatation).
  const int degree =
      p.given("--degree") ? (p.text("--degree") == "2" ? 2 : 1) : (is_quadratic(cfg.mesh.element) ? 2 : 1);
  if (degree == 1 && is_quadratic(cfg.mesh.element))
    throw UsageError("--degree 1 contradicts the case's mesh.element '" + to_string(cfg.mesh.element) +
                     "': the fast model runs 10-node tets, so the reference runs P2 (drop --degree)");
  const std::string time_integration = p.text("--time-integration");
  if (time_integration == "ida" && against != "reference")
    throw UsageError("--time-integration ida needs --against reference");
  if (p.given("--degree") && against != "reference")
    throw UsageError("--degree (the reference's element degree) needs --against reference");

  tmlab::RunOptions opt;
  opt.tmlab_root = tmlab_root();
  opt.results_root = results_root(p);
  opt.command_line = split_words(command_line);
  opt.plots = false;
  opt.log = &std::cerr;
  // The comparison is a result of its own, taken before either model runs (a folder it may not write
  // into is refused before computing) and written through the same protocol as every run (staged,
  // summary.json last, one writer, FAILED/INTERRUPTED on failure): <results>/<case>-compare/ against
  // the reference, <results>/<case>-compare-tl_oracle/ against the oracle, so neither replaces the other.
  RunOutput out(fs::path(opt.results_root) / compare_dir_name(cfg.name, against), &std::cerr);
  // Not run_with_protocol: the manifest names both runs' folders, known only after they ran, and
  // the comparison keeps no checkpoint (each run has its own).
  try {
    CaseConfig tm_cfg = cfg;
    // The fast model: the tensor-mass kernel for St VK, the F-based kernel for the other laws.
    tm_cfg.model = fast_model_for(cfg.material.law);
    // The elements other than p1 run on the F-based kernel only (any law, St VK included).
    if (cfg.mesh.element != ElementKind::P1) tm_cfg.model = CaseModel::HyperelasticTL;
    std::cerr << "tmlab compare: fast-model run (" << to_string(tm_cfg.model) << ")\n";
    const tmlab::RunResult a = tm::run_case(tm_cfg, opt);
    tmlab::RunResult b;
    // The reference's element: P1, P2, or P2 with the F-bar of p2_mean_dilatation (it follows the
    // case's mesh.element). p1_anp has no counterpart there: the reference runs plain P1 tets.
    const std::string reference_element =
        "P" + std::to_string(degree) +
        (cfg.mesh.element == ElementKind::P2MeanDilatation ? " mean dilatation (F-bar per cell)" : "");
    if (against == "reference") {
      std::cerr << "tmlab compare: deal.II reference run (" << reference_element << ")\n";
      if (cfg.mesh.element == ElementKind::P1Anp)
        std::cerr << "tmlab compare: note: the reference has no averaged-nodal-pressure element; it runs "
                     "plain P1 tets, so the differences include the two elements' (docs/elements.md)\n";
      b = run_model(cfg, opt, "reference", degree, time_integration);
    } else {
      CaseConfig o = cfg;
      o.name = cfg.name + "-tl_oracle";
      o.model = CaseModel::TlOracle;
      std::cerr << "tmlab compare: total-Lagrangian oracle run\n";
      b = tm::run_case(o, opt);
    }
    ComparisonSeries series;
    nlohmann::json cmp = compare_results(a.dir, b.dir, &series);
    cmp["case"] = cfg.name;
    cmp["a"] = a.dir;
    cmp["b"] = b.dir;
    cmp["against"] = against;
    cmp["element"] = to_string(cfg.mesh.element);
    if (against == "reference") cmp["reference_element"] = reference_element;
    ManifestInput mi;
    mi.command_line = opt.command_line;
    mi.config = p.config(kManifest);
    mi.config.update({{"case", effective_case_json(cfg)}, {"a", a.dir}, {"b", b.dir}});
    out.write_json("manifest.json", make_manifest(mi));
    out.write_json("compare.json", cmp);
    write_series_file(out.file("compare.h5"), comparison_table(series, 0.0));
    // Plot: the per-step relative differences on a log scale (round-off zeros floored at 1e-17).
    std::string plot_status = "skipped (--no-plots)";
    if (!p.flag("--no-plots")) {
      write_series_file(out.file("timeseries.h5"), comparison_table(series, 1e-17));
      nlohmann::json plots = nlohmann::json::array(
          {{{"file", "compare_displacement.png"},
            {"x", "time"},
            {"y", {"rel_diff_displacement"}},
            {"title", cfg.name + ": tensor-mass vs " + against + ", nodal displacements"},
            {"xlabel", "time [s]"},
            {"ylabel", "|u_a - u_b| / |u_b|"},
            {"logy", true}},
           {{"file", "compare_reaction_energy.png"},
            {"x", "step_time"},
            {"y", {"rel_diff_reaction", "rel_diff_energy"}},
            {"title", cfg.name + ": tensor-mass vs " + against + ", reactions and energy"},
            {"xlabel", "time [s]"},
            {"ylabel", "relative difference"},
            {"logy", true}}});
      if (!series.rel_contact_force.empty())
        plots.push_back({{"file", "compare_contact.png"},
                         {"x", "step_time"},
                         {"y", {"rel_diff_contact_force", "rel_diff_contact_area"}},
                         {"title", cfg.name + ": tensor-mass vs " + against + ", contact force and area"},
                         {"xlabel", "time [s]"},
                         {"ylabel", "relative difference"},
                         {"logy", true}});
      out.write_json("plots.json", plots);
      const ProcessStatus ps =
          run_python(fs::path(tmlab_root()) / "core" / "results" / "python" / "tmlab_plot.py",
                     {out.staging_dir().string()}, ProcessOutput::discard());
      plot_status = ps.ok() ? "ok" : "failed (" + ps.describe() + ")";
    }
    nlohmann::json summary = cmp;
    summary["plots"] = plot_status;
    out.finalize(summary);
    std::cout << "comparison of " << cfg.name << ": tensor-mass vs " << against << "\n"
              << "  quantity                          max over steps\n"
              << "  rel_diff_displacement             " << cmp["rel_diff_displacement"].get<double>() << "\n"
              << "  rel_diff_reaction                 " << cmp["rel_diff_reaction"].get<double>() << "\n"
              << "  rel_diff_energy                   " << cmp["rel_diff_energy"].get<double>() << "\n";
    if (cmp.contains("rel_diff_contact_force"))
      std::cout << "  rel_diff_contact_force            " << cmp["rel_diff_contact_force"].get<double>()
                << "\n"
                << "  rel_diff_contact_area             " << cmp["rel_diff_contact_area"].get<double>()
                << "\n"
                << "  max_diff_active_nodes             " << cmp["max_diff_active_nodes"].get<double>()
                << "\n";
    std::cout << "written: " << out.dir().string() << "/ (compare.json, compare.h5, summary.json"
              << (plot_status == "ok" ? ", *.png" : "") << ")\n";
    if (plot_status != "ok" && !p.flag("--no-plots"))
      std::cerr << "tmlab compare: plots " << plot_status << "\n";
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
  return 0;
}

}  // namespace tmlab::cli
