// The discovery loop of `tmlab discover` (issue 15; docs/discover.md):
//   0. the data checked against the sign convention (measured::check_force_sign);
//   1. baseline: the paper's model (St VK, two Prony terms) on the data's rig, fitted (tmlab::fit);
//   2. the residual studied (diagnostics.hpp): noise, or structure, and where;
//   3. every applicable effect of the library (effects.hpp) added in turn and fitted, starting from
//      the current optimum;
//   4. the candidate with the lowest BIC is accepted only if BIC drops by more than 10 (Kass and
//      Raftery's "very strong") AND the held-out RMS (tests left out, or alternate time blocks of a
//      single test, each fold fitted without them and predicting them) drops below 0.98 x the current
//      model's; the next two by BIC are tried when it fails the held-out check; before either
//      check, the current model is re-fitted from the candidate's optimum (refit_from), so that a
//      gain the current model reaches itself from there (the optimizer's, not the effect's) is not
//      credited to the effect;
//   5. after each acceptance, the backward step (backward_step): each earlier effect is removed in
//      turn and removed for good when it would not be accepted now (BIC or held-out check);
//   6. repeat until the residual is noise, no candidate passes, or the round limit;
//   7. whatever structure remains is reported with its signature (describe_signature), not forced
//      onto an effect.
#pragma once

