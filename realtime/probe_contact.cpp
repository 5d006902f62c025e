#include "realtime/probe_contact.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"

#include <cmath>

namespace tmlab::rt {

ProbeContact::ProbeContact(const Mesh& mesh, double radius, double stiffness)
    : radius_(radius), eps_(stiffness), nodes_(boundary_nodes(mesh)) {
  if (!(radius > 0.0) || !std::isfinite(radius)) throw Error("probe: radius must be > 0");
  if (!(stiffness > 0.0) || !std::isfinite(stiffness)) throw Error("probe: penalty stiffness must be > 0");
  if (nodes_.empty()) throw Error("probe: the mesh has no boundary node");
  rest_.reserve(nodes_.size());
  for (Index i : nodes_) rest_.push_back(mesh.points[static_cast<std::size_t>(i)]);
}

Vec3 ProbeContact::add_node_forces(const VecX& u, const Vec3& c, double scale, VecX& f, int* active) const {
  Vec3 probe = Vec3::Zero();
  int count = 0;
  const double r2 = radius_ * radius_;
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const Eigen::Index d = 3 * static_cast<Eigen::Index>(nodes_[k]);
    const Vec3 rel = rest_[k] + u.segment<3>(d) - c;
    const double dist2 = rel.squaredNorm();
    if (dist2 >= r2) continue;
    const double dist = std::sqrt(dist2);
    if (dist == 0.0) continue;  // the node at the centre: no direction (cannot happen for eps large)
    const Vec3 fi = (eps_ * (radius_ - dist) / dist) * rel;  // eps <-g> n
    f.segment<3>(d) += scale * fi;
    probe -= fi;
    ++count;
  }
  if (active) *active = count;
  return probe;
}

double ProbeContact::energy(const VecX& u, const Vec3& c) const {
  double w = 0.0;
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const double g = (rest_[k] + u.segment<3>(3 * static_cast<Eigen::Index>(nodes_[k])) - c).norm() - radius_;
    if (g < 0.0) w += 0.5 * eps_ * g * g;
  }
  return w;
}

namespace {
/// eps (n n^T + g H) for a node in contact (g < 0), H = (I - n n^T)/dist.
Eigen::Matrix3d node_tangent(const Vec3& rel, double radius, double eps) {
  const double dist = rel.norm();
  const Vec3 n = rel / dist;
  const double g = dist - radius;
  const Eigen::Matrix3d nn = n * n.transpose();
  return eps * (nn + (g / dist) * (Eigen::Matrix3d::Identity() - nn));
}
}  // namespace

void ProbeContact::add_tangent_apply(const VecX& u, const Vec3& c, const VecX& v, VecX& Kv) const {
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const Eigen::Index d = 3 * static_cast<Eigen::Index>(nodes_[k]);
    const Vec3 rel = rest_[k] + u.segment<3>(d) - c;
    const double dist = rel.norm();
    if (dist >= radius_ || dist == 0.0) continue;
    Kv.segment<3>(d) += node_tangent(rel, radius_, eps_) * v.segment<3>(d);
  }
}

void ProbeContact::add_tangent(const VecX& u, const Vec3& c, SpMat& K) const {
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const Eigen::Index d = 3 * static_cast<Eigen::Index>(nodes_[k]);
    const Vec3 rel = rest_[k] + u.segment<3>(d) - c;
    const double dist = rel.norm();
    if (dist >= radius_ || dist == 0.0) continue;
    const Eigen::Matrix3d B = node_tangent(rel, radius_, eps_);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) K.coeffRef(d + a, d + b) += B(a, b);
  }
}

void ProbePenaltyModel::internal_force(const VecX& u, VecX& f) const {
  base_.internal_force(u, f);
  contact_.add_node_forces(u, c_, -1.0, f);  // f_int += dW_c/du = -f_i
}

void ProbePenaltyModel::tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const {
  base_.tangent_apply(u, v, Kv);
  contact_.add_tangent_apply(u, c_, v, Kv);
}

void ProbePenaltyModel::tangent(const VecX& u, SpMat& K) const {
  base_.tangent(u, K);
  contact_.add_tangent(u, c_, K);
}

}  // namespace tmlab::rt
