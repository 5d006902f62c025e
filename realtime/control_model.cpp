#include "realtime/control_model.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/solvers/explicit_dynamics.hpp"
#include "tensormass/system/lumped_mass.hpp"

#include <Eigen/LU>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace tmlab::rt {

ControlModel::ControlModel(const Mesh& mesh, const tm::StVenantKirchhoff& long_term,
                           const tm::PronySeries& prony, tm::ViscoelasticOptions viscoelastic, double density,
                           const std::vector<Index>& fixed_nodes, const ControlOptions& options)
    : mesh_(mesh),
      opt_(options),
      material_(long_term),
      prony_(prony),
      viscoelastic_(viscoelastic),
      fixed_nodes_(fixed_nodes) {
  if (!(opt_.dt > 0.0) || !std::isfinite(opt_.dt)) throw Error("realtime control: dt must be > 0");
  if (!(opt_.mass_damping >= 0.0)) throw Error("realtime control: mass damping must be >= 0");
  if (fixed_nodes_.empty()) throw Error("realtime control: no fixed node (the liver would float away)");
  viscoelastic_.energy_bookkeeping = false;  // the loop reports forces, not energies: no extra passes
  model_ = std::make_unique<tm::ViscoelasticStVK>(mesh_, material_, prony_, viscoelastic_);
  const Index n = mesh_.num_points();
  const VecX node_mass = tm::lumped_node_mass(mesh_, density);
  mass_ = tm::lumped_dof_mass(node_mass);
  fixed_dof_.assign(static_cast<std::size_t>(3 * n), 0);
  for (Index i : fixed_nodes_)
    for (int c = 0; c < 3; ++c) fixed_dof_[static_cast<std::size_t>(3 * i + c)] = 1;

  // Tissue limit at the instantaneous modulus (the model's trial state after construction is dt = 0,
  // the instantaneous response, so its reference tangent is the stiffest).
  DirichletCondition base;
  base.name = "base";
  base.nodes = fixed_nodes_;
  tm::MechanicalSystem system(*model_, mass_, tm::DirichletSet(n, {base}),
                              tm::ExternalLoads(mesh_, node_mass), {opt_.mass_damping, 0.0});
  const tm::StabilityEstimate est = tm::estimate_critical_time_step(system);
  dt_tissue_ = est.dt_critical;
  const double w2 = est.omega_max * est.omega_max;

  // Smallest surface-node mass and the instantaneous diagonal blocks of the surface nodes.
  const std::vector<Index> surface = boundary_nodes(mesh_);
  double m_min = std::numeric_limits<double>::infinity();
  for (Index i : surface)
    if (!fixed_dof_[static_cast<std::size_t>(3 * i)]) m_min = std::min(m_min, node_mass[i]);
  const double limit_w2 = std::pow(2.0 * opt_.stability_fraction / opt_.dt, 2);
  double eps = opt_.penalty_stiffness;
  if (eps == 0.0) {
    eps = m_min * (limit_w2 - w2);
    if (!(eps > 0.0)) {
      std::ostringstream msg;
      msg << "realtime control: dt = " << opt_.dt
          << " s leaves no room for contact: the tissue alone needs dt <= " << dt_tissue_
          << " s (times the stability fraction " << opt_.stability_fraction << ")";
      throw Error(msg.str());
    }
  }
  dt_contact_ = 2.0 / std::sqrt(w2 + eps / m_min);
  if (opt_.dt > dt_contact_) {
    std::ostringstream msg;
    msg << "realtime control: dt = " << opt_.dt
        << " s exceeds the stable step with the probe's penalty stiffness " << eps << " N/m: " << dt_contact_
        << " s (tissue alone " << dt_tissue_ << " s); lower dt or the penalty stiffness";
    throw Error(msg.str());
  }
  contact_ = std::make_unique<ProbeContact>(mesh_, opt_.probe_radius, eps);

  // K_inst = the tangent of a step of size dt at rest (the stiffness the tissue shows within a
  // step: the long-term modulus times 1 + g(dt)); G = its inverse between the surface nodes, with
  // the fixed DOFs eliminated (their rows and columns replaced by the identity, their compliance 0).
  model_->begin_step(opt_.dt);
  tm::SpMat K;
  model_->tangent(VecX::Zero(3 * n), K);
  model_->begin_step(0.0);
  const double h = opt_.coupling_horizon;
  const double mass_scale = h > 0.0 ? 1.0 / (h * h) + opt_.mass_damping / h : 0.0;
  for (Eigen::Index col = 0; col < K.outerSize(); ++col)
    for (tm::SpMat::InnerIterator it(K, col); it; ++it) {
      if (fixed_dof_[static_cast<std::size_t>(it.row())] || fixed_dof_[static_cast<std::size_t>(col)])
        it.valueRef() = it.row() == col ? 1.0 : 0.0;
      else if (it.row() == col)
        it.valueRef() += mass_scale * mass_[col];
    }
  Eigen::SimplicialLDLT<tm::SpMat> ldlt(K);
  if (ldlt.info() != Eigen::Success) throw Error("realtime control: the instantaneous tangent is singular");
  const auto& surf = contact_->surface_nodes();
  const Eigen::Index S = static_cast<Eigen::Index>(surf.size());
  G_ = Eigen::MatrixXd::Zero(3 * S, 3 * S);
  VecX e = VecX::Zero(3 * n), col(3 * n);
  for (Eigen::Index k = 0; k < S; ++k)
    for (int c = 0; c < 3; ++c) {
      const Eigen::Index d = 3 * static_cast<Eigen::Index>(surf[static_cast<std::size_t>(k)]) + c;
      if (fixed_dof_[static_cast<std::size_t>(d)]) continue;
      e[d] = 1.0;
      col = ldlt.solve(e);
      e[d] = 0.0;
      for (Eigen::Index m = 0; m < S; ++m)
        for (int r = 0; r < 3; ++r) {
          const Eigen::Index dr = 3 * static_cast<Eigen::Index>(surf[static_cast<std::size_t>(m)]) + r;
          G_(3 * m + r, 3 * k + c) = fixed_dof_[static_cast<std::size_t>(dr)] ? 0.0 : col[dr];
        }
    }

  u_ = VecX::Zero(3 * n);
  vh_ = VecX::Zero(3 * n);
  fint_ = VecX::Zero(3 * n);
  fc_ = VecX::Zero(3 * n);
  reset(Vec3::Constant(1e30));  // probe far away; callers reset with their start position
}

