// What a fit writes and says (issue 14; docs/identification.md): fit.json (to_json), fit.h5
// (write_fit_h5), the report on standard output, and the forward-model rule of `tmlab fit
// --forward` (make_problem: the closed form, the FE rig, or the closed form when it covers the data
// and the law, else the FE rig). `tmlab fit` and the paper's identification (studies/paper)
// use these; the fitting itself is fitter.hpp.
#pragma once

#include "calibration/data/measured_data.hpp"
#include "calibration/fit/discretisation.hpp"
#include "calibration/fit/fitter.hpp"
#include "calibration/fit/model_spec.hpp"
#include "calibration/fit/rig_forward_model.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace tmlab::fit {

/// One parameter of fit.json: value, unit, fixed, transform, standard error, 95 % interval,
/// identifiable, its bounds and which one it sits on ("lower", "upper" or "": a constrained
/// optimum, not a free one); without `bounds`, null bounds and "". Non-finite numbers are null.
nlohmann::json parameter_json(const ParameterResult& p, const Parameter* bounds);

/// fit.json: the model, the parameters, correlations, cost, residual, AIC/BIC, the global stage,
/// priors, confounded pairs, notes, the profile, the tests with their weights; with `disc` (an
/// FE-rig fit's discretisation check) each parameter's "discretisation" object, the block
/// "discretisation" and its warnings among the notes.
nlohmann::json to_json(const FitResult& r, const Problem& problem, const FitOptions& options,
                       const ModelSpec& spec, const DiscretisationReport* disc = nullptr);

/// When fewer local runs ran than FitOptions::local_runs asked for (one per candidate start, and
/// there were fewer starts, or fewer the model could evaluate): what ran and why; "" otherwise.
std::string local_runs_note(const FitResult& r, const FitOptions& options);

/// fit.h5: per test (/tests/NNN, attribute id) the data, the model's force and the residual; the
/// profile (/profile, attribute parameter); the correlation matrix.
void write_fit_h5(const std::filesystem::path& path, const measured::DataSet& data, const FitResult& r);

/// The parameter table, the cost and its forward model, the profile, the confounded pairs and notes;
/// with `disc` a column of discretisation shifts, the refined rig and a WARNING line per parameter
/// whose shift exceeds its standard error.
void print_fit_report(std::ostream& os, const FitResult& r, const Problem& problem, const FitOptions& options,
                      const DiscretisationReport* disc = nullptr);

/// What the fit is about to do: the data, the SPEC and its forward model; the global stage (`global`,
/// the --global word) on the closed form when the FE rig has one beside it, or on the FE rig itself
/// and why (`which` "fe_rig", `why_no_closed_form` from make_problem).
void print_fit_plan(std::ostream& os, const std::string& data_name, const ModelSpec& spec,
                    const std::string& global, const std::string& which, const Problem& problem,
                    const std::string& why_no_closed_form);

/// The result name of a fit of `data_name` with `spec`: "<data>-<law>[N][-pronyM]".
std::string result_name(const std::string& data_name, const ModelSpec& spec);

/// summary.json's own block: the model, the forward model, residual, AIC/BIC, solves, `plots`.
nlohmann::json summary_json(const FitResult& r, const ModelSpec& spec, const std::string& plots);

/// The plots of a fit (calibration/fit/python/tmlab_fit_plot.py under `tmlab_root`) from fit.json
/// and fit.h5 in `dir`, titled `title`: "ok" or "failed (why)".
std::string write_fit_plots(const std::filesystem::path& dir, const std::filesystem::path& tmlab_root,
                            const std::string& title);

/// The forward model of `tmlab fit --forward WHICH`: "closed_form" (the data's closed-form
/// surrogate), "fe_rig" (the FE rig, with the closed form as the global stage's model when there is
/// one), "auto" (the closed form when it covers the data and the law, else the FE rig). Sets
/// `why_no_closed_form` when the FE rig has no closed form beside it (fe_rig) or replaced it (auto).
/// tmlab::Error for another WHICH or a problem that cannot be built.
Problem make_problem(const measured::DataSet& data, const ModelSpec& spec,
                     const std::vector<std::pair<std::string, double>>& fixes,
                     const std::vector<std::pair<std::string, double>>& weights, const std::string& which,
                     const RigForwardModelOptions& fe, std::string& why_no_closed_form);

}  // namespace tmlab::fit
