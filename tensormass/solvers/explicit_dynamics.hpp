// Explicit central-difference (leapfrog) dynamics with lumped mass and Rayleigh damping:
//   v^{n+1/2} = [(1 - alpha dt/2) v^{n-1/2} + dt M^{-1}(f_ext(t_n) - f_int(u_n) - beta K_0 v^{n-1/2})] / (1 +
//   alpha dt/2) u^{n+1}   = u^n + dt v^{n+1/2}
// Mass damping is treated semi-implicitly (it never limits the step); stiffness damping explicitly.
// Second order in dt; conditionally stable: dt <= (2/omega_max)(sqrt(1 + xi^2) - xi), xi = beta omega_max
// / 2.
#pragma once

#include "tensormass/system/mechanical_system.hpp"

#include <limits>

namespace tmlab::tm {

struct StabilityEstimate {
  double omega_max = 0.0;      ///< power-iteration estimate of the largest angular frequency at rest, rad/s
  double omega_bound = 0.0;    ///< Gershgorin upper bound on it (row sums of M^{-1} |K_0|)
  double dt_critical = 0.0;    ///< stability limit from omega_max (what dt is checked against)
  double dt_guaranteed = 0.0;  ///< the limit from omega_bound: always stable at the reference state
  int iterations = 0;
};

/// Largest eigenvalue of M^{-1} K_0 on the free DOFs by power iteration (Rayleigh quotient),
/// and the Gershgorin bound; converted to time-step limits for the leapfrog scheme.
StabilityEstimate estimate_critical_time_step(const MechanicalSystem& system, int max_iterations = 2000);

class CentralDifference {
 public:
  /// Throws tmlab::Error when dt exceeds the estimated critical step (unless check_stability is false).
  CentralDifference(const MechanicalSystem& system, double dt, bool check_stability = true);

  /// Initial state at t0; v0 is the velocity at t0.
  void initialize(double t0, const VecX& u0, const VecX& v0);
  /// Advances from t (must equal time()) to t + dt (the dt given at construction).
  void step(double t, double dt);
  /// Sets the state saved at a step boundary (checkpoints): time, step count, u, the half-step
  /// velocity and v; after initialize(), so the stability estimate and the model are set up.
  void restore(double t, long steps, const VecX& u, const VecX& v_half, const VecX& v);
  const VecX& half_step_velocity() const { return v_half_; }

  /// A kinematic correction of the step just taken (contact, tensormass/contact/kinematic_contact):
  /// u^{n+1} += du, with the half-step velocity kept consistent, v^{n+1/2} += du / dt (and the
  /// integer-level velocity by half that). du must vanish on prescribed DOFs.
  void correct(const VecX& du);

  double time() const { return t_; }
  long steps() const { return n_; }
  const VecX& displacement() const { return u_; }
  /// Velocity at the current integer time level (average of the half-step velocities).
  const VecX& velocity() const { return v_; }
  double kinetic_energy() const;
  const StabilityEstimate& stability() const { return stability_; }
  /// A displacement magnitude no stable run reaches (e.g. 10x the mesh size): passing it is
  /// reported as instability long before values overflow.
  void set_displacement_limit(double limit) { displacement_limit_ = limit; }

 private:
  const MechanicalSystem& system_;
  double dt_;
  StabilityEstimate stability_;
  double t_ = 0.0;
  long n_ = 0;
  VecX u_, v_half_, v_, fint_, fext_, fdamp_;
  VecX v_new_, g_;  ///< step() scratch, kept to avoid an allocation per step
  double displacement_limit_ = std::numeric_limits<double>::infinity();
};

}  // namespace tmlab::tm
