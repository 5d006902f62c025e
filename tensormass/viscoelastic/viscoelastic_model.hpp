// ViscoelasticStVK: the seed paper's quasi-linear viscoelastic tensor-mass model (Prony series,
// seed eqs. 9-21 in the corrected form of docs/theory/seed-errata.md), wrapping the elastic St
// Venant-Kirchhoff tensor-mass model of the LONG-TERM modulus E_inf, with committed and trial history.
// Theory, schemes and measured consequences: docs/theory/viscoelasticity.md.
//
// Hereditary integral (errata eq. 11): X(t) = integral_0^t r(t-s) dX_e/ds ds with r the normalised
// relaxation function (prony_series.hpp) and X_e the long-term elastic response, split into
//   X(t) = X_e(t) + sum_j alpha_j h_j(t),  h_j(t) = integral_0^t exp(-(t-s)/tau_j) dX_e/ds ds   (eqs. 13-21)
// and advanced over a step dt by the recursion
//   h_j^{n+1} = a_j h_j^n + c_j (X_e^{n+1} - X_e^n)                                    (eq. 20 family)
// with (a_j, c_j) = recursion_factors(Integration, dt, tau_j) of core/constitutive/prony.hpp (midpoint,
// exact_linear, backward_euler: the one copy the deal.II reference uses too).
//
// What X is (History):
//   nodal_force: X_e = the 12 nodal elastic forces f_e of each tet in GLOBAL axes
//                (TensorMassStVK::tet_force), the seed form; not objective (errata "Flaws" 1).
//   pk2:         X_e = the second Piola-Kirchhoff stress S_e = C : E of each tet (material frame),
//                force f_p = V F S_total a_p; objective.
// and (Relaxation, pk2 only) whether the full S_e = lambda tr(E) I + 2 mu E drives the history
// (E(t) relaxes at fixed nu: bulk and shear relax together, volume creeps), or only its deviatoric
// part S_dev = 2 mu (E - tr(E)/3 I) (the bulk stress K tr(E) I, K = lambda + 2 mu/3, never relaxes).
//
// Trial state. begin_step(dt) fixes a_j, c_j and g = sum_j alpha_j c_j; for u in that step
//   X_total(u) = X_e(u) + sum_j alpha_j [a_j h_j^c + c_j (X_e(u) - X_e^c)]
//              = (1 + g) X_e(u) + X_hist,   X_hist = sum_j alpha_j (a_j h_j^c - c_j X_e^c)   (constant)
// (deviatoric: S_e(u) + g S_dev(u) + S_hist). commit_step(u) stores h_j^c <- h_j(u), X_e^c <- X_e(u)
// and then resets the trial step to dt = 0, so internal_force(u_committed) is the committed total
// force (reactions) until the next begin_step. Initial committed state: h = 0, X_e^c = 0.
//
// Energies (see docs/theory/viscoelasticity.md section 5):
//   trial_potential(u): W_trial(u) whose gradient is internal_force(u) and Hessian tangent(u):
//       nodal_force: (1 + g) W_e(u) + f_hist . u;  pk2: sum_t V [ (1+g) W(E) + S_hist : E ]
//       (deviatoric: sum_t V [ W(E) + g mu |dev E|^2 + S_hist : E ]).
//   energy(u): the STORED free energy of the trial state at u: the long-term spring W_e(u) plus the
//       Maxwell-branch energies Psi_j of the trial histories h_j(u) (NOT the potential of the force).
//   Branch energy (per tet, pk2): Psi_j = V alpha_j/2 h_j : C^{-1} : h_j, C the St VK elasticity of
//       E_inf (deviatoric: h_j : h_j / (2 mu)); dissipation rate D = sum_j 2 Psi_j / tau_j >= 0.
//       nodal_force: the same with K_0^+ (pseudo-inverse of the tet's 12x12 rest stiffness, rigid
//       modes removed) in place of V C^{-1}.
//   At each commit: step dissipation = dt/2 (D^n + D^{n+1}) (trapezoidal quadrature, >= 0).
//
// With all Prony weights zero every call forwards to the elastic model (bit-for-bit identical).
#pragma once

#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/kernels/fast_force.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tet_geometry.hpp"
#include "tensormass/materials/stvk_material.hpp"
#include "tensormass/viscoelastic/viscoelastic_base.hpp"

