// The gap of a point against a rigid analytic body (docs/contact.md): a sphere, a flat cylindrical
// punch (with an optional edge radius) or an infinite plane. The one copy of this geometry: the
// fast model's rigid bodies (tensormass/contact/rigid_body.hpp) and the deal.II reference's contact
// (reference_fem/dealii/contact_geometry.hpp) both call it, so the two models measure the same gap.
//
// For a point x of the sample: the signed gap g(x) (the signed distance to the body's surface: g > 0
// outside the body, g < 0 inside), the outward unit normal n = dg/dx of the body at its closest point
// y = x - g n, and the Hessian H = d^2 g / dx^2 (the curvature term of the contact tangent). g is a
// true signed distance for all three, so |dg/dx| = 1 wherever it is smooth.
//
// Shapes, with c the body's reference point and a its unit axis:
//   sphere (radius R, centre c):   g = |x - c| - R,  n = (x - c)/|x - c|,  H = (I - n n^T)/|x - c|.
//                                   a only orients the contact-radius output (radial distance from
//                                   the line through c along a).
//   plane (point c, normal a):      the half-space (x - c).a < 0;  g = (x - c).a,  n = a,  H = 0.
//   punch (face centre c, axis a,   a semi-infinite solid cylinder s = (x - c).a <= 0, r <= R, whose
//          radius R, edge radius rho) flat face (normal a, pointing into the sample) has its rim
//                                   rounded with radius rho in [0, R]. It is the core K = {s <= -rho,
//                                   r <= R - rho} dilated by a ball of radius rho, so g = dist_K - rho
//                                   (exact for a convex core), with dist_K the signed distance to K
//                                   in the (r, s) half-plane: the face, the side, or the rim circle
//                                   (distance sqrt((r - R + rho)^2 + (s + rho)^2)). rho = 0 gives the
//                                   sharp-edged punch of Sneddon's problem: nodes beyond the rim are
//                                   then measured to the rim circle, so g stays C1 outside the body.
#pragma once

#include "core/mesh/mesh.hpp"

#include <Eigen/Core>

namespace tmlab {

enum class ContactShape { Sphere, Punch, Plane };

/// The gap of one point against a body: signed distance, outward normal, closest point, Hessian.
struct GapPoint {
  double g = 0.0;               ///< signed gap, metres (< 0: the point is inside the body)
  Vec3 normal = Vec3::UnitZ();  ///< outward unit normal of the body = dg/dx
  Vec3 closest = Vec3::Zero();  ///< closest point on the body's surface, x - g n
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();  ///< d^2 g / dx^2
};

/// The gap functions of the three shapes in the body frame (x relative to the reference point).
GapPoint sphere_gap(const Vec3& x_rel, double radius);
GapPoint plane_gap(const Vec3& x_rel, const Vec3& normal);
GapPoint punch_gap(const Vec3& x_rel, const Vec3& axis, double radius, double edge_radius);

/// The gap of x against a body of `shape` whose reference point is c and unit axis `axis`
/// (radius and edge_radius as the shape uses them; the plane ignores both).
GapPoint rigid_gap(ContactShape shape, const Vec3& c, const Vec3& axis, double radius, double edge_radius,
                   const Vec3& x);
/// Distance of x from the body's axis line through c (0 for the plane).
double radial_distance(ContactShape shape, const Vec3& c, const Vec3& axis, const Vec3& x);

}  // namespace tmlab
