// The liver experiments of Xu et al. 2011 (Figs. 5-7) as sets of case documents built from one
// committed parameter file (cases/paper/xu2011_liver.json): creep under constant nodal and patch
// forces (fig5), relaxation after a ramp-and-hold indentation of three nodes (fig6), and
// load-unload hysteresis at several rates (fig7). `tmlab paper FIG` runs them and draws the figure.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tmlab::tm {

/// One run of a figure: a case document and which of its series the figure draws.
struct PaperRun {
  std::string id;                     ///< result sub-directory, e.g. "seed_node_0.1N"
  std::string label;                  ///< legend entry
  std::string scheme;                 ///< viscoelastic scheme shorthand (seed, objective)
  nlohmann::json case_doc;            ///< a complete case-file document
  std::string x, y;                   ///< series names in timeseries.h5
  double x_sign = 1.0, y_sign = 1.0;  ///< plotted as sign * series (indentation positive)
};

struct PaperFigure {
  std::string name;  ///< fig5 | fig6 | fig7
  std::string title, xlabel, ylabel;
  std::vector<PaperRun> runs;
};

/// Builds the runs of figure `name` from the parameter document (`where` names it in errors;
/// unknown keys are rejected). Throws tmlab::Error for an unknown figure.
PaperFigure paper_figure(const std::string& name, const nlohmann::json& params, const std::string& where);

}  // namespace tmlab::tm
