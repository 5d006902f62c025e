#include "reference_fem/dealii/contact_geometry.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"

#include <algorithm>
#include <cmath>

namespace tmlab::ref {

Vec3 body_axis(const ContactBodySpec& body) { return body.axis.normalized(); }

GapPoint body_gap(const ContactBodySpec& body, const Vec3& x, double t) {
  return rigid_gap(body.shape, body.position(t), body_axis(body), body.radius, body.edge_radius, x);
}

double body_radial_distance(const ContactBodySpec& body, const Vec3& x, double t) {
  return radial_distance(body.shape, body.position(t), body_axis(body), x);
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
