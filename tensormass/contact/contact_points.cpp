// The contact points of a surface: see contact_points.hpp.
#include "tensormass/contact/contact_points.hpp"

#include "core/mesh/triangle_quadrature.hpp"

#include <algorithm>

namespace tmlab::tm {

Vec3 ContactPoints::position(const VecX& u, Index q) const {
  const std::size_t qq = static_cast<std::size_t>(q);
  if (u.size() == 0) return rest[qq];
  if (nodal) return rest[qq] + u.segment<3>(3 * static_cast<Eigen::Index>(node[qq]));
  Vec3 du = Vec3::Zero();
  for (Index i = start[qq]; i < start[qq + 1]; ++i)
    du += shape[static_cast<std::size_t>(i)] *
          u.segment<3>(3 * static_cast<Eigen::Index>(node[static_cast<std::size_t>(i)]));
  return rest[qq] + du;
}

std::vector<Vec3> ContactPoints::positions(const VecX& u) const {
  std::vector<Vec3> x(weight.size());
  for (Index q = 0; q < size(); ++q) x[static_cast<std::size_t>(q)] = position(u, q);
  return x;
}

double ContactPoints::contact_area(const ContactSurface& surface, Index q, const Vec3& n) const {
  if (nodal) return surface.contact_area(q, n);
  const std::size_t f = static_cast<std::size_t>(face[static_cast<std::size_t>(q)]);
  return weight[static_cast<std::size_t>(q)] * std::max(0.0, -surface.face_normal[f].dot(n));
}

ContactPoints ContactPoints::at_nodes(const Mesh& mesh, const ContactSurface& surface) {
  ContactPoints p;
  p.nodal = true;
  p.num_nodes = mesh.num_points();
  p.start.resize(surface.nodes.size() + 1);
  for (std::size_t k = 0; k <= surface.nodes.size(); ++k) p.start[k] = static_cast<Index>(k);
  p.node = surface.nodes;
  p.shape.assign(surface.nodes.size(), 1.0);
  p.weight.assign(surface.nodes.size(), 1.0);
  p.face.assign(surface.nodes.size(), -1);
  for (Index n : surface.nodes) p.rest.push_back(mesh.points[static_cast<std::size_t>(n)]);
  p.nodes = surface.nodes;
  p.group = p.start;
  p.group_area.assign(surface.nodes.size(), 1.0);
  return p;
}

ContactPoints ContactPoints::at_face_quadrature(const QuadraticMesh& qm, const ContactSurface& surface) {
  ContactPoints p;
  p.nodal = false;
  p.num_nodes = qm.num_points();
  p.start.push_back(0);
  p.group.push_back(0);
  const auto rule = triangle_rule_degree4();
  for (std::size_t f = 0; f < surface.faces.size(); ++f) {
    const Tri6 t = qm.triangle(surface.faces[f]);
    double area = 0.0;
    for (const TrianglePoint& r : rule) {
      const auto n = tri6_shape(r.l1, r.l2);
      Vec3 x = Vec3::Zero();
      for (std::size_t a = 0; a < 6; ++a) {
        p.node.push_back(t[a]);
        p.shape.push_back(n[a]);
        x += n[a] * qm.points[static_cast<std::size_t>(t[a])];
      }
      p.start.push_back(static_cast<Index>(p.node.size()));
      p.weight.push_back(r.weight * surface.face_area[f]);
      area += p.weight.back();
      p.rest.push_back(x);
      p.face.push_back(static_cast<Index>(f));
    }
    p.group.push_back(static_cast<Index>(p.weight.size()));
    p.group_area.push_back(area);
  }
  p.nodes = p.node;
  std::sort(p.nodes.begin(), p.nodes.end());
  p.nodes.erase(std::unique(p.nodes.begin(), p.nodes.end()), p.nodes.end());
  return p;
}

}  // namespace tmlab::tm
