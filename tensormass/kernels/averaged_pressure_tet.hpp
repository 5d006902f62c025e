// AveragedPressureTet: a locking-free linear tet for any hyperelastic Law, the average-nodal-pressure
// idea of NiftySim's T4ANP (Joldes, Wittek, Miller 2009) written as a potential, so that the force and
// the tangent are exact derivatives of one energy (nodal-averaged F-bar):
//
//   F_e = I + sum_p U_p (x) a_p,  J_e = det F_e            (per tet e, P1 as in HyperelasticTL)
//   J_a = sum_{e ∋ a} V_e J_e / sum_{e ∋ a} V_e            (node a, rest volumes V_e)
//   Jbar_e = (1/4) sum_{a ∈ e} J_a,  s_e = (Jbar_e / J_e)^(1/3),  Fbar_e = s_e F_e
//   W(u) = sum_e V_e psi(Ebar_e),  Ebar_e = (Fbar_e^T Fbar_e - I) / 2   (psi: the Law's W(E))
//
// Derivatives. With Pbar = Fbar S(Ebar) and p = (1/3) Pbar : Fbar, psi as a function of (F, Jbar) has
//   d psi / dF    = P_iso = s Pbar - p F^-T          (P_iso : F = 0: the element's own isochoric part)
//   d psi / dJbar = q     = p / Jbar                 (the volumetric part, coupled through the patch)
// and dJ_e/dU_p = cof(F_e) a_p, so
//   f = sum_e V_e P_iso,e a_p  +  sum_e pi_e cof(F_e) a_p,   pi_e = V_e sum_{a ∈ e} Q_a / sum_{e' ∋ a} V_e',
//   Q_a = (1/4) sum_{e ∋ a} V_e q_e.
// The tangent is the exact Hessian: per tet the 10x10 Hessian of psi in (F, Jbar) (its columns are
// the linearisation of (P_iso, q)) mapped through dF_e (the tet's own 12 DOFs) and dJbar_e (a patch),
// plus pi_e d^2 J_e. Because Jbar_e depends on every node of every tet that shares a node with e (the
// tet's "patch"), and the term q' dJbar_e (x) dJbar_e couples all patch nodes with each other, the
// assembled tangent couples two nodes when they are at most three edges apart in the mesh graph (P1:
// one edge). tangent() assembles that widened pattern (built once at construction) and refills it in
// place; tangent_apply() is matrix-free (the same passes as the force, linearised). Measured: 9.9x
// P1's nonzeros on a 16^3 block (5,958,999 vs 602,649).
//
// The force pass (internal_force, the explicit step's cost). Written with t = s^2 and C = F^T F
// (Ebar = (t C - I)/2, p = (t/3) S : C, V P_iso = V t F S - (V p / J) cof F) and with
// V cof(F) a_p = dV(x)/dx_p, the derivative of the deformed volume (a cross product of two deformed
// edges / 6), in sweeps that store no per-tet matrix (no allocation after the first call): (1) J_e
// from the deformed edges; (2) per node J_a, a gather over the node -> tet list with precomputed
// weights V_e / sum V; (3) per tet Jbar_e and s_e = (Jbar_e/J_e)^(1/3) (volume_cube_root, in a
// vectorisable loop), then the law once at Ebar_e, V t F S a_p scattered, p_e / J_e and q_e kept; the
// nodal pressure sums by the same gather; (4) (pi_e / V_e - p_e / J_e) dV(x)/dx_p scattered. Measured
// about as fast as HyperelasticTL's force (0.94-1.04x, docs/elements.md); internal_force_reference()
// is the direct evaluation (psi's gradient per tet, as psi_gradient), the oracle of the fast pass.
//
// No stabilisation parameter. The deviatoric part is each tet's own F_e (only the volumetric part is
// averaged), so a displacement with zero stiffness must have, in every tet, a linearised strain that
// is a pure dilatation theta_e I. Across a shared face the jump of grad u must be of rank one (c (x)
// n), and (theta_1 - theta_2) I + (W_1 - W_2) (W skew) has rank one only when it is zero: grad u is
// the same theta I + W in every tet, and the averaged volume change 3 theta must vanish too. Only
// the six rigid motions are left (tests/test_averaged_pressure_tet.cpp checks the spectrum on
// distorted patches). Unlike the node-based uniform-strain tet (FEBio UT4) nothing is nodally
// integrated in the deviatoric part, hence no hourglass-like modes and no stabilisation.
//
// Affine fields: every J_e equal gives Jbar_e = J_e, Fbar_e = F_e, and the element is exactly P1
// (HyperelasticTL) there: the patch test holds.
//
// Outside the law's domain. St VK is evaluated for every F with J_e != 0 (s_e is a real cube root).
// For every other law a tet with J_e <= 0 or Jbar_e <= 0 has energy +inf and NaN force (its NaN
// reaches the nodes of its patch through Q), as in HyperelasticTL.
//
// Not thread-safe: internal_force() uses a mutable per-model workspace (one model per thread).
#pragma once

