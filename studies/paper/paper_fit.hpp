// `tmlab paper fig2|fig3|table1|table2` (docs/paper-experiments.md, "Section IV-A"): the inverse
// identification of Xu et al. 2011, Section IV-A, redone with error bars.
//
// The paper's reference curves came from Lee and Radok's formula with the pig-liver parameters of
// Samur et al. 2007 (elastic) and the Prony terms of Nava et al. 2008 (relaxation); neither set is
// legible or available here. So the reference curves are generated from the liver-range parameter
// set of the committed parameter file (cases/paper/xu2011_indentation.json): Hertz (elastic, Fig. 2,
// Table I) and Lee-Radok (ramp and hold, Fig. 3, Table II) for a rigid sphere on a half-space at each
// depth, plus Gaussian noise of a stated fraction of the peak force (fixed seed). Each curve is then
// identified twice:
//   closed form   the generating model itself (Hertz / Lee-Radok): checks that the data determine
//                 the parameters (the fit must recover them within its intervals);
//   tensor mass   the FE rig with the fast model (calibration/fit/rig_forward_model.hpp): St VK (the paper's
//                 tensor-mass model, TensorMassStVK / ViscoelasticStVK) and, what the paper does not,
//                 a neo-Hookean base (HyperelasticTL / ViscoelasticHyperelastic), on a half-space
//                 block meshed with a uniform patch under the indenter and geometric grading beyond
//                 (paper_fit_mesh below; the rigs' power-graded block puts one cell across the
//                 contact).
// nu is fixed (force data see only E / (1 - nu^2), errata eq. 23). From the per-depth fits the study
// states the depth at which St VK stops being usable (criteria in the parameter file: the solve
// fails, the residual exceeds a bound, the identified modulus drifts from the shallowest depth's, or
// departs from the neo-Hookean one on the same rig).
#pragma once

#include "calibration/data/measured_data.hpp"
#include "calibration/fit/rig_forward_model.hpp"
#include "calibration/rigs/rig.hpp"
#include "core/mesh/mesh.hpp"
#include "studies/paper/paper_fit_settings.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace tmlab::tm {

/// The reference curve of one depth: Hertz (elastic) or Lee-Radok (viscoelastic: ramp and hold) on a
/// half-space, with the settings' noise (seeded by the seed and the depth's index), as a
/// tmlab-measured/1 data set in memory.
measured::DataSet paper_reference_data(const PaperFitSettings& s, bool viscoelastic, std::size_t depth_index);

/// The noise-free reference forces of paper_reference_data (the same samples).
std::vector<double> paper_reference_force(const PaperFitSettings& s, bool viscoelastic,
                                          const measured::Test& t);

/// The rig mesh of the study: the rig's block, uniform cells of size patch_factor a / patch_cells in
/// a patch of half-width patch_factor a around the indenter (x, y) and below the top face (z), then
/// outer_cells cells growing geometrically to each face (a = sqrt(R d_max)); faces named as
/// rigs::rig_mesh names them.
Mesh paper_fit_mesh(const rigs::RigSpec& spec, double patch_factor, int patch_cells, int outer_cells);

/// The FE-rig options of the study's tensor-mass fits: paper_fit_mesh with the settings' patch,
/// their load steps and contact stiffness.
fit::RigForwardModelOptions paper_fe_rig_options(const PaperFitSettings& s);

/// The SPEC of the study's fits of `law`: with the reference's number of Prony terms when `viscoelastic`,
/// poisson fixed at the reference value.
std::string paper_fit_spec(const PaperFitSettings& s, const std::string& law, bool viscoelastic);

/// The problem of one identification of `data` (kind "closed_form": the Hertz / Lee-Radok surrogate;
/// otherwise the FE rig of paper_fe_rig_options): with relaxation-time bands
/// (fit/relaxation_bands.hpp) when viscoelastic and the settings set them.
fit::Problem paper_fit_problem(const PaperFitSettings& s, const std::string& kind, const std::string& law,
                               bool viscoelastic, const measured::DataSet& data);

/// The generating value of a fit parameter by name (young, poisson, e<j>, tau<j>); NaN for another.
double paper_truth(const PaperFitSettings& s, const std::string& name);

/// Coordinates on [lo, hi]: uniform cells of size w / np within w of `focus` (clipped to the
/// interval), then no cells per side growing geometrically to the ends. tmlab::Error when the patch
/// does not fit.
std::vector<double> patch_graded_coordinates(double lo, double hi, double focus, double w, int np, int no);

struct PaperFitOptions {
  std::string params_file;
  std::string tmlab_root = ".";
  bool plots = true;
  bool resume = false;  ///< reuse the fits an interrupted run finished (fits/*.json in the directory)
  std::ostream* log = nullptr;
};

/// Runs target `target` (fig2 | table1: elastic; fig3 | table2: viscoelastic) into `dir` (the
/// target's staging directory): fits/<kind>_<law>_<depth>.json per fit, paper_fit.json (every fit
/// with its curves, the usable-depth finding), <table>.md and .json and, with plots, <fig>.png
/// (python/tmlab_paper_fit_figure.py). fig2 and table1 (fig3 and table2) are the same fits. Returns the
/// summary. Throws tmlab::Error for an unknown target, tmlab::Interrupted between fits.
nlohmann::json run_paper_fit(const std::string& target, const PaperFitSettings& s, const PaperFitOptions& o,
                             const std::filesystem::path& dir);

/// The St VK usable-depth finding from the tensor-mass fits (the fit JSONs of run_paper_fit): per
/// depth, usable when the fit finished and converged (fit::converged_stop), its residual RMS is at
/// most s.max_rms_percent of the peak, its E drifts at most s.max_drift_percent from the shallowest
/// depth's and differs at most s.max_law_difference_percent from the neo-Hookean E on the same rig.
nlohmann::json usable_depth(const PaperFitSettings& s, const std::vector<nlohmann::json>& fits);

/// True for the targets run_paper_fit handles.
bool is_paper_fit_target(const std::string& target);

}  // namespace tmlab::tm
