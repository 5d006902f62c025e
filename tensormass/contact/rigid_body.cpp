#include "tensormass/contact/rigid_body.hpp"

#include "core/base/error.hpp"

#include <cmath>
#include <limits>

namespace tmlab::tm {

namespace {
using Mat3 = Eigen::Matrix3d;

/// A unit vector perpendicular to a (for the degenerate on-axis directions).
Vec3 any_perpendicular(const Vec3& a) {
  const Vec3 trial = std::abs(a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return (trial - trial.dot(a) * a).normalized();
}

std::string body_label(const RigidBody& b) { return b.label(); }
}  // namespace

GapPoint sphere_gap(const Vec3& x, double radius) {
  GapPoint p;
  const double d = x.norm();
  // At the centre the direction is undefined (a point deeper than R inside the sphere): any unit
  // vector is a valid subgradient; take +z.
  p.normal = d > 0.0 ? Vec3(x / d) : Vec3::UnitZ();
  p.g = d - radius;
  p.closest = radius * p.normal;
  if (d > 0.0) p.hessian = (Mat3::Identity() - p.normal * p.normal.transpose()) / d;
  return p;
}

GapPoint plane_gap(const Vec3& x, const Vec3& normal) {
  GapPoint p;
  p.normal = normal;
  p.g = x.dot(normal);
  p.closest = x - p.g * normal;
  return p;  // H = 0
}

GapPoint punch_gap(const Vec3& x, const Vec3& a, double radius, double rho) {
  // Cylindrical coordinates about the axis: s along a, r radial with unit e_r, hoop e_theta.
  const double s = x.dot(a);
  const Vec3 radial = x - s * a;
  const double r = radial.norm();
  const bool on_axis = !(r > 1e-300);
  const Vec3 er = on_axis ? any_perpendicular(a) : Vec3(radial / r);
  const Vec3 et = a.cross(er);
  // Core K = {s' <= 0, r <= rc} with s' = s + rho, rc = R - rho; g = dist_K - rho.
  const double ds = s + rho;
  const double dr = r - radius + rho;
  GapPoint p;
  Mat3 H = Mat3::Zero();
  // Hessian of r: e_theta e_theta^T / r (the hoop curvature); skipped exactly on the axis.
  const Mat3 hoop = on_axis ? Mat3::Zero() : Mat3(et * et.transpose() / r);
  double d;
  if (dr > 0.0 && ds > 0.0) {
    // Beyond the rim: distance to the rim circle (torus-like level sets). In the (r, s) plane the
    // Hessian is t t^T / d (t the in-plane tangent); the hoop direction adds (dd/dr) / r.
    d = std::hypot(dr, ds);
    p.normal = (dr * er + ds * a) / d;
    const Vec3 tangent = (ds * er - dr * a) / d;
    H = tangent * tangent.transpose() / d + (dr / d) * hoop;
  } else if (dr > 0.0 || (ds <= 0.0 && dr > ds)) {
    // Beside the cylinder (outside), or inside and closer to the side than to the face.
    d = dr;
    p.normal = er;
    H = hoop;
  } else {
    // Above the face (outside), or inside and closer to the face.
    d = ds;
    p.normal = a;
  }
  p.g = d - rho;
  p.closest = x - p.g * p.normal;
  p.hessian = H;
  return p;
}

RigidBody RigidBody::sphere(std::string name, const Vec3& centre, double radius, const Vec3& axis) {
  RigidBody b;
  b.name = std::move(name);
  b.shape = RigidShape::Sphere;
  b.reference = centre;
  b.radius = radius;
  b.axis = axis;
  b.validate();
  return b;
}

RigidBody RigidBody::punch(std::string name, const Vec3& face_centre, const Vec3& axis, double radius,
                           double edge_radius) {
  RigidBody b;
  b.name = std::move(name);
  b.shape = RigidShape::Punch;
  b.reference = face_centre;
  b.axis = axis;
  b.radius = radius;
  b.edge_radius = edge_radius;
  b.validate();
  return b;
}

RigidBody RigidBody::plane(std::string name, const Vec3& point, const Vec3& normal) {
  RigidBody b;
  b.name = std::move(name);
  b.shape = RigidShape::Plane;
  b.reference = point;
  b.axis = normal;
  b.validate();
  return b;
}

std::string RigidBody::label() const {
  if (!origin.empty()) return origin + " (" + shape_name() + " '" + name + "')";
  return std::string("contact body '") + name + "' (" + shape_name() + ")";
}

const char* RigidBody::shape_name() const {
  switch (shape) {
    case RigidShape::Sphere:
      return "sphere";
    case RigidShape::Punch:
      return "punch";
    case RigidShape::Plane:
      return "plane";
  }
  return "?";
}

void RigidBody::validate() {
  if (!reference.allFinite()) throw Error(body_label(*this) + ": reference point is not finite");
  if (!displacement.allFinite()) throw Error(body_label(*this) + ": displacement is not finite");
  const double n = axis.norm();
  if (!std::isfinite(n) || n <= 0.0)
    throw Error(body_label(*this) + ": axis/normal must be a non-zero finite vector");
  axis /= n;
  if (shape != RigidShape::Plane && !(std::isfinite(radius) && radius > 0.0))
    throw Error(body_label(*this) + ": radius must be > 0 (got " + std::to_string(radius) + ")");
  if (shape == RigidShape::Punch &&
      !(std::isfinite(edge_radius) && edge_radius >= 0.0 && edge_radius <= radius))
    throw Error(body_label(*this) + ": edge_radius must lie in [0, radius] (got " +
                std::to_string(edge_radius) + ")");
}

GapPoint RigidBody::gap(const Vec3& x, double t) const {
  const Vec3 c = position(t);
  GapPoint p;
  switch (shape) {
    case RigidShape::Sphere:
      p = sphere_gap(x - c, radius);
      break;
    case RigidShape::Punch:
      p = punch_gap(x - c, axis, radius, edge_radius);
      break;
    case RigidShape::Plane:
      p = plane_gap(x - c, axis);
      break;
  }
  p.closest += c;
  return p;
}

double RigidBody::radial_distance(const Vec3& x, double t) const {
  if (shape == RigidShape::Plane) return 0.0;
  const Vec3 rel = x - position(t);
  return (rel - rel.dot(axis) * axis).norm();
}

void RigidBody::bounding_box(double t, double margin, Vec3& lo, Vec3& hi) const {
  const double inf = std::numeric_limits<double>::infinity();
  const Vec3 c = position(t);
  lo = Vec3::Constant(-inf);
  hi = Vec3::Constant(inf);
  switch (shape) {
    case RigidShape::Sphere:
      lo = c.array() - (radius + margin);
      hi = c.array() + (radius + margin);
      break;
    case RigidShape::Punch:
      // {s <= margin, r <= R + margin}: bounded across the axis, unbounded behind the face.
      for (int j = 0; j < 3; ++j) {
        const double aj = axis(j);
        const double across = (radius + margin) * std::sqrt(std::max(0.0, 1.0 - aj * aj));
        const double front = c(j) + margin * aj;
        if (aj > 0.0) {
          hi(j) = front + across;
        } else if (aj < 0.0) {
          lo(j) = front - across;
        } else {
          lo(j) = c(j) - across;
          hi(j) = c(j) + across;
        }
      }
      break;
    case RigidShape::Plane:
      // {(x - c).a <= margin}: a slab bound only along an axis-aligned normal.
      for (int j = 0; j < 3; ++j) {
        const bool aligned = std::abs(std::abs(axis(j)) - 1.0) == 0.0;
        if (!aligned) continue;
        if (axis(j) > 0.0)
          hi(j) = c(j) + margin;
        else
          lo(j) = c(j) - margin;
      }
      break;
  }
}

}  // namespace tmlab::tm
