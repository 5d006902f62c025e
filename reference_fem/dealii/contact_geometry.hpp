// The geometry of node-to-rigid contact in the deal.II reference (docs/reference-fem.md, "Contact"):
// the signed gap of a point against a rigid body of the case's `contact` section (ContactBodySpec,
// core/config/contact_spec.hpp) and the contact boundary of the mesh (boundary nodes, reference
// tributary areas, mean boundary edge). Deal.II-free.
//
// The reference may depend on core only, so these are the reference's own copy of the formulas of
// tensormass/contact (rigid_body.cpp, surface_grid.cpp); test_reference_contact checks that both
// copies give the same gap, normal, closest point, Hessian, areas and mean edge to round-off, so they
// cannot drift apart unnoticed. Shapes, with c(t) the body's reference point and a its unit axis:
//   sphere:  g = |x - c| - R,  n = (x - c)/|x - c|,  H = (I - n n^T)/|x - c|
//   plane:   g = (x - c).a,  n = a,  H = 0
//   punch:   the cylinder s = (x - c).a <= 0, r <= R with its rim rounded by rho: g = dist_K - rho,
//            K = {s <= -rho, r <= R - rho} (face, side, or rim-circle region)
#pragma once

#include "core/config/contact_spec.hpp"
#include "core/mesh/mesh.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace tmlab::ref {

/// The gap of one point against a body: signed distance (< 0 inside), outward unit normal dg/dx,
/// closest surface point x - g n, Hessian d^2 g/dx^2.
struct BodyGap {
  double g = 0.0;
  Vec3 normal = Vec3::UnitZ();
  Vec3 closest = Vec3::Zero();
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
};

/// The body's unit axis (the spec's axis, normalised; the spec parser refuses a zero axis).
Vec3 body_axis(const ContactBodySpec& body);
/// The gap of x against `body` at its position at time t.
BodyGap body_gap(const ContactBodySpec& body, const Vec3& x, double t);
/// Distance of x from the body's axis line through c(t) (0 for the plane).
double body_radial_distance(const ContactBodySpec& body, const Vec3& x, double t);

/// The boundary of a tet mesh as the contact rule sees it: the faces used by one tet, their nodes
/// (increasing), and per node the faces it belongs to.
struct ContactBoundary {
  std::vector<Index> nodes;       ///< boundary nodes, increasing (mesh indices)
  std::vector<Vec3> face_normal;  ///< unit outward normal per boundary face (reference)
  std::vector<double> face_area;  ///< m^2
  std::vector<Index> face_start;  ///< faces of node k: node_faces[face_start[k] .. face_start[k+1])
  std::vector<Index> node_faces;
  double mean_edge = 0.0;  ///< mean boundary edge length (each face's three edges), m

  /// Tributary area of boundary node k projected on a body normal n: sum_f A_f/3 max(0, -N_f . n).
  double contact_area(std::size_t k, const Vec3& n) const;
  /// Extracts the boundary; throws tmlab::Error when the mesh has no boundary face.
  static ContactBoundary extract(const Mesh& mesh);
};

}  // namespace tmlab::ref
