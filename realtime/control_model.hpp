// The control thread's model: the viscoelastic tensor-mass liver (ViscoelasticStVK) advanced by
// explicit central differences with lumped mass, mass-proportional damping alpha and the probe's
// penalty contact (probe_contact.hpp), in preallocated storage so a step allocates nothing.
//
// One step from t_n to t_n + dt with the probe centred at c (its position at t_n):
//   history:  begin_step(dt); f_int = f_int(u_n); commit_step(u_n)     (as tm::CentralDifference)
//   contact:  f_c = sum_i eps <-g_i(u_n, c)>+ n_i,  F_probe(t_n) = -sum_i f_c,i
//   v^{n+1/2} = [(1 - alpha dt/2) v^{n-1/2} + dt M^{-1}(f_c - f_int)] / (1 + alpha dt/2),
//   u^{n+1}   = u^n + dt v^{n+1/2},   0 on the fixed (base) DOFs.
// This is tm::CentralDifference with the contact as part of the force; the offline test runs that
// solver on ProbePenaltyModel and gets the same force history to round-off.
//
// Stability: the tissue's critical step dt_t = 2/omega_max comes from tm::estimate_critical_time_step
// at the instantaneous modulus (the stiffest the viscoelastic model gets); the penalty adds at most
// eps/m_min to omega^2 (m_min the smallest surface-node mass: Weyl's inequality, the curvature term
// eps g H of a node in contact only softens), so the step is stable for
//   dt <= 2 / sqrt(omega_max^2 + eps/m_min).
// With penalty_stiffness = 0 (automatic) eps is the largest value that keeps dt at
// `stability_fraction` of that limit: the stiffest contact the explicit step can carry at this rate.
// A requested eps or dt beyond the limit is refused with both numbers.
//
// The haptic coupling gets a ContactSnapshot: the force on the probe, the probe centre the state was
// computed with, and the probe's contact stiffness K_p = dF/dc with the tissue in equilibrium:
// with K_c,i = eps (n_i n_i^T + g_i H_i) the contact tangent of active node i (A the active set),
// B = [K_c,i] stacked (3a x 3: df_i/dc = K_c,i), K_t the tissue tangent,
//   K_p = B^T [(K_t + K_c)^{-1}]_AA B - sum_i K_c,i,   [(K_t + K_c)^{-1}]_AA = G (I + K_c G)^{-1},
// G = [K_t^{-1}]_AA the tissue's compliance between the active nodes (Woodbury, since K_c acts on
// A only). K_t is the tangent of a step of size dt at rest: the instantaneous viscoelastic
// stiffness (long-term modulus times 1 + g(dt)), so G is the instantaneous compliance. The dense
// compliance of all free surface nodes is computed once at construction (one sparse LDL^T and
// 3 solves per surface node); a snapshot gathers the a x a block and solves one small dense system
// in fixed-capacity storage. Limits: K_t at rest (no geometric stiffening), quasi-static (the
// tissue's inertia is ignored: right for probe motions slower than the liver's first modes).
#pragma once

#include "core/mesh/mesh.hpp"
#include "realtime/probe_contact.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace tmlab::rt {

struct ControlOptions {
  double dt = 1e-3;                 ///< model step, s
  double mass_damping = 0.0;        ///< alpha, 1/s
  double probe_radius = 0.01;       ///< m
  double penalty_stiffness = 0.0;   ///< eps, N/m per node; 0: automatic (see above)
  double stability_fraction = 0.8;  ///< automatic eps keeps dt at this fraction of the stable limit
  /// h > 0: the snapshot stiffness condenses the tissue's backward-Euler step matrix
  /// K_inst + (1/h^2 + alpha/h) M (inertia over a horizon h) instead of the static K_inst.
  double coupling_horizon = 0.0;
};