#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/kernels/tet_geometry.hpp"
#include "tensormass/materials/law.hpp"

#include <Eigen/LU>

#include <vector>

namespace tmlab::tm {

class AveragedPressureTet : public ElasticModel {
 public:
  using StorageIndex = SpMat::StorageIndex;
  using Mat10 = Eigen::Matrix<double, 10, 10>;

  /// Copies the connectivity, computes the rest geometry, the nodal volume sums, the node -> tet
  /// adjacency and the widened tangent pattern (throws tmlab::Error on bad tets; a node in no tet
  /// has no stiffness and no entries, as in HyperelasticTL).
  AveragedPressureTet(const Mesh& mesh, Law law);

  Index num_nodes() const override { return num_nodes_; }
  Index num_tets() const { return static_cast<Index>(tets_.size()); }
  const Law& law() const { return law_; }

  double energy(const VecX& u) const override;
  void internal_force(const VecX& u, VecX& f) const override;
  void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const override;
  /// Fills K in place when it already has this model's (widened) pattern, otherwise gives it the
  /// pattern first.
  void tangent(const VecX& u, SpMat& K) const override;

  /// The law the element evaluates at Fbar_e in a viscoelastic trial step
  /// (tensormass/viscoelastic/viscoelastic_law_anp.hpp): (1 + gain) times the Law plus a constant
  /// per-tet PK2 stress S_hist_e (6 per tet, Voigt, tensor components):
  ///   psi_e = (1 + g) W(Ebar) + S_hist_e : Ebar,  S = (1 + g) S(Ebar) + S_hist_e,  D = (1 + g) D(Ebar).
  /// s_hist == nullptr: the Law itself (what energy(), internal_force(), ... use).
  struct TrialStress {
    double gain = 0.0;
    const double* s_hist = nullptr;
  };
  /// energy / force / tangent of the potential sum_e V_e psi_e for that law (its exact derivatives).
  double energy_with(const VecX& u, const TrialStress& ts) const;
  void internal_force_with(const VecX& u, VecX& f, const TrialStress& ts) const;
  void tangent_apply_with(const VecX& u, const VecX& v, VecX& Kv, const TrialStress& ts) const;
  void tangent_with(const VecX& u, SpMat& K, const TrialStress& ts) const;
  /// The direct (slow) force: per tet psi's gradient (P_iso, q) as psi_gradient(), then the nodal
  /// pressure sums and the scatter; the oracle of internal_force()'s fused passes.
  void internal_force_reference(const VecX& u, VecX& f) const;
  void internal_force_reference(const VecX& u, VecX& f, const TrialStress& ts) const;

