#include "tensormass/contact/rigid_body.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tmlab::tm {

namespace {
std::string body_label(const RigidBody& b) { return b.label(); }
}  // namespace

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
  return rigid_gap(shape, position(t), axis, radius, edge_radius, x);
}

double RigidBody::radial_distance(const Vec3& x, double t) const {
  return tmlab::radial_distance(shape, position(t), axis, x);
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