#include "calibration/data/measured_data.hpp"
#include "calibration/discover/diagnostics.hpp"
#include "calibration/discover/effects.hpp"
#include "calibration/fit/fitter.hpp"

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace tmlab::discover {

/// One fit of the loop as `tmlab discover --resume` replays it: its result, or the error it ended
/// with (a candidate that cannot be fitted, a held-out fold fitted from the full-data optimum).
struct FitOutcome {
  fit::FitResult result;
  bool failed = false;
  std::string error;  ///< the message, when failed
};

/// The resume hook of the loop (the engine does no file I/O; the CLI owns the checkpoint). The loop
/// is deterministic, so its fits come in the same order on every run: the first restored.size()
/// are taken from here instead of being fitted (a fit interrupted half-way is not here and runs
/// again from its start), and each fit that runs is handed to `finished`.
struct FitLog {
  std::vector<FitOutcome> restored;
  std::size_t next = 0;  ///< the index of the next fit of the loop
  std::function<void(const FitOutcome&)> finished;
};

struct Fitted;

/// The discretisation gate of `tmlab discover --forward fe_rig` (issue 28; docs/discover.md): the
/// change of the baseline's FE-rig force between the rig and the rig refined 2x in h, at the
/// baseline's optimum, as an RMS over the samples the rig sees (fe_refit.hpp,
/// baseline_discretisation). A candidate effect is accepted only when its improvement of the
/// residual, sqrt(RMS_current^2 - RMS_candidate^2) (the RMS of the force change that explains part
/// of the residual; exact for nested least-squares fits), exceeds `factor` x that change: an effect
/// whose improvement the rig's own discretisation error could make stands in for it.
struct DiscretisationGate {
  bool applied = false;
  double change_rms = kNaN;  ///< N
  double factor = 2.0;
  double refine_ratio = 2.0;
  std::string rig, refined_rig;  ///< "cells,layers (N tets)"
  std::size_t samples = 0;       ///< samples the rig saw
  std::string note;              ///< why it is not applied (empty when it is)
};

/// sqrt(max(0, rms_current^2 - rms_candidate^2)), N.
double rms_improvement(double rms_current, double rms_candidate);
/// True when the gate is applied and the candidate's improvement over the current model is not more
/// than gate.factor x gate.change_rms.
bool stands_in_for_discretisation(const DiscretisationGate& gate, double rms_current, double rms_candidate);
/// The reason a step gets when the gate refuses it ("stands in for discretisation error: ...").
std::string discretisation_reason(const DiscretisationGate& gate, double rms_current, double rms_candidate);

struct Options {
  std::size_t max_samples = 1500;  ///< the data are decimated to about this many samples
  double poisson = 0.49;
  bool fix_poisson = true;
  MaterialLaw baseline_law = MaterialLaw::StVK;
  int baseline_prony = 2;
  int max_rounds = 4;
  double bic_threshold = 10.0;   ///< accept only when BIC falls by more than this
  double held_out_ratio = 0.98;  ///< ... and the held-out RMS falls below this times the current one
  bool test_control = true;      ///< ... and the BIC beats the test-consistency control (TestScaleControl)
  int starts = 8;                ///< multi-start candidates per candidate fit (3x for the baseline)
  int threads = 2;
  unsigned long seed = 1;
  Thresholds thresholds;
  std::vector<std::string> effects;  ///< restrict the library to these (empty: all)
  std::function<void(const std::string&)> progress;
  FitLog* fit_log = nullptr;  ///< checkpoints (tmlab discover --resume); null: none
  /// --forward fe_rig: the discretisation gate of the baseline (DiscretisationGate), computed once
  /// after the baseline's fit; empty: no gate (the closed-form loop alone).
  std::function<DiscretisationGate(const Prepared&, const Fitted&)> discretisation;
};

struct Fitted {
  Structure structure;
  std::vector<fit::Parameter> parameters;
  fit::FitResult fit;
  std::vector<double> x;                        ///< the optimum, physical
  std::vector<std::vector<double>> prediction;  ///< per test
  ResidualStudy study;
  double held_out_rms = kNaN;
  std::vector<double> held_out_by_test;  ///< each test's RMS when it was held out (with held_out_rms)
  double max_abs = 0.0;
};

struct Step {
  int round = 0;
  bool removal = false;  ///< a backward step: the model without `effect` (else: with it)
  std::string effect, model;
  std::size_t free_parameters = 0;
  double rms = kNaN, bic = kNaN, delta_bic = kNaN;
  double held_out_rms = kNaN, current_held_out_rms = kNaN;
  std::vector<double> held_out_by_test, current_held_out_by_test;  ///< per test, when held out
  double current_refit_rms = kNaN;  ///< the current model re-fitted from this candidate's optimum
  double improvement_rms = kNaN;    ///< rms_improvement over the current model (the gate's measure)
  bool accepted = false;            ///< added (or, for a removal, removed)
  std::string reason;
};

/// The test-consistency control: the current model's forces with one free scale factor per test
/// (each the least-squares factor of its test, the model's parameters held at their optimum). Not
/// a library effect: a factor per test is no physics shared by the tests, it is what sample history
/// (preconditioning, damage), a different sample or a recalibrated load cell leave in the data. A
/// candidate is accepted only when it explains more than this control (lower BIC); when the control
/// explains more, the structure is a test-to-test difference that no shared effect explains.
struct TestScaleControl {
  bool applicable = false;    ///< two or more tests
  std::vector<double> scale;  ///< per test
  double rms = kNaN, bic = kNaN;
  std::size_t free_parameters = 0;  ///< the current model's plus one per test (conservative)
  bool decided = false;             ///< it explained more than the best candidate that passed both checks
  int round = 0;                    ///< the round it was last computed in (0: the baseline)
  /// (RMS^2 - control RMS^2) / (RMS^2 - noise^2) of the model it controls: the share of the
  /// residual variance above the noise level that a factor per test explains (NaN: no excess)
  double explained_share = kNaN;
};

/// The control for `cur` on `p` (see TestScaleControl).
TestScaleControl test_scale_control(const Prepared& p, const Fitted& cur);

struct Report {
  Prepared data;
  Options options;
  Fitted baseline, final;
  std::vector<Step> steps;
  std::vector<std::string> selected;       ///< accepted effects, in the order of the steps
  std::vector<std::string> removed;        ///< effects the backward step took out again, in order
  std::vector<std::string> final_effects;  ///< what the final model has beyond the baseline
  std::vector<std::pair<std::string, std::string>> not_applicable;  ///< effect, why (first round)
  TestScaleControl control;                                         ///< as computed in the last round
  bool unexplained = false;
  std::string signature;
  std::string stop_reason;
  std::string forward_model, exactness;
  std::string held_out_scheme;
  std::vector<std::string> notes;     ///< what the data cannot separate, and similar caveats
  DiscretisationGate discretisation;  ///< --forward fe_rig (not applied otherwise)
  double seconds = 0.0;
};

/// Training masks of the held-out folds: up to 3 folds of whole tests when there are 2 or more
/// tests, else the even and the odd of 8 time blocks of the one test.
std::vector<std::vector<char>> held_out_folds(const Prepared& p, std::string* scheme = nullptr);

/// fit::fit through o.fit_log (FitLog): the next restored outcome when there is one (its error
/// thrown again as tmlab::Error), else the fit, whose outcome (result or error) is handed to the
/// log. A stop request (tmlab::Interrupted) passes through unrecorded: that fit runs again.
fit::FitResult fit_logged(const fit::Problem& pr, const fit::FitOptions& fo, const Options& o);

/// Fits `s` with `params` to `p` (under `mask`, empty: all) and studies the residual.
Fitted fit_structure(const Prepared& p, const Structure& s, std::vector<fit::Parameter> params,
                     const Options& o, int starts);

/// The pooled held-out RMS of `f`'s structure: each fold refitted from f's optimum without its
/// held-out samples, which it then predicts. `by_test` (when given) receives each test's RMS over
/// its held-out samples (NaN for a test never held out).
double held_out_rms(const Prepared& p, const Fitted& f, const Options& o,
                    std::vector<double>* by_test = nullptr);

/// The current model `cur`'s structure re-fitted from candidate `c`'s optimum (the values they
/// share by name): what the current structure itself reaches from there. A candidate whose gain
/// this refit matches gained by a better optimum of the shared parameters, not by its effect.
Fitted refit_from(const Prepared& p, const Fitted& cur, const Fitted& c, const Options& o);

/// `s` without `effect` (a law effect reverts to `baseline`'s law, extra_prony_term drops the last
/// term); tmlab::Error when `s` does not have it beyond `baseline`.
Structure without_effect(const Structure& s, const std::string& effect, const Structure& baseline);

/// The backward step after `just_added` was accepted: every other effect of `cur` beyond `baseline`
/// is removed in turn (the reduced model re-fitted from cur's optimum) and removed for good when it
/// would not be accepted if it were added to the reduced model now: its BIC drop is not more than
/// o.bic_threshold, or the held-out RMS with it is not below o.held_out_ratio x that without it.
/// Appends a removal Step per effect tried (round `round`) and returns the effects removed.
std::vector<std::string> backward_step(const Prepared& p, const Structure& baseline, Fitted& cur,
                                       const std::string& just_added, int round, const Options& o,
                                       std::vector<Step>& steps);

/// "all samples kept" or "every k-th sample kept" (the progress line and the report).
std::string stride_text(std::size_t stride);

/// Caveats the data's protocol imposes on what the loop can conclude (e.g. one rate, no hold).
std::vector<std::string> protocol_notes(const Prepared& p);

/// Runs the loop on `data`.
Report run(const measured::DataSet& data, const Options& o);

/// report.json (docs/discover.md lists every key).
nlohmann::json to_json(const Report& r);

}  // namespace tmlab::discover
