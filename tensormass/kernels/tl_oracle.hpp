// TotalLagrangianStVK: the independent, F-based total-Lagrangian P1 St Venant-Kirchhoff element, the
// oracle every tensor-mass kernel is checked against. It is written for obviousness, not speed:
//
//   F = I + sum_j U_j (x) a_j              (deformation gradient, constant per tet)
//   E = (F^T F - I) / 2                    (Green-Lagrange strain, seed eq. 1)
//   S = lambda tr(E) I + 2 mu E            (second Piola-Kirchhoff stress)
//   P = F S                                (first Piola-Kirchhoff stress)
//   W_T = V W(E),  f_p = dW_T/dU_p = V P a_p
//   K_pq = V [ (a_p . S a_q) I + lambda b_p b_q^T + mu b_q b_p^T + mu (a_p . a_q) F F^T ],  b = F a
//
// (material + geometric stiffness). The tangent is assembled from triplets (no shared pattern code
// with TensorMassStVK, so the two stay independent).
#pragma once

#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/kernels/tet_geometry.hpp"
#include "tensormass/materials/stvk_material.hpp"

#include <vector>

namespace tmlab::tm {

using Mat34 = Eigen::Matrix<double, 3, 4>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

class TotalLagrangianStVK : public ElasticModel {
 public:
  /// Copies the connectivity and computes the rest geometry (throws tmlab::Error on bad tets).
  TotalLagrangianStVK(const Mesh& mesh, const StVenantKirchhoff& material);

  Index num_nodes() const override { return num_nodes_; }
  Index num_tets() const { return static_cast<Index>(tets_.size()); }
  const StVenantKirchhoff& material() const { return material_; }
  const std::vector<Tet>& tets() const { return tets_; }
  const TetRest& rest(Index t) const { return rest_[static_cast<std::size_t>(t)]; }

  double energy(const VecX& u) const override;
  void internal_force(const VecX& u, VecX& f) const override;
  void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const override;
  void tangent(const VecX& u, SpMat& K) const override;

  // ---- per-tet kernels (also used by the viscoelastic models) ----
  /// F = I + sum_j U_j (x) a_j of tet t.
  Mat3 deformation_gradient(Index t, const VecX& u) const;
  /// E = (F^T F - I)/2 of tet t.
  Mat3 green_strain(Index t, const VecX& u) const;
  /// V W(E) of tet t.
  double tet_energy(Index t, const VecX& u) const;
  /// Column p = f_p = V F S a_p, the internal force dW_T/dU_p on local node p.
  Mat34 tet_force(Index t, const VecX& u) const;
  /// Column p = V F S a_p for a given F and S (e.g. a viscoelastic PK2 stress history).
  Mat34 tet_force_from_stress(Index t, const Mat3& F, const Mat3& S) const;
  /// d^2(V W)/dU^2 of tet t, 12x12, local node-major (row 3p+c).
  Mat12 tet_stiffness(Index t, const VecX& u) const;

 private:
  Index num_nodes_ = 0;
  std::vector<Tet> tets_;
  std::vector<TetRest> rest_;
  StVenantKirchhoff material_;
};

}  // namespace tmlab::tm
