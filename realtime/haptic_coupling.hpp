// Haptic couplings: the force the haptic thread renders at its own rate from the newest control
// snapshot, without waiting for the control thread.
//
// Extrapolation (the paper, Section IV-C): linear extrapolation of the last two control forces
//   F(t) = F_k + (F_k - F_{k-1}) (t - t_k) / (t_k - t_{k-1}),
// horizon t - t_k clamped to [0, 4 (t_k - t_{k-1})] (a stalled control thread must not extrapolate
// without bound). It ignores where the probe is now: all it knows is the force history.
//
// Local linear model (ours): the snapshot's force corrected for the probe's motion since the state
// was computed, through the probe's contact stiffness (control_model.hpp: the contact tangent
// condensed with the tissue's instantaneous viscoelastic compliance):
//   F(x) = F_k + K_p (x - c_k),   c_k the probe centre the snapshot was computed with,
// and 0 when the snapshot has no contact, or when the prediction would pull the probe into the tissue
// (F . F_k < 0: frictionless contact only pushes). It has no delay in the probe position, so within
// one snapshot it renders a conservative (symmetric K_p) spring; energy can only enter at snapshot
// changes.
//
// Both keep copies of what they need (a few numbers) and are allocation-free.
#pragma once

#include "realtime/control_model.hpp"

#include <string>

namespace tmlab::rt {

enum class CouplingScheme { Extrapolation, LocalModel };
/// "extrapolation" | "local_model".
const char* to_string(CouplingScheme s);
CouplingScheme parse_coupling(const std::string& s);

class ExtrapolationCoupling {
 public:
  void on_snapshot(const ContactSnapshot& s);
  Vec3 force(double t, const Vec3& x) const;

 private:
  int have_ = 0;
  double t0_ = 0.0, t1_ = 0.0;
  Vec3 f0_ = Vec3::Zero(), f1_ = Vec3::Zero();
};

class LocalModelCoupling {
 public:
  void on_snapshot(const ContactSnapshot& s) {
    f_ = s.force;
    c_ = s.probe;
    k_ = s.stiffness;
    have_ = true;
  }
  Vec3 force(double t, const Vec3& x) const;

 private:
  bool have_ = false;
  Vec3 f_ = Vec3::Zero(), c_ = Vec3::Zero();
  Eigen::Matrix3d k_ = Eigen::Matrix3d::Zero();
};

}  // namespace tmlab::rt
