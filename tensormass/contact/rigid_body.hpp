// Rigid analytic bodies for node-to-rigid contact (docs/contact.md): a sphere, a flat cylindrical
// punch (with an optional edge radius) and an infinite plane (a platen), each translated by a
// prescribed displacement history  c(t) = c_0 + d f(t)  (d a vector, f a TimeFunction; t explicit).
//
// Each body answers, for a point x of the sample, the signed gap g(x) (the signed distance to the
// body's surface: g > 0 outside the body, g < 0 inside), the outward unit normal n = dg/dx of the
// body at its closest point y = x - g n, and the Hessian H = d^2 g / dx^2 (the curvature term of the
// contact tangent). g is a true signed distance for all three, so |dg/dx| = 1 wherever it is smooth.
//
// Shapes, with c the body's reference point at time t and a its unit axis:
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

#include "core/config/time_function.hpp"
#include "core/mesh/mesh.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>

namespace tmlab::tm {

/// The gap of one point against a body: signed distance, outward normal, closest point, Hessian.
struct GapPoint {
  double g = 0.0;               ///< signed gap, metres (< 0: the point is inside the body)
  Vec3 normal = Vec3::UnitZ();  ///< outward unit normal of the body = dg/dx
  Vec3 closest = Vec3::Zero();  ///< closest point on the body's surface, x - g n
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();  ///< d^2 g / dx^2
};

enum class RigidShape { Sphere, Punch, Plane };
enum class ContactMode {
  Frictionless,  ///< unilateral, g >= 0, normal force only
  Bonded,        ///< a node that touches sticks: all three components follow the body (glue)
};

struct RigidBody {
  std::string name;  ///< for messages and output ("indenter", "top_platen", ...)
  /// Where the body was given, for messages ("case.json: key 'contact.bodies[0]'"); may be empty.
  std::string origin;
  RigidShape shape = RigidShape::Plane;
  ContactMode mode = ContactMode::Frictionless;
  Vec3 reference = Vec3::Zero();     ///< c_0: sphere centre, punch face centre, a point of the plane
  Vec3 axis = -Vec3::UnitZ();        ///< unit; plane: outward normal; punch: face normal into the sample
  double radius = 0.0;               ///< sphere / punch radius R, metres
  double edge_radius = 0.0;          ///< punch rim radius rho in [0, R] (0: sharp edge)
  Vec3 displacement = Vec3::Zero();  ///< d: translation at f(t) = 1
  TimeFunction function = TimeFunction::constant(1.0);  ///< f(t)

  static RigidBody sphere(std::string name, const Vec3& centre, double radius,
                          const Vec3& axis = -Vec3::UnitZ());
  static RigidBody punch(std::string name, const Vec3& face_centre, const Vec3& axis, double radius,
                         double edge_radius = 0.0);
  static RigidBody plane(std::string name, const Vec3& point, const Vec3& normal);

  /// Throws tmlab::Error naming the body unless the axis is a non-zero finite vector (normalised
  /// here), radii are finite and positive (edge radius in [0, R]) and the motion is finite.
  void validate();

  /// c(t) = c_0 + d f(t).
  Vec3 position(double t) const { return reference + displacement * function(t); }
  /// The gap of x against the body at its position at time t.
  GapPoint gap(const Vec3& x, double t) const;
  /// True for the sphere and the punch (their contact radius is measured from the axis).
  bool axisymmetric() const { return shape != RigidShape::Plane; }
  /// Distance of x from the body's axis line through c(t) (0 for the plane).
  double radial_distance(const Vec3& x, double t) const;
  /// Axis-aligned box holding every point with g <= margin (infinite where unbounded).
  void bounding_box(double t, double margin, Vec3& lo, Vec3& hi) const;
  /// "sphere", "punch" or "plane".
  const char* shape_name() const;
  /// The body in messages: "<origin> (sphere 'indenter')", or "contact body 'indenter' (sphere)".
  std::string label() const;
};

/// The gap functions of the three shapes in the body frame (x relative to the reference point).
GapPoint sphere_gap(const Vec3& x_rel, double radius);
GapPoint plane_gap(const Vec3& x_rel, const Vec3& normal);
GapPoint punch_gap(const Vec3& x_rel, const Vec3& axis, double radius, double edge_radius);

}  // namespace tmlab::tm
