// The quadrature rule and the shape functions of the quadratic (10-node) tetrahedron on the reference
// tet with vertices (0,0,0), (1,0,0), (0,1,0), (0,0,1) (barycentrics L0 = 1 - x - y - z, L1 = x,
// L2 = y, L3 = z), local node order of core/mesh/quadratic_mesh.hpp (VTK):
//
//   N_i = L_i (2 L_i - 1)   (vertices i = 0..3),   N_{4+e} = 4 L_a L_b   (edge e = (a, b) of kTet10Edges)
//
// The rule is the one the deal.II reference integrates its P2 cells with: reference_fem/dealii/solid.cpp
// uses QGaussSimplex<3>(degree + 1) = QGaussSimplex<3>(3), which deal.II 9.4 (source/base/
// quadrature_lib.cc) defines as the 14-point Witherden-Vincent WV-5 rule (degree 5, positive weights):
// three orbits of barycentric points, (a, a, a, 1 - 3a) for a = 0.3108859192633006 (weight
// 0.1126879257180159) and a = 0.09273525031089125 (0.07349304311636196), and (a, a, 1/2 - a, 1/2 - a)
// for a = 0.04550370412564964 (0.04254602077708147), weights times the reference volume 1/6. The
// points are listed in deal.II's order (each orbit's barycentric permutations in lexicographic order,
// the first three coordinates as (x, y, z)); checked against the installed deal.II 9.4.1 to the last
// digit (tests/test_hyperelastic_p2.cpp holds the printed values). The rule is symmetric under every
// vertex permutation, so the same set of points is used whatever the vertex order deal.II gives a
// cell: "10-node tet = deal.II P2 on the same mesh" holds to round-off.
#pragma once

#include "core/mesh/mesh.hpp"

#include <array>

namespace tmlab::tm {

struct P2Quadrature {
  static constexpr int kPoints = 14;
  std::array<Vec3, kPoints> points{};     ///< reference coordinates (x, y, z)
  std::array<double, kPoints> weights{};  ///< sum 1/6, the reference volume
};

/// The 14-point rule above (deal.II 9.4's QGaussSimplex<3>(3)).
P2Quadrature p2_quadrature();

/// The ten shape functions at reference point xi.
std::array<double, 10> p2_shape_values(const Vec3& xi);
/// Their gradients with respect to the reference coordinates.
std::array<Vec3, 10> p2_shape_gradients(const Vec3& xi);

}  // namespace tmlab::tm