  /// Nonzeros of the widened tangent pattern (9 per pair of nodes at most three edges apart).
  Index pattern_nonzeros() const { return static_cast<Index>(inner_.size()); }
  /// Jbar_e / J_e of every tet at u (1 for an affine u), for tests and diagnostics.
  std::vector<double> volume_ratios(const VecX& u) const;
  /// Fbar_e of tet t at u (costs a whole averaging pass over the mesh).
  Mat3 averaged_deformation_gradient(Index t, const VecX& u) const;
  /// Fbar_e of every tet at u (one averaging pass).
  std::vector<Mat3> averaged_deformation_gradients(const VecX& u) const;
  /// The rest volume V_e of tet t.
  double rest_volume(Index t) const { return rest_[static_cast<std::size_t>(t)].volume; }
  /// The 10x10 Hessian of psi(F, Jbar) = W_law(E((Jbar / det F)^(1/3) F)) in (vec F row-major, Jbar)
  /// (NaN outside the domain), exposed for its finite-difference test.
  Mat10 psi_hessian(const Mat3& F, double Jbar) const;
  /// (d psi/dF, d psi/dJbar) as a 10-vector in the same order.
  Eigen::Matrix<double, 10, 1> psi_gradient(const Mat3& F, double Jbar) const;
  /// The real cube root of the volume ratio every path uses (s_e = volume_cube_root(Jbar_e / J_e)): a
  /// polynomial and two Halley steps on [1/2, 2], std::cbrt elsewhere; exposed for its test.
  static double volume_cube_root(double r);
  /// psi(F, Jbar) (+inf outside the domain).
  double psi(const Mat3& F, double Jbar) const;

 private:
  Mat3 grad(Index t, const VecX& u) const;  // sum_p U_p (x) a_p
  // The passes for a tet law TL: void operator()(std::size_t t, const Mat3& E, double* W, Mat3* S,
  // Mat6* D) const (defined and instantiated in the .cpp: the Law, and the trial law of TrialStress).
  template <class TL>
  double energy_impl(const VecX& u, const TL& tl) const;
  template <class TL>
  void force_impl(const VecX& u, VecX& f, const TL& tl) const;
  template <class TL>
  void force_reference_impl(const VecX& u, VecX& f, const TL& tl) const;
  template <class TL>
  void tangent_apply_impl(const VecX& u, const VecX& v, VecX& Kv, const TL& tl) const;
  template <class TL>
  void tangent_impl(const VecX& u, SpMat& K, const TL& tl) const;
  /// J_e of every tet, then Jbar_e, into j and jbar.
  void averaged_volumes(const VecX& u, std::vector<double>& j, std::vector<double>& jbar) const;
  void build_pattern();
  /// Adds the dense local matrix Kloc (rows/cols 3i+a over the sorted nodes `nodes`) into values.
  void scatter(const std::vector<Index>& nodes, const Eigen::MatrixXd& Kloc, double* values) const;

  Index num_nodes_ = 0;
  std::vector<Tet> tets_;
  std::vector<TetRest> rest_;
  Law law_;
  std::vector<double> inv_node_volume_;            ///< 1 / sum_{e ∋ a} V_e (0 for a node in no tet)
  std::vector<Index> node_tet_start_, node_tets_;  ///< CSR: tets around each node
  std::vector<double> node_tet_weight_;            ///< V_e / sum_{e' ∋ a} V_e' per CSR entry
  static constexpr std::size_t kGeo = 10;
  std::vector<double> geo_;  ///< internal_force's compact rest data per tet: V, a_1, a_2, a_3 (kGeo)
  std::vector<double> inv_six_volume_;            ///< 1 / (6 V_e)
  std::vector<double> points_;                    ///< rest positions X, 3 per node
  std::vector<Index> node_adj_start_, node_adj_;  ///< CSR: sorted nodes sharing a tet (incl. self)
  std::vector<StorageIndex> outer_, inner_;       ///< widened CSC pattern (3 DOFs per node)
  mutable std::vector<double> work_;              ///< internal_force's workspace (see the .cpp)
};

}  // namespace tmlab::tm
