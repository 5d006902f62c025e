// The discretisation shift of an FE-rig fit (issue 28; docs/identification.md "Discretisation
// shift"): how far the fitted parameters would move if the rig's mesh were refined, from one forward
// solve on a refined rig at the optimum theta* and the fit's own linearisation there.
//
// The refined rig's forces F_fine(theta*) differ from the fit's F_coarse(theta*) by
// delta = F_fine - F_coarse. Re-fitting on the refined rig, linearised at theta* (F_fine(theta) ~
// F_fine(theta*) + J dtheta, J the fit's Jacobian of the weighted force errors, J^T r = 0 at the
// optimum) gives
//     dtheta = -(J^T J)^{-1} J^T W delta,
// W the fit's weights (per test), (J^T J)^{-1} the matrix of the fit's covariance (C = s^2 (J^T
// J)^{-1}, its floor on singular directions, its prior rows), in the fit's internal (transformed)
// coordinates; the physical shift is dx/dt dtheta (the delta method of the standard errors). The
// sign is the move: value + shift is the refined rig's estimate. |shift| is issue 28's
// (J^T J)^{-1} J^T (F_fine - F_coarse); the minus sign only says which way.
#pragma once

#include "calibration/data/measured_data.hpp"
#include "calibration/fit/fitter.hpp"
#include "calibration/fit/rig_forward_model.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace tmlab::fit {

/// The refinement ratio in h of the check when none is given.
inline constexpr double kDefaultRefineRatio = 2.0;

/// The refined rig of the check: `coarse` with its mesh resolution (rigs::RigFromDataMesh cells and
/// layers, the RigSpec fields rig_from_data fills) multiplied by `ratio` and rounded, the grading and
/// everything else kept. The one place that makes the refined rig (a rig-level refinement rule
/// replaces this body). tmlab::Error when ratio <= 1 or the rounded resolution is not finer.
RigForwardModelOptions refined_rig(const RigForwardModelOptions& coarse, double ratio);

/// The internal shift per free parameter (Linearisation order): dt = -(J^T J)^{-1} J^T W (f_fine -
/// f_coarse), W the per-test weights of `data`. tmlab::Error when the sizes disagree or the
/// linearisation is empty.
std::vector<double> linearised_shift(const Linearisation& lin, const Observations& data,
                                     const std::vector<double>& f_coarse, const std::vector<double>& f_fine);

/// One parameter's discretisation shift.
struct ParameterShift {
  std::string name, unit;
  bool fixed = false;
  bool known = false;  ///< false: fixed or not identifiable (no shift)
  double value = 0.0, standard_error = 0.0;
  double shift = 0.0;           ///< physical; value + shift is the refined rig's estimate
  double shift_relative = 0.0;  ///< shift / |value|
  double shift_per_se = 0.0;    ///< shift / standard error (0 when the error is infinite)
  /// The statistical 95 % interval joined with the same interval moved by the shift:
  /// [lower95 + min(0, shift), upper95 + max(0, shift)], clipped to the bounds.
  double lower = 0.0, upper = 0.0;
  bool warning = false;  ///< |shift| > standard error
};

struct DiscretisationReport {
  double refine_ratio = kDefaultRefineRatio;
  RigForwardModelSize coarse, fine;
  /// The change of the predicted force at the optimum, F_fine - F_coarse (unweighted), N.
  double change_rms = 0.0, change_max = 0.0;
  double peak_force = 0.0;
  std::vector<ParameterShift> parameters;  ///< every parameter, FitResult order
  std::vector<std::string> warnings;       ///< one per parameter whose |shift| exceeds its SE
  double seconds = 0.0;                    ///< the refined solve
  std::vector<double> fine_force;          ///< F_fine(theta*), Observations order
};

/// The check of fit `r` of `problem` (its model the coarse FE rig): one solve of `fine` (the refined
/// rig's model, refined_rig) at the optimum, the linearised shifts, the warnings. `progress` (may be
/// empty) gets a line before the refined solve and one after. tmlab::Error when the fit has no
/// linearisation, the model is not an FE rig, or the refined rig cannot be solved at the optimum.
DiscretisationReport discretisation_report(const FitResult& r, const Problem& problem,
                                           const ForwardModel& fine, double refine_ratio,
                                           const std::function<void(const std::string&)>& progress = {});

/// The fit.json block "discretisation": the formula, the meshes, the force change, the warnings.
nlohmann::json discretisation_json(const DiscretisationReport& d);
/// The "discretisation" object of one parameter of fit.json (shift, relative, per SE, the
/// refined rig's mesh and the option that controls it, the joined interval); null numbers when
/// the shift is not known.
nlohmann::json parameter_discretisation_json(const ParameterShift& s, const DiscretisationReport& d);

/// The option text that controls the check: "--mesh C,L --refine-ratio R (refined rig C',L')".
std::string discretisation_option_text(const DiscretisationReport& d);

}  // namespace tmlab::fit
