#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/solvers/load_increments.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <sstream>

namespace tmlab::tm {

StaticResidual::StaticResidual(const MechanicalSystem& s, double t, const VecX& u0) : s_(s), t_(t) {
  VecX fi;
  s_.loads().assemble(u0, t_, fext0_);
  s_.model().internal_force(u0, fi);
  scale_ = std::max(fext0_.norm(), fi.norm());
}

void StaticResidual::residual(const VecX& u, VecX& r) {
  s_.model().internal_force(u, r);
  s_.loads().assemble(u, t_, fext_);
  r -= fext_;
}

void StaticResidual::jacobian(const VecX& u, SpMat& J) {
  s_.model().tangent(u, J);
  s_.add_load_stiffness(u, t_, J);
}

bool StaticResidual::symmetric() const { return !s_.loads().has_follower(); }

bool StaticResidual::potential(const VecX& u, double& value) {
  if (s_.loads().has_follower() || !s_.model().energy_is_potential()) return false;
  value = s_.model().energy(u) - fext0_.dot(u);
  return true;
}

StaticSolver::StaticSolver(const MechanicalSystem& system, NewtonOptions options, int max_cutbacks)
    : system_(system), options_(options), max_cutbacks_(max_cutbacks), linear_(options.linear_solver) {}

NewtonResult StaticSolver::solve(double t, VecX& u) {
  StaticResidual r(system_, t, u);
  return newton_solve(r, system_.bc(), t, u, options_, linear_);
}

StaticStepReport StaticSolver::advance(double t_prev, double t_next, VecX& u) {
  StaticStepReport report;
  LoadIncrements inc(t_prev, t_next, max_cutbacks_);
  while (inc.more()) {
    const double t_try = inc.next();
    VecX u_try = u;
    NewtonResult nr;
    bool ok = false;
    system_.model().begin_step(t_try - inc.done());  // trial history for this (sub-)increment
    try {
      nr = solve(t_try, u_try);
      ok = nr.converged;
    } catch (const Error&) {
      ok = false;  // a non-finite residual in a too-large increment: cut back like non-convergence
      if (inc.exhausted()) throw;
    }
    report.newton_iterations += nr.iterations;
    if (ok) {
      system_.model().commit_step(u_try);  // the increment is accepted: advance the history once
      u.swap(u_try);
      inc.accept(t_try);
      report.newton = nr;
      report.at_roundoff = report.at_roundoff || nr.at_roundoff;
      ++report.sub_increments;
      continue;
    }
    if (inc.exhausted()) {
      std::ostringstream msg;
      msg << "static Newton did not converge at t = " << t_try << " after " << max_cutbacks_
          << " cut-backs of the load increment (last residual " << nr.residual_final << " from "
          << nr.residual_initial
          << "); the load may exceed what the model can carry (St Venant-Kirchhoff softens and inverts "
             "elements "
             "under strong compression)";
      throw Error(msg.str());
    }
    inc.cut_back();
    ++report.cutbacks;
  }
  return report;
}

}  // namespace tmlab::tm
