// Static equilibrium f_int(u) = f_ext(u, t) by Newton with line search, with automatic bisection of
// the load increment when Newton fails (load stepping is driven by the time functions of the loads
// and prescribed displacements; t is a pseudo-time).
#pragma once

#include "tensormass/solvers/newton.hpp"
#include "tensormass/system/mechanical_system.hpp"

namespace tmlab::tm {

struct StaticStepReport {
  NewtonResult newton;        ///< of the last (successful) sub-increment
  int newton_iterations = 0;  ///< summed over sub-increments
  int cutbacks = 0;           ///< how many times the increment was halved
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

 private:
  const MechanicalSystem& system_;
  NewtonOptions options_;
  int max_cutbacks_;
  ConstrainedLinearSolver linear_;
};

}  // namespace tmlab::tm
