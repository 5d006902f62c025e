#include "tensormass/system/external_loads.hpp"

#include "core/mesh/triangle_quadrature.hpp"

#include "core/base/error.hpp"

#include <Eigen/Geometry>

#include <cassert>

namespace tmlab::tm {

namespace {
Eigen::Matrix3d cross_matrix(const Vec3& a) {
  Eigen::Matrix3d m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}
}  // namespace

ExternalLoads::ExternalLoads(const Mesh& mesh, VecX lumped_node_mass)
    : mesh_(&mesh), node_mass_(std::move(lumped_node_mass)) {
  assert(node_mass_.size() == mesh.num_points());
}

void ExternalLoads::add(NodalForce f) {
  if (f.nodes.empty()) throw Error("nodal force '" + f.name + "' selects no nodes (check its node selector)");
  nodal_.push_back(std::move(f));
}
void ExternalLoads::add(SurfacePressure p) {
  if (p.faces.empty())
    throw Error("pressure '" + p.name + "' selects no boundary faces (check its face selector)");
  pressure_.push_back(std::move(p));
}
void ExternalLoads::add(SurfaceTraction t) {
  if (t.faces.empty())
    throw Error("traction '" + t.name + "' selects no boundary faces (check its face selector)");
  traction_.push_back(std::move(t));
}
void ExternalLoads::add(Gravity g) { gravity_.push_back(std::move(g)); }

void ExternalLoads::add(QuadraticFaceLoad q) {
  if (q.faces.empty())
    throw Error("surface load '" + q.name + "' selects no boundary faces (check its face selector)");
  for (const Tri6& f : q.faces)
    for (Index n : f)
      if (n < 0 || n >= mesh_->num_points())
        throw Error("surface load '" + q.name + "': a face names node " + std::to_string(n) +
                    " out of range");
  quadratic_.push_back(std::move(q));
}

bool ExternalLoads::has_follower() const {
  for (const auto& p : pressure_)
    if (p.follower) return true;
  return false;
}

void ExternalLoads::assemble(const VecX& u, double t, VecX& f) const {
  assert(mesh_ != nullptr);
  const Index n = mesh_->num_points();
  f.setZero(3 * n);
  for (const auto& nf : nodal_) {
    const Vec3 per_node = nf.force * (nf.function(t) / static_cast<double>(nf.nodes.size()));
    for (Index i : nf.nodes) f.segment<3>(3 * i) += per_node;
  }
  for (const auto& g : gravity_) {
    const Vec3 a = g.acceleration * g.function(t);
    for (Index i = 0; i < n; ++i) f.segment<3>(3 * i) += node_mass_[i] * a;
  }
  for (const auto& tr : traction_) {
    // Dead traction: each node of a face carries traction * (reference area) / 3.
    const Vec3 tt = tr.traction * tr.function(t);
    for (const Tri& tri : tr.faces) {
      const Vec3& x0 = mesh_->points[tri[0]];
      const double area = 0.5 * (mesh_->points[tri[1]] - x0).cross(mesh_->points[tri[2]] - x0).norm();
      for (int a = 0; a < 3; ++a) f.segment<3>(3 * tri[a]) += (area / 3.0) * tt;
    }
  }
  for (const auto& p : pressure_) {
    const double pt = p.pressure * p.function(t);
    if (pt == 0.0) continue;
    for (const Tri& tri : p.faces) {
      // Area vector n = 1/2 (x1 - x0) x (x2 - x0), outward; each node carries -p n / 3.
      Vec3 x[3];
      for (int a = 0; a < 3; ++a) {
        x[a] = mesh_->points[tri[a]];
        if (p.follower) x[a] += u.segment<3>(3 * tri[a]);
      }
      const Vec3 area = 0.5 * (x[1] - x[0]).cross(x[2] - x[0]);
      for (int a = 0; a < 3; ++a) f.segment<3>(3 * tri[a]) -= (pt / 3.0) * area;
    }
  }
  if (!quadratic_.empty()) assemble_quadratic(t, f);
}

void ExternalLoads::assemble_quadratic(double t, VecX& f) const {
  const auto rule = triangle_rule_degree4();
  for (const auto& q : quadratic_) {
    const double s = q.function(t);
    const double pt = q.pressure * s;
    const Vec3 tt = q.traction * s;
    for (const Tri6& tri : q.faces) {
      for (const TrianglePoint& r : rule) {
        // n dA = (dx/dl1 x dx/dl2) dl1 dl2 over the unit right triangle (area 1/2).
        const auto n = tri6_shape(r.l1, r.l2);
        const auto dn = tri6_shape_gradient(r.l1, r.l2);
        Vec3 d1 = Vec3::Zero(), d2 = Vec3::Zero();
        for (std::size_t a = 0; a < 6; ++a) {
          d1 += dn[a][0] * mesh_->points[static_cast<std::size_t>(tri[a])];
          d2 += dn[a][1] * mesh_->points[static_cast<std::size_t>(tri[a])];
        }
        const Vec3 area = 0.5 * r.weight * d1.cross(d2);
        const Vec3 load = area.norm() * tt - pt * area;
        for (std::size_t a = 0; a < 6; ++a)
          f.segment<3>(3 * static_cast<Eigen::Index>(tri[a])) += n[a] * load;
      }
    }
  }
}

void ExternalLoads::add_load_stiffness(const VecX& u, double t,
                                       std::vector<Eigen::Triplet<double>>& triplets) const {
  for (const auto& p : pressure_) {
    if (!p.follower) continue;
    const double pt = p.pressure * p.function(t);
    if (pt == 0.0) continue;
    for (const Tri& tri : p.faces) {
      Vec3 x[3];
      for (int a = 0; a < 3; ++a) x[a] = mesh_->points[tri[a]] + u.segment<3>(3 * tri[a]);
      // f_a = -(p/3) n with n = 1/2 sum_cyc x_i x x_{i+1}; dn/dx_b = 1/2 [x_{b-1} - x_{b+1}]_x.
      // Load stiffness entry: -df_a/dx_b = (p/6) [x_{b-1} - x_{b+1}]_x.
      for (int b = 0; b < 3; ++b) {
        const Eigen::Matrix3d kb = (pt / 6.0) * cross_matrix(x[(b + 2) % 3] - x[(b + 1) % 3]);
        for (int a = 0; a < 3; ++a)
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) triplets.emplace_back(3 * tri[a] + r, 3 * tri[b] + c, kb(r, c));
      }
    }
  }
}

}  // namespace tmlab::tm
