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

#include "core/constitutive/prony.hpp"
#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/kernels/fast_force.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tet_geometry.hpp"
#include "tensormass/materials/stvk_material.hpp"
#include "tensormass/viscoelastic/prony_series.hpp"

#include <memory>
#include <string>
#include <vector>

namespace tmlab::tm {

/// The names of the choices are the shared vocabulary (core/constitutive/prony.hpp).
struct ViscoelasticOptions {
  using History = PronyHistory;
  using Integration = PronyIntegration;
  using Relaxation = PronyRelaxation;

  History history = History::Pk2;
  Integration integration = Integration::Midpoint;
  Relaxation relaxation = Relaxation::Full;
  /// Keep the committed energies and the dissipation. Every commit updates the branch energies and
  /// the dissipation rate (the trapezoidal dissipation needs the rate at every commit); the
  /// long-term spring energy W_e(u_c) is computed only when it is asked for
  /// (committed_elastic_energy(), committed_state()), from a copy of the committed u, so a run that
  /// records every k-th step pays for it every k-th step. Off: none of it (long explicit runs that
  /// report no energies).
  bool energy_bookkeeping = true;
  /// 0: the trial force on the reference per-tet kernels (results bit-identical to earlier versions).
  /// N >= 1: on FastTetForce (kernels/fast_force.hpp) with N threads: equal to the reference to
  /// round-off (1e-12 relative, tested), several times faster (docs/performance.md).
  int fast_threads = 0;

  /// "nodal_force" | "pk2", "midpoint" | "exact_linear" | "backward_euler", "full" | "deviatoric"
  /// (the shared parsers of prony.hpp). Throw tmlab::Error naming the accepted values.
  static History parse_history(const std::string& s);
  static Integration parse_integration(const std::string& s);
  static Relaxation parse_relaxation(const std::string& s);
  /// tmlab::to_string of prony.hpp, kept here for the model's users.
  static std::string to_string(History h) { return tmlab::to_string(h); }
  static std::string to_string(Integration i) { return tmlab::to_string(i); }
  static std::string to_string(Relaxation r) { return tmlab::to_string(r); }
};

using tmlab::recursion_factors;
using tmlab::RecursionFactors;

class ViscoelasticStVK : public ElasticModel {
 public:
  /// `long_term` is the St VK material of the long-term modulus E_inf (use
  /// PronySeries::long_term_modulus to convert an instantaneous E_0). Throws tmlab::Error for
  /// deviatoric relaxation with nodal_force history, and on bad tets.
  ViscoelasticStVK(const Mesh& mesh, const StVenantKirchhoff& long_term, PronySeries prony,
                   ViscoelasticOptions options = {});

  Index num_nodes() const override { return elastic_.num_nodes(); }
  Index num_tets() const { return elastic_.num_tets(); }
  const TensorMassStVK& elastic() const { return elastic_; }  ///< the long-term spring
  const PronySeries& prony() const { return prony_; }
  const ViscoelasticOptions& options() const { return options_; }

  /// Stored free energy of the trial state at u (long-term W_e(u) + branch energies), joules.
  double energy(const VecX& u) const override;
  /// Total (trial) internal force X_total(u) = d trial_potential / du.
  void internal_force(const VecX& u, VecX& f) const override;
  void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const override;
  void tangent(const VecX& u, SpMat& K) const override;

  bool has_history() const override { return true; }
  void begin_step(double dt) override;
  void commit_step(const VecX& u) override;
  /// hist, driver, then the committed energies, rate and dissipations (5 values).
  std::vector<double> committed_state() const override;
  void restore_committed_state(const std::vector<double>& state) override;
  /// internal_force(u, f) then commit_step(u) in one pass over the tets (the per-tet strains or
  /// elastic forces serve both); bit-identical to the two calls.
  void force_and_commit(const VecX& u, VecX& f) override;

  /// W_trial(u): the potential of the trial force (its gradient is internal_force, its Hessian tangent).
  double trial_potential(const VecX& u) const;
  /// The current trial step size (0 after construction and after every commit).
  double trial_dt() const { return dt_; }
  /// g = sum_j alpha_j c_j of the trial step: the tangent is the elastic one scaled by (1 + g)
  /// (nodal_force, pk2 full) or with mu scaled by (1 + g) and lambda by -2 g mu / 3 (deviatoric).
  double trial_gain() const { return gain_; }

