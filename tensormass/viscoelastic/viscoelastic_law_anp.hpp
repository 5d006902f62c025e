// ViscoelasticAveragedPressureTet: the objective Prony-series scheme of ViscoelasticHyperelastic
// (viscoelastic_law.hpp: history "pk2", relaxation "full", any long-term law) on the locking-free
// linear tet AveragedPressureTet (p1_anp, tensormass/kernels/averaged_pressure_tet.hpp), with one
// history per tet (the element has one point) driven by the PK2 stress at the tet's averaged
// deformation gradient Fbar_e:
//
//   S_e = dW/dE (Ebar_e),  Ebar_e = (Fbar_e^T Fbar_e - I)/2,  Fbar_e = (Jbar_e / J_e)^(1/3) F_e
//   h_j^{n+1} = a_j h_j^n + c_j (S_e^{n+1} - S_e^n)               (the recursion of ViscoelasticStVK)
//   trial step dt: psi_e = (1 + g) W(Ebar_e) + S_hist_e : Ebar_e,  g = sum_j alpha_j c_j,
//                  S_hist_e = sum_j alpha_j (a_j h_j^c - c_j S_e^c)      (constant in the step)
//   trial_potential(u) = sum_e V_e psi_e  (force and tangent: its exact derivatives, through the
//                  element's own passes with this tet law: AveragedPressureTet::TrialStress)
//
// The choice (docs/elements.md): the whole PK2 stress at Fbar relaxes ("full", as the P1 and P2
// general-law models), so the averaged pressure carries its share of the relaxation too; the
// element stays locking-free because every term is still a function of Fbar_e alone (the volume
// change enters only through the nodal average Jbar). On a homogeneous deformation Jbar_e = J_e and
// Fbar_e = F_e: this model is then the P1 model ViscoelasticHyperelastic to round-off (tested).
// Deviatoric-only relaxation is not offered, as for the other general-law models.
//
// Energies as the P1 model: branch energies Psi_j = V alpha_j/2 h_j : C_0^{-1} : h_j (C_0 the law's
// small-strain elasticity), dissipation rate D = sum_j 2 Psi_j / tau_j >= 0, trapezoidal step
// dissipation. The drivers of all tets need one averaging pass over the mesh, so commit_step and
// energy are done mesh-wide here (driver() for one tet costs a whole pass).
#pragma once

#include "tensormass/kernels/averaged_pressure_tet.hpp"
#include "tensormass/materials/law.hpp"
#include "tensormass/viscoelastic/prony_series.hpp"
#include "tensormass/viscoelastic/viscoelastic_base.hpp"

#include <vector>

namespace tmlab::tm {

class ViscoelasticAveragedPressureTet : public ViscoelasticBase {
 public:
  /// Throws tmlab::Error unless options.history is Pk2, options.relaxation is Full and
  /// options.fast_threads is 0 (naming the refused option), and on bad tets.
  ViscoelasticAveragedPressureTet(const Mesh& mesh, Law long_term, PronySeries prony,
                                  ViscoelasticOptions options = {});

  Index num_nodes() const override { return elastic_.num_nodes(); }
  Index num_tets() const { return elastic_.num_tets(); }
  const AveragedPressureTet& elastic() const { return elastic_; }  ///< the long-term spring
  /// Total (trial) internal force, the gradient of trial_potential.
  void internal_force(const VecX& u, VecX& f) const override;
  void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const override;
  void tangent(const VecX& u, SpMat& K) const override;
  /// The history update with one averaging pass (the same values as the base's per-tet loop).
  void commit_step(const VecX& u) override;
  /// Long-term spring plus the trial branch energies (one averaging pass).
  double energy(const VecX& u) const override;

  /// W_trial(u) = sum_e V_e [ (1 + g) W(Ebar_e) + S_hist_e : Ebar_e ].
  double trial_potential(const VecX& u) const;
  /// The trial total PK2 stress (1 + g) S_e(Ebar_e) + S_hist_e of tet t (output).
  Mat3 total_pk2_stress(Index t, const VecX& u) const;

 private:
  AveragedPressureTet::TrialStress trial() const { return {trial_gain(), s_hist_.data()}; }
  /// S_e(Ebar_e) of every tet (Voigt, 6 per tet).
  std::vector<double> drivers(const VecX& u) const;
  double long_term_energy(const VecX& u) const override { return elastic_.energy(u); }
  double branch_form(std::size_t t, const double* h, double* rate) const override;
  void trial_changed() override;
  /// S_e of tet t at u (Voigt); a whole averaging pass for one tet.
  void driver(std::size_t t, const VecX& u, double* x) const override;

  AveragedPressureTet elastic_;
  LameConstants c0_;            ///< small-strain elasticity of the law (branch energies)
  std::vector<double> s_hist_;  ///< per tet 6 (Voigt)
};

}  // namespace tmlab::tm
