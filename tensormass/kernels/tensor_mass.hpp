// TensorMassStVK: Picinbono's nonlinear (St Venant-Kirchhoff) tensor-mass model with the corrected
// tensors of docs/theory/seed-errata.md (eqs. 2, 3, 5, 6, 7), evaluated per tet on RELATIVE displacements
//
//   e_j = U_j - U_0,  j = 1..3     (exact: a_0 = -(a_1 + a_2 + a_3), so grad u = sum_{j=1..3} e_j (x) a_j)
//
// Evaluating on e instead of the absolute U keeps the polynomial free of the catastrophic
// cancellation of the original absolute form (see picinbono_storage.hpp, docs/theory/tensor-mass.md).
//
// Corrected tensors (errata eq. 3; here j,k,l,m = 1..3):
//   B_jk   = V [ lambda/2 a_j (x) a_k + mu/2 ( a_k (x) a_j + (a_j . a_k) I ) ]
//   C_jkl  = V [ lambda/2 a_j (a_k . a_l) + mu/2 ( a_l (a_j . a_k) + a_k (a_j . a_l) ) ]
//   D_jklm = V [ lambda/8 (a_j . a_k)(a_l . a_m) + mu/4 (a_j . a_m)(a_k . a_l) ]
// Energy (errata eq. 2):
//   W_T = sum_jk e_j^T B_jk e_k + sum_jkl (e_j . C_jkl)(e_k . e_l) + sum_jklm D_jklm (e_j . e_k)(e_l . e_m)
//
// Stored per tet with the symmetries folded in. With the 6 Gram entries G_P = e_k . e_l,
// P = (k,l) in {(1,1),(2,2),(3,3),(1,2),(1,3),(2,3)} and multiplicity m_P (1 diagonal, 2 off):
//   B   : the 9x9 matrix with blocks B_jk, symmetric (B_kj = B_jk^T): 45 packed values
//   Chat: 6x9, row P, block j = m_P C_jkl                                  : 54 values
//   Dhat: 6x6 symmetric, m_P m_Q Dsym_PQ (Dsym symmetrised over j<->k, l<->m, (jk)<->(lm)): 21
// so that  W_T = e^T B e + h . G + G^T Dhat G,  h = Chat e.
// Internal force (errata eq. 7, written through G): with sigma = h + 2 Dhat G and Gamma = dG/de,
//   g = dW_T/de = 2 B e + Chat^T G + Gamma^T sigma,   f_j = g_j (j=1..3),  f_0 = -(g_1+g_2+g_3).
// Tangent: d^2W_T/de^2 = 2B + Sigma (x) I + Chat^T Gamma + Gamma^T Chat + 2 Gamma^T Dhat Gamma,
//   Sigma_kk = 2 sigma_kk, Sigma_kl = sigma_kl; the 12x12 block follows from e = T U.
#pragma once

#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/kernels/tangent_pattern.hpp"
#include "tensormass/kernels/tet_geometry.hpp"
#include "tensormass/materials/stvk_material.hpp"

#include <vector>

namespace tmlab::tm {

/// The precomputed tensors of one tet (960 bytes), layout documented above.
struct TensorMassTet {
  double B[45];  ///< packed upper triangle (row-major) of the symmetric 9x9 [B_jk], index 3j+alpha
  double C[54];  ///< Chat row-major 6x9: C[9P + 3j + alpha]
  double D[21];  ///< packed upper triangle (row-major) of the symmetric 6x6 Dhat
};

/// Corrected B, C, D of one tet (errata eq. 3) in the folded layout.
TensorMassTet make_tensor_mass_tet(const TetRest& rest, const StVenantKirchhoff& material);

class TensorMassStVK : public ElasticModel {
 public:
  using Mat34 = Eigen::Matrix<double, 3, 4>;
  using Mat12 = Eigen::Matrix<double, 12, 12>;

  /// Computes rest geometry (throws tmlab::Error on bad tets), the per-tet tensors and the tangent
  /// sparsity pattern.
  TensorMassStVK(const Mesh& mesh, const StVenantKirchhoff& material);

  Index num_nodes() const override { return num_nodes_; }
  Index num_tets() const { return static_cast<Index>(tets_.size()); }
  const StVenantKirchhoff& material() const { return material_; }
  const std::vector<Tet>& tets() const { return tets_; }
  const TensorMassTet& tensors(Index t) const { return tensors_[static_cast<std::size_t>(t)]; }
  const TangentPattern& pattern() const { return pattern_; }

  double energy(const VecX& u) const override;
  void internal_force(const VecX& u, VecX& f) const override;
  void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const override;
  /// Fills K in place when it already has this model's pattern (from an earlier call), otherwise
  /// gives it the pattern first.
  void tangent(const VecX& u, SpMat& K) const override;

  // ---- per-tet kernels ----
  double tet_energy(Index t, const VecX& u) const;
  /// Column p = dW_T/dU_p (internal force on local node p).
  Mat34 tet_force(Index t, const VecX& u) const;
  /// g_j = dW_T/de_j (j = 1..3, g[3(j-1) + c]): the relative-form gradient from which internal_force
  /// (f_j += g_j, f_0 -= g_j) and tet_force (f_0 = -(g_1 + g_2 + g_3)) are built; lets a caller
  /// form both from one evaluation (the fused viscoelastic step).
  void tet_gradient(Index t, const VecX& u, double* g) const;
  /// d^2 W_T / dU^2, 12x12 local node-major.
  Mat12 tet_stiffness(Index t, const VecX& u) const;

 private:
  Index num_nodes_ = 0;
  std::vector<Tet> tets_;
  std::vector<TensorMassTet> tensors_;
  StVenantKirchhoff material_;
  TangentPattern pattern_;
};

}  // namespace tmlab::tm