/// What the control step hands the haptic thread (fixed size: no allocation when copied/filled).
struct ContactSnapshot {
  std::uint64_t step = 0;     ///< model steps done when the snapshot was taken
  double t = 0.0;             ///< model time of the state, s
  Vec3 probe = Vec3::Zero();  ///< probe centre the contact force was evaluated with
  Vec3 force = Vec3::Zero();  ///< force of the tissue on the probe at (u, probe), N
  /// dF/dc: the probe's contact stiffness with the tissue in equilibrium at its instantaneous
  /// compliance (see ControlModel::fill_snapshot), N/m; negative semi-definite.
  Eigen::Matrix3d stiffness = Eigen::Matrix3d::Zero();
  int active = 0;   ///< nodes in contact
  int dropped = 0;  ///< active nodes beyond kMaxActive, left out of the stiffness (reported)
};

class ControlModel {
 public:
  /// Builds the model; throws tmlab::Error for a dt beyond the stable limit (naming both).
  ControlModel(const Mesh& mesh, const tm::StVenantKirchhoff& long_term, const tm::PronySeries& prony,
               tm::ViscoelasticOptions viscoelastic, double density, const std::vector<Index>& fixed_nodes,
               const ControlOptions& options);
  ControlModel(const ControlModel&) = delete;
  ControlModel& operator=(const ControlModel&) = delete;

  /// Back to rest at t = 0 with the probe at c0: a fresh viscoelastic model (history cleared; this
  /// allocates: call it before the loop, never in it).
  void reset(const Vec3& c0);
  /// One explicit step with the probe at c; returns the force on the probe at (u_n, c). Allocation-free.
  Vec3 step(const Vec3& c);
  /// Force on the probe at the current state for a probe at c (no step). Allocation-free.
  Vec3 contact_force(const Vec3& c, int* active = nullptr);
  /// Fills `s` for the current state and a probe at c. Allocation-free.
  void fill_snapshot(const Vec3& c, ContactSnapshot& s);
  /// Current positions of all nodes as floats (xyz per node) into out (size 3 n). Allocation-free.
  void positions(float* out) const;

  double dt() const { return opt_.dt; }
  double time() const { return static_cast<double>(steps_) * opt_.dt; }
  std::uint64_t steps() const { return steps_; }
  const VecX& displacement() const { return u_; }
  const VecX& dof_mass() const { return mass_; }
  const Mesh& mesh() const { return mesh_; }
  const ProbeContact& contact() const { return *contact_; }
  const std::vector<Index>& fixed_nodes() const { return fixed_nodes_; }
  double penalty_stiffness() const { return contact_->stiffness(); }
  double dt_critical_tissue() const { return dt_tissue_; }    ///< 2/omega_max, no contact
  double dt_critical_contact() const { return dt_contact_; }  ///< with the penalty
  /// Active nodes the snapshot's stiffness can hold.
  static constexpr int kMaxActive = 24;
  /// The compliance between two free surface nodes (surface-local indices), m/N.
  Eigen::Matrix3d compliance(Index a, Index b) const {
    return G_.block<3, 3>(3 * static_cast<Eigen::Index>(a), 3 * static_cast<Eigen::Index>(b));
  }

 private:
  Mesh mesh_;
  ControlOptions opt_;
  tm::StVenantKirchhoff material_;
  tm::PronySeries prony_;
  tm::ViscoelasticOptions viscoelastic_;
  std::unique_ptr<tm::ViscoelasticStVK> model_;
  std::unique_ptr<ProbeContact> contact_;
  std::vector<Index> fixed_nodes_;
  std::vector<char> fixed_dof_;
  VecX mass_;          ///< per DOF
  Eigen::MatrixXd G_;  ///< [K_inst^{-1}] between the surface nodes (0 for fixed ones), 3S x 3S
  double dt_tissue_ = 0.0, dt_contact_ = 0.0;
  // fill_snapshot scratch, fixed capacity (no heap)
  using SmallMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3 * kMaxActive, 3 * kMaxActive>;
  using SmallRhs = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, 3 * kMaxActive, 3>;
  std::array<Index, kMaxActive> active_{};
  std::array<Eigen::Matrix3d, kMaxActive> kc_{};
  std::uint64_t steps_ = 0;
  VecX u_, vh_, fint_, fc_;
};

}  // namespace tmlab::rt
