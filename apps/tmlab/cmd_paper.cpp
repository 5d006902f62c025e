// tmlab paper fig2|fig3|table1|table2: the identification of Xu et al. 2011, Section IV-A
// (studies/paper/paper_fit.hpp); tmlab paper fig5|fig6|fig7: the liver experiments
// (studies/paper/paper_run.hpp).
#include "commands.hpp"

#include "cli_args.hpp"
#include "command_specs.hpp"

#include "core/config/config_reader.hpp"
#include "core/results/run_output.hpp"
#include "core/results/run_protocol.hpp"
#include "studies/paper/paper_fit.hpp"
#include "studies/paper/paper_run.hpp"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

namespace tmlab::cli {

namespace fs = std::filesystem;

namespace {

/// fig2|fig3|table1|table2: the Section IV-A identification, one result directory per target.
int paper_fit(const ParsedOptions& p, const std::string& target, const std::string& command_line) {
  tm::PaperFitOptions o;
  o.params_file = p.given("--params")
                      ? p.text("--params")
                      : (fs::path(tmlab_root()) / "cases" / "paper" / "xu2011_indentation.json").string();
  const nlohmann::json params = ConfigReader::parse_file(o.params_file);
  const bool quick = p.flag("--quick");
  const tm::PaperFitSettings s = tm::paper_fit_settings(params, o.params_file, quick);
  o.tmlab_root = tmlab_root();
  o.plots = !p.flag("--no-plots");
  o.resume = p.flag("--resume");
  o.log = &std::cerr;
  const fs::path dir = fs::path(results_root(p)) / "paper" / target;
  // Same protocol as the figures below; --resume reuses the fits an interrupted run finished.
  RunOutput out(dir, &std::cerr,
                o.resume ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  ManifestInput mi;
  mi.command_line = split_words(command_line);
  mi.config = p.config(kManifest);
  mi.config.update({{"target", target}, {"params", params}});
  mi.input_files = {o.params_file};
  nlohmann::json summary;
  run_with_protocol(out, mi, [&] { return summary = tm::run_paper_fit(target, s, o, out.staging_dir()); });
  const bool elastic = target == "fig2" || target == "table1";
  std::ifstream md(out.dir() / (elastic ? "table1.md" : "table2.md"));
  std::cout << md.rdbuf() << "\n"
            << summary["fits"].get<std::size_t>() << " fits, " << summary["fe_forward_solves"].get<long>()
            << " FE forward solves + " << summary["closed_form_solves"].get<long>() << " closed-form solves, "
            << summary["fit_wall_seconds"].get<double>() << " s of fitting\n"
            << "written: " << out.dir().string() << "/\n";
  return 0;
}

}  // namespace

int cmd_paper(const std::vector<std::string>& args, const std::string& command_line) {
  const ParsedOptions p = parse(paper_spec(), args);
  if (p.positional.size() != 1)
    throw UsageError("paper needs one target: fig2, fig3, table1, table2, fig5, fig6 or fig7");
  if (tm::is_paper_fit_target(p.positional[0])) return paper_fit(p, p.positional[0], command_line);
  if (p.positional[0] != "fig5" && p.positional[0] != "fig6" && p.positional[0] != "fig7")
    throw UsageError("unknown paper target '" + p.positional[0] +
                     "' (expected fig2, fig3, table1, table2, fig5, fig6 or fig7)");
  if (p.flag("--quick")) throw UsageError("--quick applies to fig2, fig3, table1 and table2 only");
  tm::PaperRunOptions o;
  o.params_file = p.given("--params")
                      ? p.text("--params")
                      : (fs::path(tmlab_root()) / "cases" / "paper" / "xu2011_liver.json").string();
  const nlohmann::json params = ConfigReader::parse_file(o.params_file);
  const tm::PaperFigure fig = tm::paper_figure(p.positional[0], params, o.params_file);
  o.tmlab_root = tmlab_root();
  o.command_line = split_words(command_line);
  o.plots = !p.flag("--no-plots");
  o.log = &std::cerr;
  // The figure is one result directory, results/paper/<fig>/, written through the run protocol:
  // its runs are staged inside it, figure.json and the drawing next to them, and the whole appears
  // at once when everything has succeeded (a killed run leaves FAILED/INTERRUPTED, never an old
  // figure that looks current).
  const fs::path dir = fs::path(results_root(p)) / "paper" / fig.name;
  // --resume: the runs an interrupted figure finished (complete result directories in its staging
  // area) are reused; the others run again from their start.
  o.resume = p.flag("--resume");
  RunOutput out(dir, &std::cerr,
                o.resume ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  ManifestInput mi;
  mi.command_line = o.command_line;
  mi.config = {{"figure", fig.name}, {"params", params}};  // --quick is refused for the figures
  mi.input_files = {o.params_file};
  nlohmann::json summary;
  run_with_protocol(out, mi, [&] { return summary = tm::run_paper_figure(fig, o, out.staging_dir()); });
  if (summary.contains("energy")) {
    std::cout << "hysteresis: loop area = dissipated + stored at the end of the cycle\n";
    for (const auto& row : summary["energy"])
      std::cout << "  " << std::left << std::setw(24) << row["run"].get<std::string>() << " loop "
                << row["loop_area_J"].get<double>() << " J, dissipated " << row["dissipation_J"].get<double>()
                << " J, stored " << row["stored_end_J"].get<double>() << " J, relative residual "
                << row["relative_residual"].get<double>() << "\n";
  }
  std::cout << "written: " << out.dir().string() << "/\n";
  return 0;
}

}  // namespace tmlab::cli
