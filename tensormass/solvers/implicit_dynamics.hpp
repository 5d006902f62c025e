// Implicit dynamics: backward Euler (first order, strongly dissipative) and the trapezoidal
// Newmark scheme (beta = 1/4, gamma = 1/2: second order, energy conserving for linear problems).
// Each step solves  M a(u) + C v(u) + f_int(u) - f_ext(u, t+dt) = 0  for u = u^{n+1} by Newton, with
//   a(u) = c_a (u - u^n) - c_v v^n - c_aa a^n,     v(u) = d_u (u - u^n) + d_v v^n + d_a a^n
// and Jacobian c_a M + d_u C + K(u) (+ load stiffness).
#pragma once

#include "core/config/implicit_scheme.hpp"
#include "tensormass/solvers/newton.hpp"
#include "tensormass/system/mechanical_system.hpp"

#include <string>

namespace tmlab::tm {

using tmlab::ImplicitScheme;  ///< core/config/implicit_scheme.hpp: the case file's names too

/// a = ca (u - un) - cv vn - caa an;  v = du (u - un) + dv vn + da an.
struct ImplicitCoefficients {
  double ca, cv, caa;
  double du, dv, da;
};
ImplicitCoefficients implicit_coefficients(ImplicitScheme s, double dt);

/// The nonlinear system of one implicit step to t1:
///   R(u) = f_int(u) + M a(u) + C v(u) - f_ext(u, t1),  J = K(u) + (ca + du alpha) M + du beta K_0 (+ load
///   stiffness),
/// with the incremental potential (hyperelastic model, dead loads; d = u - un)
///   Pi(u) = W(u) + d.M (ca/2 d + a0) + d.C (du/2 d + v0) - f_ext . u,   a0 = a(un), v0 = v(un),
/// whose gradient is R (tested by finite differences).
class ImplicitStepResidual final : public NonlinearSystem {
 public:
  /// un, vn, an are referenced, not copied: they must outlive the residual.
  ImplicitStepResidual(const MechanicalSystem& s, double t1, const ImplicitCoefficients& c, const VecX& un,
                       const VecX& vn, const VecX& an);
  void acc_vel(const VecX& u, VecX& a, VecX& v) const;
  void residual(const VecX& u, VecX& r) override;
  void jacobian(const VecX& u, SpMat& J) override;
  bool symmetric() const override;
  double force_scale() const override { return scale_; }
  bool potential(const VecX& u, double& value) override;

 private:
  const MechanicalSystem& s_;
  double t1_;
  ImplicitCoefficients c_;
  const VecX& un_;
  const VecX& vn_;
  const VecX& an_;
  double scale_ = 0.0;
};

/// The start of an implicit run at t0 (ImplicitDynamics, and the contact loop around it): the
/// Dirichlet values of t0 applied to u, u committed as the model's initial state (an initial
/// displacement is applied instantaneously), and the initial acceleration a solving
/// M a = f_ext - f_int - C v, zero on the constrained DOFs.
void implicit_initial_state(const MechanicalSystem& system, double t0, VecX& u, const VecX& v, VecX& a);

class ImplicitDynamics {
 public:
  ImplicitDynamics(const MechanicalSystem& system, ImplicitScheme scheme, NewtonOptions options);

  /// Initial state at t0; the initial acceleration solves M a0 = f_ext - f_int - C v0.
  void initialize(double t0, const VecX& u0, const VecX& v0);
  /// Advances from t (= time()) to t + dt; throws tmlab::Error when Newton fails.
  NewtonResult step(double t, double dt);
  /// Sets the state saved at a step boundary (checkpoints); after initialize().
  void restore(double t, const VecX& u, const VecX& v, const VecX& a);

  double time() const { return t_; }
  /// The linear solver of the Newton steps (NewtonOptions::linear_solver; its fallback count).
  const ConstrainedLinearSolver& linear_solver() const { return linear_; }
  const VecX& displacement() const { return u_; }
  const VecX& velocity() const { return v_; }
  const VecX& acceleration() const { return a_; }
  double kinetic_energy() const { return 0.5 * v_.dot(system_.mass().cwiseProduct(v_)); }

 private:
  const MechanicalSystem& system_;
  ImplicitScheme scheme_;
  NewtonOptions options_;
  ConstrainedLinearSolver linear_;
  double t_ = 0.0;
  VecX u_, v_, a_;
};

}  // namespace tmlab::tm