void ControlModel::reset(const Vec3& c0) {
  // A fresh viscoelastic model (history cleared), as tm::CentralDifference::initialize starts it:
  // begin_step(0), commit_step(u0) at u0 = 0.
  model_ = std::make_unique<tm::ViscoelasticStVK>(mesh_, material_, prony_, viscoelastic_);
  u_.setZero();
  vh_.setZero();
  steps_ = 0;
  model_->begin_step(0.0);
  model_->commit_step(u_);
  // v^{-1/2} = -dt/2 a^0 with a^0 = M^{-1}(f_c(0, c0) - f_int(0)), f_int(0) = 0 at rest.
  fc_.setZero();
  contact_->add_node_forces(u_, c0, 1.0, fc_);
  for (Eigen::Index d = 0; d < u_.size(); ++d)
    vh_[d] = fixed_dof_[static_cast<std::size_t>(d)] ? 0.0 : -0.5 * opt_.dt * fc_[d] / mass_[d];
}

Vec3 ControlModel::step(const Vec3& c) {
  const double dt = opt_.dt, a = opt_.mass_damping;
  if (steps_ > 0) {
    model_->begin_step(dt);
    model_->internal_force(u_, fint_);
    model_->commit_step(u_);
  } else {
    model_->internal_force(u_, fint_);
  }
  fc_.setZero();
  const Vec3 force = contact_->add_node_forces(u_, c, 1.0, fc_);
  const double lo = 1.0 - 0.5 * a * dt, hi = 1.0 / (1.0 + 0.5 * a * dt);
  const Eigen::Index nd = u_.size();
  for (Eigen::Index d = 0; d < nd; ++d) {
    if (fixed_dof_[static_cast<std::size_t>(d)]) {
      vh_[d] = 0.0;
      continue;
    }
    vh_[d] = (lo * vh_[d] + dt * (fc_[d] - fint_[d]) / mass_[d]) * hi;
    u_[d] += dt * vh_[d];
  }
  ++steps_;
  return force;
}

Vec3 ControlModel::contact_force(const Vec3& c, int* active) {
  fc_.setZero();
  return contact_->add_node_forces(u_, c, 1.0, fc_, active);
}

void ControlModel::fill_snapshot(const Vec3& c, ContactSnapshot& s) {
  s.step = steps_;
  s.t = time();
  s.probe = c;
  s.force = contact_force(c);
  // Active nodes and their contact tangents K_c,i = eps (n n^T + (g/dist)(I - n n^T)).
  const auto& nodes = contact_->surface_nodes();
  const auto& rest = contact_->surface_rest();
  const double R = contact_->radius(), eps = contact_->stiffness();
  int a = 0;
  s.active = 0;
  s.dropped = 0;
  Eigen::Matrix3d sum_kc = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const Vec3 rel = rest[k] + u_.segment<3>(3 * static_cast<Eigen::Index>(nodes[k])) - c;
    const double dist = rel.norm();
    if (dist >= R || dist == 0.0) continue;
    ++s.active;
    if (a == kMaxActive) {
      ++s.dropped;
      continue;
    }
    const Vec3 nv = rel / dist;
    const Eigen::Matrix3d nn = nv * nv.transpose();
    kc_[static_cast<std::size_t>(a)] = eps * (nn + ((dist - R) / dist) * (Eigen::Matrix3d::Identity() - nn));
    sum_kc += kc_[static_cast<std::size_t>(a)];
    active_[static_cast<std::size_t>(a)] = static_cast<Index>(k);
    ++a;
  }
  if (a == 0) {
    s.stiffness.setZero();
    return;
  }
  // K_p = B^T G (I + K_c G)^{-1} B - sum K_c,i  (fixed-capacity matrices: no heap).
  const Eigen::Index m = 3 * a;
  SmallMat Gaa(m, m), A(m, m);
  SmallRhs B(m, 3);
  for (int i = 0; i < a; ++i) {
    B.block<3, 3>(3 * i, 0) = kc_[static_cast<std::size_t>(i)];
    for (int j = 0; j < a; ++j)
      Gaa.block<3, 3>(3 * i, 3 * j) =
          compliance(active_[static_cast<std::size_t>(i)], active_[static_cast<std::size_t>(j)]);
  }
  A.setIdentity();
  for (int i = 0; i < a; ++i)
    A.block(3 * i, 0, 3, m).noalias() += kc_[static_cast<std::size_t>(i)] * Gaa.block(3 * i, 0, 3, m);
  const Eigen::PartialPivLU<SmallMat> lu(A);
  const SmallRhs W = lu.solve(B);
  const SmallRhs Z = Gaa * W;
  s.stiffness = B.transpose() * Z - sum_kc;
}

void ControlModel::positions(float* out) const {
  const Index n = mesh_.num_points();
  for (Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      out[3 * i + c] = static_cast<float>(mesh_.points[static_cast<std::size_t>(i)][c] + u_[3 * i + c]);
}

}  // namespace tmlab::rt
