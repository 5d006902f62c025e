// The face quadrature of the quadratic elements: a symmetric 6-point rule on the triangle, exact for
// polynomials of degree 4 (Strang & Fix 1973 / Dunavant 1985; the same points and weights as
// deal.II's QWitherdenVincentSimplex<2>(2), which the reference's face contact uses), and the
// shape functions of the 6-node triangle. P2 face loads (the consistent load of a pressure) and the
// fast model's contact at face quadrature points (tensormass/contact) use them: the rule
// integrates N_a (degree 2) and N_a N_b (degree 4) exactly on a flat triangle.
#pragma once

#include <array>

namespace tmlab {

/// A point of a triangle rule: barycentric coordinates (l0 = 1 - l1 - l2) and its weight as a
/// fraction of the triangle's area (the weights sum to 1).
struct TrianglePoint {
  double l1 = 0.0, l2 = 0.0, weight = 0.0;
};

/// The 6-point degree-4 rule: two orbits (a, a, 1 - 2a) of three points each.
inline std::array<TrianglePoint, 6> triangle_rule_degree4() {
  constexpr double a = 0.44594849091596488632, wa = 0.22338158967801146570;
  constexpr double b = 0.091576213509770743460, wb = 0.10995174365532186764;
  return {{{a, a, wa},
           {1.0 - 2.0 * a, a, wa},
           {a, 1.0 - 2.0 * a, wa},
           {b, b, wb},
           {1.0 - 2.0 * b, b, wb},
           {b, 1.0 - 2.0 * b, wb}}};
}

/// The 6-node triangle's shape functions at barycentric (l1, l2), in the Tri6 node order of
/// core/mesh/quadratic_mesh.hpp: vertices 0, 1, 2 (L(2L - 1)), then the midside nodes of the edges
/// (0,1), (1,2), (0,2) (4 L_a L_b).
inline std::array<double, 6> tri6_shape(double l1, double l2) {
  const double l0 = 1.0 - l1 - l2;
  return {l0 * (2.0 * l0 - 1.0), l1 * (2.0 * l1 - 1.0), l2 * (2.0 * l2 - 1.0),
          4.0 * l0 * l1,         4.0 * l1 * l2,         4.0 * l0 * l2};
}

/// Their derivatives with respect to (l1, l2) (l0 = 1 - l1 - l2), same order: {dN/dl1, dN/dl2}.
inline std::array<std::array<double, 2>, 6> tri6_shape_gradient(double l1, double l2) {
  const double l0 = 1.0 - l1 - l2;
  return {{{-(4.0 * l0 - 1.0), -(4.0 * l0 - 1.0)},
           {4.0 * l1 - 1.0, 0.0},
           {0.0, 4.0 * l2 - 1.0},
           {4.0 * (l0 - l1), -4.0 * l1},
           {4.0 * l2, 4.0 * l1},
           {-4.0 * l2, 4.0 * (l0 - l2)}}};
}

}  // namespace tmlab
