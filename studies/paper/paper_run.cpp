#include "studies/paper/paper_run.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/config/case_config.hpp"
#include "core/io/atomic_file.hpp"
#include "core/results/run_output.hpp"
#include "runner/case_runner.hpp"
#include "studies/common/study_plot.hpp"

#include <fstream>
#include <ostream>

namespace tmlab::tm {

namespace {

namespace fs = std::filesystem;

/// One run of the figure: reused when --resume finds it complete, else run into `dir`.
RunResult run_one(const PaperFigure& fig, const PaperRun& run, std::size_t k, const PaperRunOptions& o,
                  const fs::path& dir) {
  const CaseConfig cfg =
      parse_case(run.case_doc, o.params_file + " (" + fig.name + "/" + run.id + ")", {o.tmlab_root});
  const fs::path done = dir / cfg.name / RunOutput::kSummary;
  if (o.resume && fs::exists(done)) {
    std::ifstream in(done);
    if (o.log)
      *o.log << "tmlab paper " << fig.name << ": run " << run.id
             << " finished before the interruption: reused\n";
    return {done.parent_path().string(), nlohmann::json::parse(in)};
  }
  RunOptions opt;
  opt.tmlab_root = o.tmlab_root;
  opt.results_root = dir.string();
  opt.command_line = o.command_line;
  opt.plots = false;
  try {
    RunResult r = run_case(cfg, opt);
    note_progress_point();  // a finished run is what --resume reuses
    return r;
  } catch (const Interrupted& e) {
    throw Interrupted(e.signal(), std::string(e.what()) + " (run " + run.id + ", " + std::to_string(k - 1) +
                                      " of " + std::to_string(fig.runs.size()) +
                                      " runs finished): continue with the same command and --resume");
  }
}

/// Draws the figure; fig7 adds the energy table the drawing wrote to the summary.
void draw(const PaperFigure& fig, const PaperRunOptions& o, const fs::path& dir, nlohmann::json& summary) {
  const ProcessStatus ps = draw_study_plot(o.tmlab_root, "paper", "tmlab_paper_figure.py", dir);
  if (!ps.ok()) throw Error("drawing " + fig.name + " failed (" + ps.describe() + ")");
  summary["plots"] = "ok";
  if (fig.name == "fig7") {
    const fs::path energy = dir / "fig7_energy.json";
    std::ifstream in(energy);
    if (!in) throw Error(energy.string() + ": not written by the figure script");
    summary["energy"] = nlohmann::json::parse(in);
  }
}

}  // namespace

nlohmann::json run_paper_figure(const PaperFigure& fig, const PaperRunOptions& o, const fs::path& dir) {
  nlohmann::json spec = {{"name", fig.name},        {"title", fig.title},
                         {"xlabel", fig.xlabel},    {"ylabel", fig.ylabel},
                         {"params", o.params_file}, {"runs", nlohmann::json::array()}};
  std::size_t k = 0;
  for (const auto& run : fig.runs) {
    ++k;
    if (o.log)
      *o.log << "tmlab paper " << fig.name << ": run " << k << "/" << fig.runs.size() << " " << run.id
             << "\n";
    const RunResult r = run_one(fig, run, k, o, dir);
    spec["runs"].push_back({{"id", run.id},
                            {"label", run.label},
                            {"scheme", run.scheme},
                            {"dir", fs::path(r.dir).filename().string()},  // relative to the figure
                            {"x", run.x},
                            {"y", run.y},
                            {"x_sign", run.x_sign},
                            {"y_sign", run.y_sign}});
  }
  write_file_atomically(dir / "figure.json", spec.dump(2) + "\n");
  nlohmann::json summary = {
      {"figure", fig.name}, {"runs", fig.runs.size()}, {"plots", "skipped (--no-plots)"}};
  if (o.plots) draw(fig, o, dir, summary);
  return summary;
}

}  // namespace tmlab::tm