#include <memory>
#include <string>
#include <vector>

namespace tmlab::tm {

class ViscoelasticStVK : public ViscoelasticBase {
 public:
  /// `long_term` is the St VK material of the long-term modulus E_inf (use
  /// PronySeries::long_term_modulus to convert an instantaneous E_0). Throws tmlab::Error for
  /// deviatoric relaxation with nodal_force history, and on bad tets.
  ViscoelasticStVK(const Mesh& mesh, const StVenantKirchhoff& long_term, PronySeries prony,
                   ViscoelasticOptions options = {});

  Index num_nodes() const override { return elastic_.num_nodes(); }
  Index num_tets() const { return elastic_.num_tets(); }
  const TensorMassStVK& elastic() const { return elastic_; }  ///< the long-term spring
  /// Total (trial) internal force X_total(u) = d trial_potential / du.
  void internal_force(const VecX& u, VecX& f) const override;
  void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const override;
  void tangent(const VecX& u, SpMat& K) const override;

  /// internal_force(u, f) then commit_step(u) in one pass over the tets (the per-tet strains or
  /// elastic forces serve both); bit-identical to the two calls.
  void force_and_commit(const VecX& u, VecX& f) override;

  /// W_trial(u): the potential of the trial force (its gradient is internal_force, its Hessian tangent).
  double trial_potential(const VecX& u) const;

 private:
  bool pk2() const { return options().history == ViscoelasticOptions::History::Pk2; }
  bool deviatoric() const { return options().relaxation == ViscoelasticOptions::Relaxation::Deviatoric; }
  /// X_e of tet t at u (history_width() values): nodal forces, S_e or S_dev (Voigt).
  void driver(std::size_t t, const VecX& u, double* x) const override;
  /// pk2: X_e from the Green strain E of a tet (S_e or S_dev, Voigt).
  void driver_from_strain(const Mat3& E, double* x) const;
  /// After a commit the trial is dt = 0; its constant parts are recomputed on first use (an
  /// explicit step calls begin_step(dt) next, which recomputes them anyway).
  void ensure_trial() const {
    if (trial_stale_) update_trial();
  }
  double long_term_energy(const VecX& u) const override { return elastic_.energy(u); }
  /// sum_j alpha_j h_j : M : h_j / tau_j-weighted quadratic forms of tet t for a set of histories.
  double branch_form(std::size_t t, const double* h, double* rate) const override;
  void trial_changed() override { trial_stale_ = true; }
  /// The elasticity scaled by the trial gain g (pk2): the Lame pair of the trial S(E) part: (1 + g)
  /// C (full), or mu scaled by (1 + g) and lambda by -2 g mu / 3 (deviatoric).
  StVenantKirchhoff trial_elasticity() const;
  /// Recomputes the constant trial parts (f_hist or S_hist) from the committed state.
  void update_trial() const;
  /// pk2: grad u of tet t from relative displacements.
  Mat3 displacement_gradient(Index t, const VecX& u) const;
  /// pk2: adds tet t's trial force f_p = V F S_total a_p (S_total = lambda_eff tr(E) I + 2 mu_eff E
  /// + S_hist) to f and returns its Green strain E.
  Mat3 add_trial_force(std::size_t t, const VecX& u, double lam_eff, double mu_eff, VecX& f) const;

  TensorMassStVK elastic_;
  StVenantKirchhoff material_;
  std::vector<TetRest> rest_;  ///< pk2
  std::vector<double> kpinv_;  ///< nodal_force: 144 per tet, pseudo-inverse of the rest stiffness

  // The constant trial parts, mutable: recomputed lazily after a commit (ensure_trial). A model is
  // therefore not safe for concurrent const calls (no solver makes them).
  mutable VecX f_hist_;                       ///< nodal_force: assembled constant force
  mutable std::vector<double> s_hist_;        ///< pk2: per tet 6 (Voigt)
  mutable std::vector<double> s_hist_lanes_;  ///< pk2 on the fast kernel: s_hist_ in its lane order
  mutable bool trial_stale_ = false;
  std::shared_ptr<const FastTetForce> fast_;  ///< options().fast_threads >= 1
};

}  // namespace tmlab::tm
