// `tmlab paper FIG` (docs/paper-experiments.md): the runs of one figure (paper_experiments.hpp), each a
// complete result directory inside the figure's, then figure.json (which series of which run the
// figure draws) and the drawing (python/tmlab_paper_figure.py: <fig>.png, <fig>.h5 and, for fig7,
// the energy balance of each hysteresis loop). The command (apps/tmlab/cmd_paper.cpp) parses the
// arguments and owns the figure's result directory.
#pragma once

#include "studies/paper/paper_experiments.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace tmlab::tm {

struct PaperRunOptions {
  std::string params_file;                ///< the parameter document the figure was built from
  std::string tmlab_root = ".";           ///< meshes/, studies/<study>/python/
  std::vector<std::string> command_line;  ///< recorded in each run's manifest
  bool plots = true;                      ///< draw the figure
  /// Reuse the runs an interrupted figure finished (a complete result directory in `dir`).
  bool resume = false;
  std::ostream* log = nullptr;  ///< one line per run (nullptr: silent)
};

/// Runs every run of `fig` into `dir` (the figure's staging directory) and writes figure.json; with
/// plots, draws the figure. Returns the summary (for summary.json): the figure, the number of runs,
/// the plot status and, for fig7, the energy table the drawing wrote. Throws tmlab::Error for a bad
/// case or a failing drawing, and tmlab::Interrupted (saying how to resume) for an interrupted run.
nlohmann::json run_paper_figure(const PaperFigure& fig, const PaperRunOptions& options,
                                const std::filesystem::path& dir);

}  // namespace tmlab::tm
