// The points at which the contact constraint is imposed (docs/contact.md, "Contact points"): each a
// weighted combination of mesh nodes, x_q = sum_a N_a x_a, with a weight w_q in the contact potential
//   Phi = sum_q w_q / (2 eps) (<lambda_q - eps g_q>_+^2 - lambda_q^2)   (bonded: w_q (lambda_q . c_q + eps/2
//   |c_q|^2)),
// whose force on node a is w_q N_a times the point's force per unit weight.
//   at_nodes:           P1, one point per boundary node (one node, N = 1, w = 1): lambda is a nodal
//                       force (N) and eps a stiffness (N/m), the node-to-rigid rule unchanged.
//   at_face_quadrature: P2, the 6 points of the degree-4 triangle rule (core/mesh/triangle_quadrature.hpp)
//                       on each boundary 6-node triangle, w_q = the rest area weight. The constraint
//                       is then one per face (a group of 6 points): its weighted mean gap
//                       g_f = sum_q w_q g_q / A_f >= 0 with one multiplier, the face's contact
//                       pressure (Pa), eps an area density (Pa/m) (contact_solver.hpp). A uniform
//                       pressure gives the consistent quadratic load (corners 0, midside nodes A/3 each).
#pragma once

#include "core/mesh/mesh.hpp"
#include "core/mesh/quadratic_mesh.hpp"
#include "tensormass/contact/surface_grid.hpp"
#include "tensormass/kernels/elastic_model.hpp"

#include <vector>

namespace tmlab::tm {

struct ContactPoints {
  bool nodal = true;           ///< point k is the surface node k (at_nodes)
  std::vector<Index> start;    ///< nodes of point q: node[start[q] .. start[q+1])
  std::vector<Index> node;     ///< mesh node indices (of the model's node numbering)
  std::vector<double> shape;   ///< N_a(xi_q) per entry of `node`
  std::vector<double> weight;  ///< w_q: 1 (nodal) or the reference area weight, m^2
  std::vector<Vec3> rest;      ///< X_q = sum_a N_a X_a
  std::vector<Index> face;     ///< the point's face in ContactSurface::faces (-1 for a nodal point)
  std::vector<Index> nodes;    ///< sorted, unique nodes of all points (the DOFs contact touches)
  Index num_nodes = 0;         ///< node count of the model the points belong to
  /// The constraints: constraint c acts on the points group[c] .. group[c+1] (nodal: one point each;
  /// face quadrature: the 6 points of boundary face c, which all list that face's 6 nodes in the
  /// same order).
  std::vector<Index> group;
  std::vector<double> group_area;  ///< A_c = sum of its points' weights (nodal: 1), m^2 on faces

  Index size() const { return static_cast<Index>(weight.size()); }
  Index num_constraints() const { return static_cast<Index>(group_area.size()); }
  /// Current position x_q = X_q + sum_a N_a u_a (u node-major; empty: the rest position).
  Vec3 position(const VecX& u, Index q) const;
  /// Current positions of every point.
  std::vector<Vec3> positions(const VecX& u) const;
  /// The reference area a point stands for, projected on a body normal n: the nodal tributary area
  /// (ContactSurface::contact_area) for a node, w_q max(0, -N_f . n) for a face point.
  double contact_area(const ContactSurface& surface, Index q, const Vec3& n) const;

  /// One point per node of `surface` (of the linear mesh `mesh`).
  static ContactPoints at_nodes(const Mesh& mesh, const ContactSurface& surface);
  /// The face quadrature points of the 6-node triangles of `qm` on the faces of `surface` (the
  /// boundary of the linear mesh qm was made from).
  static ContactPoints at_face_quadrature(const QuadraticMesh& qm, const ContactSurface& surface);
};

}  // namespace tmlab::tm
