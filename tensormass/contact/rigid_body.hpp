// Rigid analytic bodies for node-to-rigid contact (docs/contact.md): a sphere, a flat cylindrical
// punch (with an optional edge radius) and an infinite plane (a platen), each translated by a
// prescribed displacement history  c(t) = c_0 + d f(t)  (d a vector, f a TimeFunction; t explicit).
//
// Each body answers, for a point x of the sample, the signed gap g(x), the outward unit normal
// n = dg/dx at its closest point and the Hessian d^2 g / dx^2: the one copy of that geometry
// (core/geometry/rigid_gap.hpp, which the deal.II reference uses too). The body's description is the
// case file's (ContactBodySpec, core/config/contact_spec.hpp), validated, with where it was given.
#pragma once

#include "core/config/contact_spec.hpp"
#include "core/geometry/rigid_gap.hpp"
#include "core/mesh/mesh.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>

namespace tmlab::tm {

/// The shapes and contact modes are the case file's (core/config/contact_spec.hpp).
using RigidShape = ContactShape;
using ContactMode = ContactBodyMode;

/// A rigid body: the case file's description (shape, mode, c_0 = reference, unit axis, radii, motion
/// c(t) = reference + displacement f(t)) with its validation, messages and gap.
struct RigidBody : ContactBodySpec {
  /// Where the body was given, for messages ("case.json: key 'contact.bodies[0]'"); may be empty.
  std::string origin;

  static RigidBody sphere(std::string name, const Vec3& centre, double radius,
                          const Vec3& axis = -Vec3::UnitZ());
  static RigidBody punch(std::string name, const Vec3& face_centre, const Vec3& axis, double radius,
                         double edge_radius = 0.0);
  static RigidBody plane(std::string name, const Vec3& point, const Vec3& normal);

  /// Throws tmlab::Error naming the body unless the axis is a non-zero finite vector (normalised
  /// here), radii are finite and positive (edge radius in [0, R]) and the motion is finite.
  void validate();

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

}  // namespace tmlab::tm
