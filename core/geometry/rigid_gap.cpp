#include "core/geometry/rigid_gap.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace tmlab {

namespace {
using Mat3 = Eigen::Matrix3d;

/// A unit vector perpendicular to a (for the degenerate on-axis directions).
Vec3 any_perpendicular(const Vec3& a) {
  const Vec3 trial = std::abs(a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return (trial - trial.dot(a) * a).normalized();
}
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

GapPoint rigid_gap(ContactShape shape, const Vec3& c, const Vec3& axis, double radius, double edge_radius,
                   const Vec3& x) {
  GapPoint p;
  switch (shape) {
    case ContactShape::Sphere:
      p = sphere_gap(x - c, radius);
      break;
    case ContactShape::Punch:
      p = punch_gap(x - c, axis, radius, edge_radius);
      break;
    case ContactShape::Plane:
      p = plane_gap(x - c, axis);
      break;
  }
  p.closest += c;
  return p;
}

double radial_distance(ContactShape shape, const Vec3& c, const Vec3& axis, const Vec3& x) {
  if (shape == ContactShape::Plane) return 0.0;
  const Vec3 rel = x - c;
  return (rel - rel.dot(axis) * axis).norm();
}

}  // namespace tmlab
