// The geometry of node-to-rigid contact in the deal.II reference (docs/reference-fem.md, "Contact"):
// the signed gap of a point against a rigid body of the case's `contact` section (ContactBodySpec,
// core/config/contact_spec.hpp) and the contact boundary of the mesh (boundary nodes, reference
// tributary areas, mean boundary edge). Deal.II-free.
//
// The gap itself is core's one copy (core/geometry/rigid_gap.hpp, the fast model's rigid bodies use
// it too); here it is evaluated for a ContactBodySpec at time t. The boundary is the reference's own
// copy of tensormass/contact/surface_grid.cpp's (the reference may depend on core only);
// test_reference_runner (ReferenceContactGeometry) checks that both give the same areas and mean
// edge to round-off, and that the gap of a spec equals the fast model's RigidBody::gap.
#pragma once

#include "core/config/contact_spec.hpp"
#include "core/geometry/rigid_gap.hpp"
#include "core/mesh/mesh.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace tmlab::ref {

/// The body's unit axis (the spec's axis, normalised; the spec parser refuses a zero axis).
Vec3 body_axis(const ContactBodySpec& body);
/// The gap of x against `body` at its position at time t.
GapPoint body_gap(const ContactBodySpec& body, const Vec3& x, double t);
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
