// Static equilibrium f_int(u) = f_ext(u, t) by Newton with line search, with automatic bisection of
// the load increment when Newton fails, and the increment doubled again (up to the step's own)
// after each success that followed a cut-back (load stepping is driven by the time functions of the loads
// and prescribed displacements; t is a pseudo-time).
#pragma once

#include "tensormass/solvers/newton.hpp"
#include "tensormass/system/mechanical_system.hpp"

namespace tmlab::tm {

/// R(u) = f_int(u) - f_ext(u, t);  J = K(u) - d f_ext/du;  under dead loads with a hyperelastic model
/// the potential Pi(u) = W(u) - f_ext(t) . u (dR = dPi/du, tested by finite differences).
class StaticResidual final : public NonlinearSystem {
 public:
  /// The force scale of the relative tolerance: the larger of |f_ext| and |f_int(u0)| (the latter
  /// carries the reactions of prescribed displacements, the only forces in a displacement-driven
  /// hold phase, where |R(u0)| itself is already at round-off).
  StaticResidual(const MechanicalSystem& s, double t, const VecX& u0);
  void residual(const VecX& u, VecX& r) override;
  void jacobian(const VecX& u, SpMat& J) override;
  bool symmetric() const override;
  double force_scale() const override { return scale_; }
  bool potential(const VecX& u, double& value) override;

 private:
  const MechanicalSystem& s_;
  double t_;
  double scale_ = 0.0;
  VecX fext_, fext0_;
};

struct StaticStepReport {
  NewtonResult newton;        ///< of the last (successful) sub-increment
  int newton_iterations = 0;  ///< summed over sub-increments
  int cutbacks = 0;           ///< how many times the increment was halved
  int sub_increments = 0;     ///< accepted (sub-)increments: 1 without cut-backs
  bool at_roundoff = false;   ///< some sub-increment converged by the round-off stagnation test
};

class StaticSolver {
 public:
  StaticSolver(const MechanicalSystem& system, NewtonOptions options, int max_cutbacks = 8);

  /// Equilibrium at pseudo-time t_next starting from the equilibrium u at t_prev (u overwritten).
  /// Halves the increment up to max_cutbacks times when Newton does not converge, then throws
  /// tmlab::Error naming the time reached.
  StaticStepReport advance(double t_prev, double t_next, VecX& u);
  /// One Newton solve at time t from u, no cut-backs.
  NewtonResult solve(double t, VecX& u);
  /// The linear solver of the Newton steps (NewtonOptions::linear_solver; its fallback count).
  const ConstrainedLinearSolver& linear_solver() const { return linear_; }

 private:
  const MechanicalSystem& system_;
  NewtonOptions options_;
  int max_cutbacks_;
  ConstrainedLinearSolver linear_;
};

}  // namespace tmlab::tm
