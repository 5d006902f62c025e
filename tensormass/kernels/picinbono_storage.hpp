// PicinbonoAbsoluteStVK: Picinbono's original MESH-LEVEL tensor-mass storage, kept as the
// paper-faithful variant. The corrected per-tet tensors (docs/theory/seed-errata.md eq. 3, all four
// nodes, j,k,l,m = 0..3)
//   B_jk, C_jkl, D_jklm
// are summed over the tets sharing the same set of mesh vertices and stored on that set:
//   vertex p         : B_pp (sym 3x3), C_ppp, D_pppp
//   edge {p<q}       : B_pq (+B_qp^T), C_p(pq), C_q(pp), C_p(qq), C_q(pq), 4 D products
//   triangle {p<q<r} : C_p(qr), C_q(pr), C_r(pq), 6 D products
//   tet {p<q<r<s}    : 3 D products (pq)(rs), (pr)(qs), (ps)(qr)
// and the energy polynomial (errata eq. 2) and its gradient (eq. 7) are evaluated on the ABSOLUTE
// displacements U, exactly as the paper describes. It is exact in exact arithmetic, but a rigid
// translation t adds O(|t|^4 D) terms that must cancel: after a translation of 1e3-1e4 mesh sizes the
// energy and force lose many digits (tests/test_picinbono_storage.cpp), while TensorMassStVK, which
// evaluates the same tensors on relative displacements, stays at round-off.
// Not an ElasticModel: energy and internal force only (no tangent).
#pragma once

#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/materials/stvk_material.hpp"

#include <array>
#include <vector>

namespace tmlab::tm {

class PicinbonoAbsoluteStVK {
 public:
  struct VertexTensors {
    double B[6];  ///< packed upper triangle of B_pp (symmetric)
    double C[3];  ///< C_ppp
    double D;     ///< D_pppp
  };
  struct EdgeTensors {
    Index v[2];      ///< p < q
    double B[9];     ///< row-major; energy term U_p^T B U_q
    double C[4][3];  ///< (U_p.C0)(U_p.U_q) + (U_q.C1)(U_p.U_p) + (U_p.C2)(U_q.U_q) + (U_q.C3)(U_p.U_q)
    double D[4];     ///< G_pp G_pq, G_pp G_qq, G_pq G_pq, G_pq G_qq   (G_ab = U_a . U_b)
  };
  struct TriangleTensors {
    Index v[3];      ///< p < q < r
    double C[3][3];  ///< (U_p.C0) G_qr + (U_q.C1) G_pr + (U_r.C2) G_pq
    double D[6];     ///< G_pp G_qr, G_qq G_pr, G_rr G_pq, G_pq G_pr, G_pq G_qr, G_pr G_qr
  };
  struct TetTensors {
    Index v[4];   ///< p < q < r < s
    double D[3];  ///< G_pq G_rs, G_pr G_qs, G_ps G_qr
  };

  /// Throws tmlab::Error on bad tets (via the rest geometry).
  PicinbonoAbsoluteStVK(const Mesh& mesh, const StVenantKirchhoff& material);

  Index num_nodes() const { return static_cast<Index>(vertices_.size()); }
  Index num_dofs() const { return 3 * num_nodes(); }
  std::size_t num_edges() const { return edges_.size(); }
  std::size_t num_triangles() const { return triangles_.size(); }
  std::size_t num_tets() const { return tets_.size(); }
  /// Bytes of stored tensors (vertex + edge + triangle + tet records).
  std::size_t storage_bytes() const;

  /// W(U) = sum over vertices, edges, triangles, tets of the stored polynomial terms.
  double energy(const VecX& u) const;
  /// f = dW/dU (overwrites f).
  void internal_force(const VecX& u, VecX& f) const;

 private:
  std::vector<VertexTensors> vertices_;
  std::vector<EdgeTensors> edges_;
  std::vector<TriangleTensors> triangles_;
  std::vector<TetTensors> tets_;
};

}  // namespace tmlab::tm
