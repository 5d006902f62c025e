// ViscoelasticHyperelastic: the objective Prony-series scheme of ViscoelasticStVK (history "pk2",
// relaxation "full"; viscoelastic_model.hpp, docs/theory/viscoelasticity.md) on top of ANY
// hyperelastic law of the long-term response (tensormass/materials/law.hpp), through the F-based
// element HyperelasticTL:
//
//   S_e(E) = dW/dE of the long-term law, the driver of the history (material frame: objective)
//   h_j^{n+1} = a_j h_j^n + c_j (S_e^{n+1} - S_e^n)               (the recursion of ViscoelasticStVK)
//   trial step dt: S_total(u) = (1 + g) S_e(E(u)) + S_hist,  g = sum_j alpha_j c_j,
//                  S_hist = sum_j alpha_j (a_j h_j^c - c_j S_e^c)      (constant in the step)
//   force f_p = V F S_total a_p, tangent V [ (a_p . S_total a_q) I + (1 + g) B_p^T D B_q ]
//   trial_potential(u) = sum_t V [ (1 + g) W(E) + S_hist : E ]  (its gradient is the force)
//
// This is a separate class, not a change to ViscoelasticStVK: that model's nodal-force history and
// deviatoric relaxation are defined through St VK's constant elasticity (S_dev = 2 mu dev E, the
// nodal-force branches' compliance K_0^+), which a general law does not have, and its pk2 path
// keeps the paper's tensor-mass long-term spring. Here: history pk2 and relaxation full only
// (anything else is refused with a tmlab::Error). For St VK this model equals ViscoelasticStVK
// (pk2, full) to round-off (tests/test_viscoelastic_law.cpp).
//
// Energies. energy(u) = long-term W_e(u) + branch energies Psi_j = V alpha_j/2 h_j : C_0^{-1} : h_j
// with C_0 the law's SMALL-STRAIN elasticity (Law::small_strain()): exact for St VK (whose
// elasticity is C_0 at every strain) and, for the other laws, the quadratic branch energy of the
// linearised law (quasi-linear viscoelasticity defines the history by the stress, not by a branch
// potential; the bookkeeping is then a small-strain estimate). Dissipation rate
// D = sum_j 2 Psi_j / tau_j >= 0, step dissipation by the trapezoidal rule, as ViscoelasticStVK.
#pragma once

#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/materials/law.hpp"
#include "tensormass/viscoelastic/prony_series.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include <vector>

namespace tmlab::tm {

class ViscoelasticHyperelastic : public ElasticModel {
 public:
  /// `long_term` is the law of the long-term response. Throws tmlab::Error unless options.history
  /// is Pk2 and options.relaxation is Full (naming the refused option), and on bad tets.
  ViscoelasticHyperelastic(const Mesh& mesh, Law long_term, PronySeries prony,
                           ViscoelasticOptions options = {});

  Index num_nodes() const override { return elastic_.num_nodes(); }
  Index num_tets() const { return elastic_.num_tets(); }
  const HyperelasticTL& elastic() const { return elastic_; }  ///< the long-term spring
  const PronySeries& prony() const { return prony_; }
  const ViscoelasticOptions& options() const { return options_; }

  /// Stored free energy of the trial state at u (long-term W_e(u) + branch energies), joules.
  double energy(const VecX& u) const override;
  /// Total (trial) internal force, the gradient of trial_potential.
  void internal_force(const VecX& u, VecX& f) const override;
  void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const override;
  void tangent(const VecX& u, SpMat& K) const override;

  bool has_history() const override { return true; }
  void begin_step(double dt) override;
  void commit_step(const VecX& u) override;
  /// hist, driver, then the committed energies, rate and dissipations (5 values).
  std::vector<double> committed_state() const override;
  void restore_committed_state(const std::vector<double>& state) override;

  /// W_trial(u) = sum_t V [ (1 + g) W(E) + S_hist : E ].
  double trial_potential(const VecX& u) const;
  double trial_dt() const { return dt_; }
  double trial_gain() const { return gain_; }  ///< g = sum_j alpha_j c_j

  /// W_e(u_c) of the last commit, computed on the first call after it (as ViscoelasticStVK).
  double committed_elastic_energy() const;
  double committed_branch_energy() const { return committed_branch_; }
  double step_dissipation() const { return step_dissipation_; }
  double total_dissipation() const { return total_dissipation_; }
  double committed_dissipation_rate() const { return committed_rate_; }
  /// Committed h_j^c per tet [t][j][6] (Voigt xx, yy, zz, xy, xz, yz) and S_e^c per tet [t][6].
  const std::vector<double>& committed_history() const { return hist_; }
  const std::vector<double>& committed_driver() const { return driver_; }

 private:
  /// S_total = (1 + g) S_e + S_hist of tet t.
  Mat3 total_stress(std::size_t t, const Mat3& S_e) const;
  double branch_form(std::size_t t, const double* h, double* rate) const;
  void update_trial();

  HyperelasticTL elastic_;
  PronySeries prony_;
  ViscoelasticOptions options_;
  LameConstants c0_;  ///< small-strain elasticity of the law (branch energies)
  bool elastic_only_ = false;

  std::vector<double> hist_, driver_;
  mutable double committed_elastic_ = 0.0;  ///< valid unless spring_stale_
  double committed_branch_ = 0.0, committed_rate_ = 0.0;
  double step_dissipation_ = 0.0, total_dissipation_ = 0.0;
  VecX committed_u_;                   ///< u of the last commit while its spring energy is pending
  mutable bool spring_stale_ = false;  ///< committed_elastic_ is still to be computed

  double dt_ = 0.0, gain_ = 0.0;
  std::vector<RecursionFactors> factors_;
  std::vector<double> s_hist_;  ///< per tet 6 (Voigt)
};

}  // namespace tmlab::tm
