// ViscoelasticHyperelasticP2: the objective Prony-series scheme of ViscoelasticHyperelastic
// (viscoelastic_law.hpp: history "pk2", relaxation "full", any long-term law) on the 10-node tet
// HyperelasticP2, with the histories at the quadrature points: ViscoelasticBase's per-tet slots are
// per-point slots here, slot s = 14 t + q (allocate_history(num_tets * 14, 6)), and at each point
//
//   S_e = dW/dE (E of the law's F at the point: F_q, or Fbar_q with mean dilatation)
//   h_j^{n+1} = a_j h_j^n + c_j (S_e^{n+1} - S_e^n)
//   trial step: S_total = (1 + g) S_e + S_hist,  D_total = (1 + g) D
//   trial_potential(u) = sum_q w_q [ (1 + g) W(E_q) + S_hist_q : E_q ]  (its gradient is the force)
//
// The element code is HyperelasticP2's (its PointLaw template), so force and tangent are exact
// derivatives of the trial potential for both volumetric variants. Branch energies Psi_j = w_q
// alpha_j/2 h_j : C_0^{-1} : h_j per point, with C_0 the law's small-strain elasticity (as the P1 model).
// On a homogeneous deformation every point has the same state and the weights sum to the volume, so
// this model equals the P1 model (tests/test_viscoelastic_law_p2.cpp).
#pragma once

#include "core/mesh/quadratic_mesh.hpp"
#include "tensormass/kernels/hyperelastic_p2.hpp"
#include "tensormass/materials/law.hpp"
#include "tensormass/viscoelastic/prony_series.hpp"
#include "tensormass/viscoelastic/viscoelastic_base.hpp"

#include <vector>

namespace tmlab::tm {

class ViscoelasticHyperelasticP2 : public ViscoelasticBase {
 public:
  /// Throws tmlab::Error unless options.history is Pk2 and options.relaxation is Full (naming the
  /// refused option), and on bad tets.
  ViscoelasticHyperelasticP2(const QuadraticMesh& mesh, Law long_term, PronySeries prony,
                             ViscoelasticOptions options = {}, P2Options p2 = {});

  Index num_nodes() const override { return elastic_.num_nodes(); }
  Index num_tets() const { return elastic_.num_tets(); }
  int num_points_per_tet() const { return elastic_.num_points_per_tet(); }
  const HyperelasticP2& elastic() const { return elastic_; }  ///< the long-term spring
  void internal_force(const VecX& u, VecX& f) const override;
  void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const override;
  void tangent(const VecX& u, SpMat& K) const override;
  /// The history update with one kinematics evaluation per tet (the same values as the base's
  /// per-slot loop).
  void commit_step(const VecX& u) override;
  /// Long-term spring plus the trial branch energies, with one kinematics evaluation per tet (the
  /// same value, bit for bit, as the base's per-slot loop ViscoelasticBase::energy).
  double energy(const VecX& u) const override;

  /// W_trial(u) = sum_t sum_q w_q [ (1 + g) W(E_q) + S_hist_q : E_q ].
  double trial_potential(const VecX& u) const;
  /// The trial total PK2 stress (1 + g) S_e + S_hist averaged over the points of tet t (output).
  Mat3 mean_pk2_stress(Index t, const VecX& u) const;

  /// The trial point law: (1 + g) times the long-term law plus the constant history stress.
  struct TrialPoint {
    const Law* law;
    double g;
    const double* s_hist;  ///< per slot 6 (Voigt)
    int points;
    bool operator()(Index t, int q, const Mat3& E, double* W, Mat3* S, Mat6* D) const;
  };

 private:
  TrialPoint trial_point() const;
  double long_term_energy(const VecX& u) const override { return elastic_.energy(u); }
  double branch_form(std::size_t slot, const double* h, double* rate) const override;
  void trial_changed() override;
  /// S_e at slot (t, q) (Voigt): the point's own F alone for the standard element, the tet's
  /// kinematics with mean dilatation (Fbar_q needs every point's J).
  void driver(std::size_t slot, const VecX& u, double* x) const override;

  HyperelasticP2 elastic_;
  LameConstants c0_;
  std::vector<double> s_hist_;  ///< per slot 6 (Voigt)
};

}  // namespace tmlab::tm
