// Rest geometry of linear (P1) tetrahedra, computed once per mesh: rest volume V and the constant
// shape-function gradients a_j = grad N_j (j = 0..3), with sum_j a_j = 0 and sum_j P_j (x) a_j = I.
//
// With J = [P1-P0, P2-P0, P3-P0] (columns), V = det(J)/6, a_1..a_3 are the rows of J^{-1} and
// a_0 = -(a_1 + a_2 + a_3). (The seed's alpha_k of eq. 6 are -6V a_k, see docs/theory/seed-errata.md, eq. 6.)
#pragma once

#include "core/mesh/mesh.hpp"

#include <array>
#include <string>
#include <vector>

namespace tmlab::tm {

struct TetRest {
  double volume = 0.0;         ///< V > 0, m^3
  std::array<Vec3, 4> grad{};  ///< a_j = grad N_j, 1/m
};

/// Rest volume and shape gradients of one tet from its four rest positions. Throws tmlab::Error
/// naming `element` when the tet is inverted (V < 0), flat (V == 0) or degenerate
/// (6V < 1e-12 * longest_edge^3).
TetRest tet_rest(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, const std::string& element);

/// Rest geometry of every tet of a mesh (index t <-> mesh.tets[t]). Throws tmlab::Error naming the
/// first bad element, or a tet that references a missing node.
std::vector<TetRest> compute_tet_rest(const Mesh& mesh);

}  // namespace tmlab::tm
