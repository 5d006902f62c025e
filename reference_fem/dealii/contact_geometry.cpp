#include "reference_fem/dealii/contact_geometry.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"

#include <algorithm>
#include <cmath>

namespace tmlab::ref {

namespace {

using Mat3 = Eigen::Matrix3d;

/// A unit vector perpendicular to a (the radial direction of a point exactly on the axis).
Vec3 any_perpendicular(const Vec3& a) {
  const Vec3 trial = std::abs(a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return (trial - trial.dot(a) * a).normalized();
}

BodyGap sphere(const Vec3& x, double radius) {
  BodyGap p;
  const double d = x.norm();
  p.normal = d > 0.0 ? Vec3(x / d) : Vec3::UnitZ();  // at the centre any direction is a subgradient
  p.g = d - radius;
  p.closest = radius * p.normal;
  if (d > 0.0) p.hessian = (Mat3::Identity() - p.normal * p.normal.transpose()) / d;
  return p;
}

BodyGap plane(const Vec3& x, const Vec3& normal) {
  BodyGap p;
  p.normal = normal;
  p.g = x.dot(normal);
  p.closest = x - p.g * normal;
  return p;
}

/// Cylindrical coordinates about the axis: s along a, r radial (e_r), hoop e_theta; the core
/// K = {s + rho <= 0, r <= R - rho}, g = dist_K - rho.
BodyGap punch(const Vec3& x, const Vec3& a, double radius, double rho) {
  const double s = x.dot(a);
  const Vec3 radial = x - s * a;
  const double r = radial.norm();
  const bool on_axis = !(r > 1e-300);
  const Vec3 er = on_axis ? any_perpendicular(a) : Vec3(radial / r);
  const Vec3 et = a.cross(er);
  const double ds = s + rho, dr = r - radius + rho;
  const Mat3 hoop = on_axis ? Mat3::Zero() : Mat3(et * et.transpose() / r);
  BodyGap p;
  double d;
  if (dr > 0.0 && ds > 0.0) {  // beyond the rim: distance to the rim circle
    d = std::hypot(dr, ds);
    p.normal = (dr * er + ds * a) / d;
    const Vec3 tangent = (ds * er - dr * a) / d;
    p.hessian = tangent * tangent.transpose() / d + (dr / d) * hoop;
  } else if (dr > 0.0 || (ds <= 0.0 && dr > ds)) {  // beside the side (or inside, nearer the side)
    d = dr;
    p.normal = er;
    p.hessian = hoop;
  } else {  // above the face (or inside, nearer the face)
    d = ds;
    p.normal = a;
  }
  p.g = d - rho;
  p.closest = x - p.g * p.normal;
  return p;
}

}  // namespace

Vec3 body_axis(const ContactBodySpec& body) { return body.axis.normalized(); }

BodyGap body_gap(const ContactBodySpec& body, const Vec3& x, double t) {
  const Vec3 c = body.position(t);
  BodyGap p;
  switch (body.shape) {
    case ContactShape::Sphere:
      p = sphere(x - c, body.radius);
      break;
    case ContactShape::Punch:
      p = punch(x - c, body_axis(body), body.radius, body.edge_radius);
      break;
    case ContactShape::Plane:
      p = plane(x - c, body_axis(body));
      break;
  }
  p.closest += c;
  return p;
}

double body_radial_distance(const ContactBodySpec& body, const Vec3& x, double t) {
  if (body.shape == ContactShape::Plane) return 0.0;
  const Vec3 a = body_axis(body), rel = x - body.position(t);
  return (rel - rel.dot(a) * a).norm();
}

double ContactBoundary::contact_area(std::size_t k, const Vec3& n) const {
  double a = 0.0;
  for (Index i = face_start[k]; i < face_start[k + 1]; ++i) {
    const std::size_t f = static_cast<std::size_t>(node_faces[static_cast<std::size_t>(i)]);
    a += face_area[f] / 3.0 * std::max(0.0, -face_normal[f].dot(n));
  }
  return a;
}

ContactBoundary ContactBoundary::extract(const Mesh& mesh) {
  ContactBoundary b;
  const std::vector<Tri> faces = boundary_faces(mesh);
  if (faces.empty()) throw Error("contact: the mesh has no boundary face (no tetrahedra?)");
  std::vector<Index> local(static_cast<std::size_t>(mesh.num_points()), -1);
  for (const Tri& f : faces)
    for (Index n : f) local[static_cast<std::size_t>(n)] = 0;
  for (Index i = 0; i < mesh.num_points(); ++i)
    if (local[static_cast<std::size_t>(i)] == 0) {
      local[static_cast<std::size_t>(i)] = static_cast<Index>(b.nodes.size());
      b.nodes.push_back(i);
    }
  b.face_start.assign(b.nodes.size() + 1, 0);
  double edges = 0.0;
  for (const Tri& f : faces) {
    const Vec3& p0 = mesh.points[static_cast<std::size_t>(f[0])];
    const Vec3& p1 = mesh.points[static_cast<std::size_t>(f[1])];
    const Vec3& p2 = mesh.points[static_cast<std::size_t>(f[2])];
    const Vec3 cross = (p1 - p0).cross(p2 - p0);
    const double area = 0.5 * cross.norm();
    b.face_area.push_back(area);
    b.face_normal.push_back(area > 0.0 ? Vec3(cross.normalized()) : Vec3::Zero());
    for (Index n : f) ++b.face_start[static_cast<std::size_t>(local[static_cast<std::size_t>(n)]) + 1];
    edges += (p1 - p0).norm() + (p2 - p1).norm() + (p0 - p2).norm();
  }
  for (std::size_t k = 0; k < b.nodes.size(); ++k) b.face_start[k + 1] += b.face_start[k];
  b.node_faces.resize(static_cast<std::size_t>(b.face_start.back()));
  std::vector<Index> fill(b.face_start.begin(), b.face_start.end() - 1);
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (Index n : faces[f]) {
      const std::size_t k = static_cast<std::size_t>(local[static_cast<std::size_t>(n)]);
      b.node_faces[static_cast<std::size_t>(fill[k]++)] = static_cast<Index>(f);
    }
  b.mean_edge = edges / (3.0 * static_cast<double>(faces.size()));
  return b;
}

}  // namespace tmlab::ref
