// tmlab paper fig5|fig6|fig7: the liver experiments of Xu et al. 2011.
#include "commands.hpp"

#include "cli_args.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/base/process.hpp"
#include "core/config/case_config.hpp"
#include "core/config/config_reader.hpp"
#include "core/results/run_output.hpp"
#include "tensormass/runner/case_runner.hpp"
#include "verification/studies/paper_experiments.hpp"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

namespace tmlab::cli {

namespace fs = std::filesystem;

int cmd_paper(const std::vector<std::string>& args, const std::string& command_line) {
  const Parsed p = parse(args, {"--results", "--params"}, {"--no-plots", "--resume"});
  if (p.positional.size() != 1) throw UsageError("paper needs one figure: fig5, fig6 or fig7");
  const std::string params_file =
      p.get("--params", (fs::path(tmlab_root()) / "cases" / "paper" / "xu2011_liver.json").string());
  const nlohmann::json params = ConfigReader::parse_file(params_file);
  const tm::PaperFigure fig = tm::paper_figure(p.positional[0], params, params_file);
  // The figure is one result directory, results/paper/<fig>/, written through the run protocol:
  // its runs are staged inside it, figure.json and the drawing next to them, and the whole appears
  // at once when everything has succeeded (a killed run leaves FAILED/INTERRUPTED, never an old
  // figure that looks current).
  const fs::path dir =
      fs::path(p.get("--results", (fs::path(tmlab_root()) / "results").string())) / "paper" / fig.name;
  // --resume: the runs an interrupted figure finished (complete result directories in its staging
  // area) are reused; the others run again from their start.
  const bool resume = p.has("--resume");
  RunOutput out(dir, &std::cerr,
                resume ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  try {
    ManifestInput mi;
    mi.command_line = split_words(command_line);
    mi.config = {{"figure", fig.name}, {"params", params}};
    mi.input_files = {params_file};
    out.write_json("manifest.json", make_manifest(mi));
    nlohmann::json spec = {{"name", fig.name},      {"title", fig.title},
                           {"xlabel", fig.xlabel},  {"ylabel", fig.ylabel},
                           {"params", params_file}, {"runs", nlohmann::json::array()}};
    std::size_t k = 0;
    for (const auto& run : fig.runs) {
      ++k;
      std::cerr << "tmlab paper " << fig.name << ": run " << k << "/" << fig.runs.size() << " " << run.id
                << "\n";
      const CaseConfig cfg =
          parse_case(run.case_doc, params_file + " (" + fig.name + "/" + run.id + ")", {tmlab_root()});
      tmlab::RunOptions opt;
      opt.tmlab_root = tmlab_root();
      opt.results_root = out.staging_dir().string();
      opt.command_line = split_words(command_line);
      opt.plots = false;
      tmlab::RunResult r;
      const fs::path done = out.staging_dir() / cfg.name / RunOutput::kSummary;
      if (resume && fs::exists(done)) {
        std::ifstream in(done);
        r = {done.parent_path().string(), nlohmann::json::parse(in)};
        std::cerr << "tmlab paper " << fig.name << ": run " << run.id
                  << " finished before the interruption: reused\n";
      } else {
        try {
          r = tm::run_case(cfg, opt);
        } catch (const Interrupted& e) {
          throw Interrupted(e.signal(), std::string(e.what()) + " (run " + run.id + ", " +
                                            std::to_string(k - 1) + " of " + std::to_string(fig.runs.size()) +
                                            " runs finished): continue with the same command and --resume");
        }
      }
      spec["runs"].push_back({{"id", run.id},
                              {"label", run.label},
                              {"scheme", run.scheme},
                              {"dir", fs::path(r.dir).filename().string()},  // relative to the figure
                              {"x", run.x},
                              {"y", run.y},
                              {"x_sign", run.x_sign},
                              {"y_sign", run.y_sign}});
    }
    out.write_json("figure.json", spec);
    nlohmann::json summary = {
        {"figure", fig.name}, {"runs", fig.runs.size()}, {"plots", "skipped (--no-plots)"}};
    if (!p.has("--no-plots")) {
      const fs::path script =
          fs::path(tmlab_root()) / "verification" / "studies" / "python" / "tmlab_paper_figure.py";
      const ProcessStatus ps = run_python(script, {out.staging_dir().string()});
      if (!ps.ok()) throw Error("drawing " + fig.name + " failed (" + ps.describe() + ")");
      summary["plots"] = "ok";
      if (fig.name == "fig7") {
        std::ifstream in(out.file("fig7_energy.json"));
        if (!in) throw Error(out.file("fig7_energy.json").string() + ": not written by the figure script");
        summary["energy"] = nlohmann::json::parse(in);
      }
    }
    out.finalize(summary);
    if (summary.contains("energy")) {
      std::cout << "hysteresis: loop area = dissipated + stored at the end of the cycle\n";
      for (const auto& row : summary["energy"])
        std::cout << "  " << std::left << std::setw(24) << row["run"].get<std::string>() << " loop "
                  << row["loop_area_J"].get<double>() << " J, dissipated "
                  << row["dissipation_J"].get<double>() << " J, stored " << row["stored_end_J"].get<double>()
                  << " J, relative residual " << row["relative_residual"].get<double>() << "\n";
    }
    std::cout << "written: " << out.dir().string() << "/\n";
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
  return 0;
}

}  // namespace tmlab::cli
