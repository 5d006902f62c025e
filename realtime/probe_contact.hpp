// The probe: a rigid sphere of radius R pressed into the surface nodes of a mesh by PENALTY contact
// (node-to-rigid, frictionless), so an explicit step can apply it without a solve and the haptic
// coupling gets a contact stiffness.
//
// For a surface node at x_i = X_i + u_i and the probe centred at c, with the gap of tensormass/contact
// (sphere_gap: g_i = |x_i - c| - R, n_i = (x_i - c)/|x_i - c| the outward normal of the probe):
//   force on the node   f_i = eps <-g_i>+ n_i          (pushes the node out of the probe)
//   force on the probe  F   = -sum_i f_i
//   penalty energy      W_c = eps/2 sum_i <-g_i>+^2     (so f_int += dW_c/du = -f_i)
//   tangent             dW_c^2/du_i^2 = eps (n_i n_i^T + g_i H_i),  H_i = (I - n_i n_i^T)/|x_i - c|
// for the nodes with g_i < 0. eps (N/m per node) is the penalty stiffness; the probe penetrates by
// O(F_node/eps). Only boundary nodes (faces used by one tet) are candidates; they are scanned in a
// flat loop (a few hundred nodes on the liver: cheaper than a grid query, and allocation-free).
//
// ProbePenaltyModel adds W_c to any ElasticModel (energy, force, tangent; history forwarded), with
// the probe centre set by the caller before each evaluation: the library's explicit and implicit
// solvers then run the same contact problem offline (the reference of the real-time control step).
#pragma once

#include "core/mesh/mesh.hpp"
#include "tensormass/kernels/elastic_model.hpp"

#include <vector>

namespace tmlab::rt {

using tm::SpMat;
using tm::VecX;

class ProbeContact {
 public:
  /// Extracts the boundary nodes of `mesh`. Throws tmlab::Error for radius or stiffness <= 0.
  ProbeContact(const Mesh& mesh, double radius, double stiffness);

  double radius() const { return radius_; }
  double stiffness() const { return eps_; }  ///< eps, N/m per node
  const std::vector<Index>& surface_nodes() const { return nodes_; }
  const std::vector<Vec3>& surface_rest() const { return rest_; }  ///< X_i of surface_nodes()

  /// f += scale * (the contact forces on the nodes) at displacement u for the probe at c; returns
  /// the force on the probe (-sum f_i) and, when `active` is given, the number of nodes in contact.
  /// Allocation-free.
  Vec3 add_node_forces(const VecX& u, const Vec3& c, double scale, VecX& f, int* active = nullptr) const;
  /// eps/2 sum <-g>^2, J.
  double energy(const VecX& u, const Vec3& c) const;
  /// Kv += K_c v.
  void add_tangent_apply(const VecX& u, const Vec3& c, const VecX& v, VecX& Kv) const;
  /// K += K_c (the 3x3 diagonal blocks, which a mesh-graph pattern holds).
  void add_tangent(const VecX& u, const Vec3& c, SpMat& K) const;

 private:
  double radius_, eps_;
  std::vector<Index> nodes_;
  std::vector<Vec3> rest_;
};

/// base model + probe penalty energy (see above). The probe centre is state of the decorator.
class ProbePenaltyModel final : public tm::ElasticModel {
 public:
  ProbePenaltyModel(tm::ElasticModel& base, const ProbeContact& contact) : base_(base), contact_(contact) {}
  void set_probe(const Vec3& c) { c_ = c; }
  const Vec3& probe() const { return c_; }

  Index num_nodes() const override { return base_.num_nodes(); }
  double energy(const VecX& u) const override { return base_.energy(u) + contact_.energy(u, c_); }
  void internal_force(const VecX& u, VecX& f) const override;
  void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const override;
  void tangent(const VecX& u, SpMat& K) const override;
  bool has_history() const override { return base_.has_history(); }
  bool energy_is_potential() const override { return base_.energy_is_potential(); }
  void begin_step(double dt) override { base_.begin_step(dt); }
  void commit_step(const VecX& u) override { base_.commit_step(u); }

 private:
  tm::ElasticModel& base_;
  const ProbeContact& contact_;
  Vec3 c_ = Vec3::Zero();
};

}  // namespace tmlab::rt