  // ---- committed state and energy bookkeeping (updated by commit_step) ----
  /// W_e(u_c), the long-term spring at the last commit (computed on the first call after a commit:
  /// the same function of the same u as at the commit, so the value is identical bit for bit).
  double committed_elastic_energy() const;
  double committed_branch_energy() const { return committed_branch_; }   ///< sum of Psi_j at commit
  double step_dissipation() const { return step_dissipation_; }          ///< of the last commit, >= 0
  double total_dissipation() const { return total_dissipation_; }        ///< sum over commits
  double committed_dissipation_rate() const { return committed_rate_; }  ///< D at the last commit, W
  /// Raw committed history h_j^c, per tet [t][j][k] with k < 12 (nodal_force) or 6 (pk2, Voigt
  /// xx,yy,zz,xy,xz,yz), and the committed driver X_e^c per tet [t][k].
  const std::vector<double>& committed_history() const { return hist_; }
  const std::vector<double>& committed_driver() const { return driver_; }
  /// Number of history components per tet and term: 12 (nodal_force) or 6 (pk2).
  int history_width() const { return width_; }

 private:
  bool pk2() const { return options_.history == ViscoelasticOptions::History::Pk2; }
  bool deviatoric() const { return options_.relaxation == ViscoelasticOptions::Relaxation::Deviatoric; }
  /// X_e of tet t at u (width_ values): nodal forces, S_e or S_dev (Voigt).
  void driver(Index t, const VecX& u, double* x) const;
  /// pk2: X_e from the Green strain E of a tet (S_e or S_dev, Voigt).
  void driver_from_strain(const Mat3& E, double* x) const;
  /// The per-tet history update of commit_step (eq. 20 family) with the new driver x, and the
  /// branch energy bookkeeping of that tet.
  void commit_tet(std::size_t t, const double* x, bool book, double& psi, double& rate);
  /// The end of commit_step: dissipation bookkeeping, then the trial reset to dt = 0.
  void finish_commit(bool book, double psi, double rate);
  /// After a commit the trial is dt = 0; its constant parts are recomputed on first use (an
  /// explicit step calls begin_step(dt) next, which recomputes them anyway).
  void ensure_trial() const {
    if (trial_stale_) update_trial();
  }
  /// sum_j alpha_j h_j : M : h_j / tau_j-weighted quadratic forms of tet t for a set of histories.
  double branch_form(Index t, const double* h, double* rate) const;
  /// The elasticity scaled by the trial gain g (pk2): the Lame pair of the trial S(E) part.
  StVenantKirchhoff trial_elasticity() const;
  /// Recomputes the constant trial parts (f_hist or S_hist) from the committed state.
  void update_trial() const;
  /// pk2: grad u of tet t from relative displacements.
  Mat3 displacement_gradient(Index t, const VecX& u) const;

  TensorMassStVK elastic_;
  StVenantKirchhoff material_;
  PronySeries prony_;
  ViscoelasticOptions options_;
  bool elastic_only_ = false;  ///< all weights zero: forward every call to elastic_
  int width_ = 0;
  std::vector<TetRest> rest_;  ///< pk2
  std::vector<double> kpinv_;  ///< nodal_force: 144 per tet, pseudo-inverse of the rest stiffness

  // committed
  std::vector<double> hist_;                ///< [t][j][k]
  std::vector<double> driver_;              ///< [t][k]
  mutable double committed_elastic_ = 0.0;  ///< valid unless spring_stale_
  double committed_branch_ = 0.0, committed_rate_ = 0.0;
  double step_dissipation_ = 0.0, total_dissipation_ = 0.0;
  VecX committed_u_;                   ///< u of the last commit while its spring energy is pending
  mutable bool spring_stale_ = false;  ///< committed_elastic_ is still to be computed from committed_u_
  /// At a commit with bookkeeping: W_e(u) is computed lazily (committed_elastic_energy()).
  void defer_spring_energy(const VecX& u) {
    committed_u_ = u;
    spring_stale_ = true;
  }

  // trial
  double dt_ = 0.0;
  double gain_ = 0.0;  ///< g = sum alpha_j c_j
  std::vector<RecursionFactors> factors_;
  // The constant trial parts, mutable: recomputed lazily after a commit (ensure_trial). A model is
  // therefore not safe for concurrent const calls (no solver makes them).
  mutable VecX f_hist_;                 ///< nodal_force: assembled constant force
  mutable std::vector<double> s_hist_;  ///< pk2: per tet 6 (Voigt)
  mutable bool trial_stale_ = false;
  std::shared_ptr<const FastTetForce> fast_;  ///< options_.fast_threads >= 1
};

}  // namespace tmlab::tm
