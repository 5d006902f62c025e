// HyperelasticTL: the F-based total-Lagrangian P1 element for any hyperelastic Law (St Venant-
// Kirchhoff, neo-Hookean, Mooney-Rivlin, Yeoh, Ogden, Veronda-Westmann; tensormass/materials/law.hpp):
//
//   F = I + sum_{j=1..3} (U_j - U_0) (x) a_j     (relative form: exact, sum_j a_j = 0, and free of
//                                                 the round-off of large rigid translations)
//   E = (F^T F - I)/2,  S = dW/dE,  D = dS/dE    (the law)
//   W_T = V W(E),  f_p = V F S a_p
//   K_pq = V [ (a_p . S a_q) I + B_p^T D B_q ],  B_p = the 6x3 map dU_p -> engineering dE,
//          column i of B_p = engineering(sym((F^T e_i) (x) a_p))
//
// Why a new kernel beside TotalLagrangianStVK (tl_oracle.hpp): the oracle is the slow, obviously
// correct St VK element that every tensor-mass kernel is checked against, so it stays as it is
// (St VK only, closed-form stiffness, triplet assembly, absolute form). This kernel is the general
// one: any law through the Law variant, the tangent refilled in place through the mesh's
// TangentPattern; tests/test_hyperelastic_tl.cpp checks it against finite differences of itself
// for every law and against the oracle, to round-off, for St VK. The tensor-mass kernel
// (tensor_mass.hpp) stays the paper's St VK model.
//
// Outside the law's domain. St VK is defined for every F (including inverted tets) and this kernel
// evaluates it there as the oracle does. For every other law a tet with det F <= 0 has energy +inf
// and NaN force and tangent entries: the Newton solvers (tensormass/solvers/newton.hpp) treat a
// non-finite residual as a failed trial and backtrack.
#pragma once

#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/kernels/tangent_pattern.hpp"
#include "tensormass/kernels/tet_geometry.hpp"
#include "tensormass/materials/law.hpp"

#include <Eigen/LU>

#include <vector>

namespace tmlab::tm {

class HyperelasticTL : public ElasticModel {
 public:
  using Mat34 = Eigen::Matrix<double, 3, 4>;
  using Mat12 = Eigen::Matrix<double, 12, 12>;

  /// Copies the connectivity, computes the rest geometry and the tangent pattern (throws
  /// tmlab::Error on bad tets).
  HyperelasticTL(const Mesh& mesh, Law law);

  Index num_nodes() const override { return num_nodes_; }
  Index num_tets() const { return static_cast<Index>(tets_.size()); }
  const Law& law() const { return law_; }
  const std::vector<Tet>& tets() const { return tets_; }
  const TetRest& rest(Index t) const { return rest_[static_cast<std::size_t>(t)]; }
  const TangentPattern& pattern() const { return pattern_; }

  double energy(const VecX& u) const override;
  void internal_force(const VecX& u, VecX& f) const override;
  void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const override;
  /// Fills K in place when it already has this model's pattern, otherwise gives it the pattern first.
  void tangent(const VecX& u, SpMat& K) const override;

  // ---- per-tet kernels (also used by the viscoelastic model on a general law) ----
  /// grad u = sum_j (U_j - U_0) (x) a_j of tet t (for a direction v: dF = grad v).
  Mat3 displacement_gradient(Index t, const VecX& u) const;
  /// F = I + grad u of tet t.
  Mat3 deformation_gradient(Index t, const VecX& u) const {
    return Mat3::Identity() + displacement_gradient(t, u);
  }
  /// False when the law is not St VK and det F <= 0 (outside the law's domain).
  bool in_domain(const Mat3& F) const { return law_.is_stvk() || F.determinant() > 0.0; }
  /// V W(E) of tet t (+inf outside the domain).
  double tet_energy(Index t, const VecX& u) const;
  /// Column p = f_p = V F S a_p.
  Mat34 tet_force(Index t, const VecX& u) const;
  /// Column p = V F S a_p for a given F and S (e.g. a viscoelastic PK2 stress).
  Mat34 tet_force_from_stress(Index t, const Mat3& F, const Mat3& S) const;
  /// d^2(V W)/dU^2 of tet t, 12x12, local node-major (row 3p+c).
  Mat12 tet_stiffness(Index t, const VecX& u) const;
  /// V [ (a_p . S a_q) I + B_p^T D B_q ] for given F, S and D (e.g. a viscoelastic total stress
  /// and its consistent tangent).
  Mat12 tet_stiffness_from(Index t, const Mat3& F, const Mat3& S, const Mat6& D) const;

 private:
  Index num_nodes_ = 0;
  std::vector<Tet> tets_;
  std::vector<TetRest> rest_;
  TangentPattern pattern_;
  Law law_;
};

}  // namespace tmlab::tm
