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
#include "tensormass/viscoelastic/viscoelastic_base.hpp"

#include <vector>

namespace tmlab::tm {

class ViscoelasticHyperelastic : public ViscoelasticBase {
 public:
  /// `long_term` is the law of the long-term response. Throws tmlab::Error unless options.history
  /// is Pk2 and options.relaxation is Full (naming the refused option), and on bad tets.
  ViscoelasticHyperelastic(const Mesh& mesh, Law long_term, PronySeries prony,
                           ViscoelasticOptions options = {});

  Index num_nodes() const override { return elastic_.num_nodes(); }
  Index num_tets() const { return elastic_.num_tets(); }
  const HyperelasticTL& elastic() const { return elastic_; }  ///< the long-term spring
  /// Total (trial) internal force, the gradient of trial_potential.
  void internal_force(const VecX& u, VecX& f) const override;
  void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const override;
  void tangent(const VecX& u, SpMat& K) const override;

  /// W_trial(u) = sum_t V [ (1 + g) W(E) + S_hist : E ].
  double trial_potential(const VecX& u) const;

 private:
  /// S_total = (1 + g) S_e + S_hist of tet t.
  Mat3 total_stress(std::size_t t, const Mat3& S_e) const;
  double long_term_energy(const VecX& u) const override { return elastic_.energy(u); }
  double branch_form(std::size_t t, const double* h, double* rate) const override;
  /// Recomputes S_hist from the committed state (at every begin_step and commit).
  void trial_changed() override;
  /// S_e of tet t at u (Voigt).
  void driver(std::size_t t, const VecX& u, double* x) const override;

  HyperelasticTL elastic_;
  LameConstants c0_;            ///< small-strain elasticity of the law (branch energies)
  std::vector<double> s_hist_;  ///< per tet 6 (Voigt)
};

}  // namespace tmlab::tm
