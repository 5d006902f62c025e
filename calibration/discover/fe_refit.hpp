// The FE-rig refit of `tmlab discover --forward fe_rig` (issue 15, "the test simulated by its rig";
// docs/discover.md section 1). The selection loop runs on the closed-form forward model
// (DiscoverModel: hundreds of fits per data set); this step then takes the baseline and the final
// model to the FE rig of `tmlab fit --forward fe_rig` (calibration/fit/rig_forward_model.hpp: the tensor-mass
// St VK model, or the F-based element for another law, with the Prony terms, on the rig the data's
// JSON names), evaluates it at the closed-form optimum (how far the closed form is from the rig) and
// refits it from there with Levenberg-Marquardt (local only: the closed-form optimum is the start).
//
// Indentation: the refit uses the loading and the hold of each test (up to the first unloading
// sample): the rig's contact solver does not follow a sphere that leaves a relaxing sample, and
// Lee-Radok, which the closed form is, holds only while the contact grows or holds.
//
// The FE rig models the law and the Prony terms. A model with another effect (an experiment effect,
// friction, a layer, a poroelastic term) is not refitted there; the report says which and why.
#pragma once

#include "calibration/data/measured_data.hpp"
#include "calibration/discover/discover.hpp"
#include "calibration/fit/fitter.hpp"
#include "calibration/rigs/rig_from_data.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tmlab::discover {

struct FeRefitOptions {
  rigs::RigFromDataMesh mesh{8, 4, 2.0};  ///< coarser than tmlab fit's default: two refits per data set
  int substeps = 1;                       ///< static load steps per (decimated) sampling interval
  int max_iterations = 8;                 ///< Levenberg-Marquardt iterations of each refit
  std::size_t max_samples = 300;          ///< the loop's data decimated further for the rig
};

struct FeRefit {
  std::string which;  ///< "baseline" or "final"
  std::string model;  ///< the structure's label
  bool done = false;
  std::string why_not;                          ///< when not done
  double closed_form_rms = 0.0;                 ///< the closed form at its optimum on the same samples, N
  double fe_rms_at_closed_form = 0.0;           ///< the FE rig at the closed-form optimum, N
  fit::FitResult fit;                           ///< the FE-rig refit (fit.rms: its RMS, N)
  std::vector<std::vector<double>> prediction;  ///< the refitted FE rig force, per test (indentation:
                                                ///< loading and hold only, the tests' first samples)
  std::size_t samples = 0;                      ///< samples the FE rig was fitted to
  double seconds = 0.0;
};

/// The data the loop worked on, decimated further to about `max_samples` samples, as a data set
/// (the FE rig is driven by it; `kept` gets the indices into p.series of the samples kept); with
/// `loading_only` each test ends before its first unloading sample (indentation: the contact
/// solver of the rig and Lee-Radok both hold while the contact grows or holds).
measured::DataSet decimated_data(const measured::DataSet& data, const Prepared& p, bool loading_only,
                                 std::size_t max_samples, std::vector<std::vector<std::size_t>>* kept);

/// The discretisation gate of `tmlab discover --forward fe_rig` (DiscretisationGate, issue 28): the
/// baseline's FE-rig force at its (closed-form) optimum on the rig of `fo` and on that rig refined
/// `refine_ratio` x in h (fit::refined_rig), on the samples the refit uses (decimated_data), and the
/// RMS of their difference. Not applied (with the reason in `note`) when the rig cannot be built or
/// solved there.
DiscretisationGate baseline_discretisation(const measured::DataSet& data, const Prepared& p,
                                           const Fitted& baseline, const FeRefitOptions& fo,
                                           double refine_ratio = 2.0, double factor = 2.0);

/// FE-rig refits of the baseline and (when it differs) the final model of `r`.
std::vector<FeRefit> fe_rig_refit(const measured::DataSet& data, const Report& r, const Options& o,
                                  const FeRefitOptions& fo);

nlohmann::json to_json(const std::vector<FeRefit>& v, double peak_force, const FeRefitOptions& fo);

}  // namespace tmlab::discover
