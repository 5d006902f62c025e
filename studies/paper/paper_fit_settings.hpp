// The settings of the Section IV-A identification (`tmlab paper fig2|fig3|table1|table2`,
// docs/paper-experiments.md), read strictly from the parameter file
// (cases/paper/xu2011_indentation.json or --params FILE). Kept apart from the study (paper_fit.hpp)
// so that the reader builds on core alone (fuzz/fuzz_paper_params.cpp).
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tmlab::tm {

/// The settings of the Section IV-A study, read from the parameter file (strict keys).
struct PaperFitSettings {
  // Reference curves (our documented liver-range choice, not the paper's numbers).
  double indenter_radius = 0.01;  ///< m
  std::vector<double> depths;     ///< m
  double young = 4000.0;          ///< long-term (relaxed) Young's modulus E_inf, Pa
  double poisson = 0.45;
  std::vector<double> prony_moduli,
      prony_taus;                          ///< E_j (long-term convention: E = E_inf + sum E_j e^-t/tau_j)
  double ramp = 1.0, hold = 5.0;           ///< s
  int ramp_samples = 5, hold_samples = 6;  ///< samples after t = 0 on the ramp / in the hold
  double noise_percent = 0.5;              ///< Gaussian noise, % of each curve's peak force
  unsigned long seed = 2011;
  // The FE rig's mesh (paper_fit_mesh) and load steps.
  double patch_factor = 1.5;  ///< patch half-width / the deepest contact radius sqrt(R d)
  int patch_cells = 3, outer_cells = 3, substeps = 1;
  /// > 0: contact stiffness from the nodes under the indenter (fit::RigForwardModelOptions); 0: solver
  /// default.
  double contact_stiffness_factor = 0.0;
  int newton_max_iterations = 40;  ///< before a load step is cut back (fit::RigForwardModelOptions)
  // Identification.
  std::vector<std::string> laws = {"stvk", "neo_hookean"};
  int starts = 12, local_runs = 1, max_iterations = 20, threads = 2;
  /// The relaxation fits (fig3, table2: five free parameters; identification.relaxation in the
  /// parameter file). The elastic fits (one free parameter) use the engine's defaults.
  struct Relaxation {
    /// Relaxation-time bands (fit/relaxation_bands.hpp): tau >= time_floor x the shortest sampling
    /// interval, tau <= time_ceiling x the test's duration, one ordered band per term. 0: no bands
    /// (tau > 0 only, the terms unordered).
    double time_floor = 0.0, time_ceiling = 0.0;
    /// the FE rig's relative finite-difference step (fit::RigForwardModelOptions)
    double jacobian_step = 1e-6;
    double xtol = 1e-9;      ///< Levenberg-Marquardt's step test (fit::FitOptions::xtol)
    int max_iterations = 0;  ///< Levenberg-Marquardt iterations; 0: identification.max_iterations
  } relaxation;
  // When St VK counts as usable at a depth (all must hold).
  double max_rms_percent = 3.0;              ///< residual RMS, % of peak
  double max_drift_percent = 10.0;           ///< |E(d) / E(shallowest) - 1|, same law
  double max_law_difference_percent = 10.0;  ///< |E_stvk / E_neo_hookean - 1|, same depth

  /// The viscoelastic reference modulus E(t) has Prony terms (fig3, table2 need them).
  bool viscoelastic() const { return !prony_moduli.empty(); }
};

/// Reads the settings from the parameter document; with `quick`, its "quick" block (a JSON merge
/// patch of the document) is applied first. tmlab::Error naming `where` and the key for bad input.
PaperFitSettings paper_fit_settings(const nlohmann::json& params, const std::string& where, bool quick);

}  // namespace tmlab::tm
