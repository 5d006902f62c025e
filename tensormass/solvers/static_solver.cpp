#include "tensormass/solvers/static_solver.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <sstream>

namespace tmlab::tm {

namespace {
/// R(u) = f_int(u) - f_ext(u, t);  J = K(u) - d f_ext/du.
class StaticResidual final : public NonlinearSystem {
 public:
  /// The force scale of the relative tolerance: the larger of |f_ext| and |f_int(u0)| (the latter
  /// carries the reactions of prescribed displacements, the only forces in a displacement-driven
  /// hold phase, where |R(u0)| itself is already at round-off).
  StaticResidual(const MechanicalSystem& s, double t, const VecX& u0) : s_(s), t_(t) {
    VecX f, fi;
    s_.loads().assemble(u0, t_, f);
    s_.model().internal_force(u0, fi);
    scale_ = std::max(f.norm(), fi.norm());
  }
  void residual(const VecX& u, VecX& r) override {
    s_.model().internal_force(u, r);
    s_.loads().assemble(u, t_, fext_);
    r -= fext_;
  }
  void jacobian(const VecX& u, SpMat& J) override {
    s_.model().tangent(u, J);
    s_.add_load_stiffness(u, t_, J);
  }
  bool symmetric() const override { return !s_.loads().has_follower(); }
  double force_scale() const override { return scale_; }

 private:
  const MechanicalSystem& s_;
  double t_;
  double scale_ = 0.0;
  VecX fext_;
};
}  // namespace

StaticSolver::StaticSolver(const MechanicalSystem& system, NewtonOptions options, int max_cutbacks)
    : system_(system), options_(options), max_cutbacks_(max_cutbacks) {}

NewtonResult StaticSolver::solve(double t, VecX& u) {
  StaticResidual r(system_, t, u);
  return newton_solve(r, system_.bc(), t, u, options_, linear_);
}

StaticStepReport StaticSolver::advance(double t_prev, double t_next, VecX& u) {
  StaticStepReport report;
  double t_done = t_prev;
  double h = t_next - t_prev;
  int depth = 0;
  while (t_done < t_next) {
    const double t_try = (t_next - t_done <= h * (1.0 + 1e-12)) ? t_next : t_done + h;
    VecX u_try = u;
    NewtonResult nr;
    bool ok = false;
    system_.model().begin_step(t_try - t_done);  // trial history for this (sub-)increment
    try {
      nr = solve(t_try, u_try);
      ok = nr.converged;
    } catch (const Error&) {
      ok = false;  // a non-finite residual in a too-large increment: cut back like non-convergence
      if (depth >= max_cutbacks_) throw;
    }
    report.newton_iterations += nr.iterations;
    if (ok) {
      system_.model().commit_step(u_try);  // the increment is accepted: advance the history once
      u.swap(u_try);
      t_done = t_try;
      report.newton = nr;
      continue;
    }
    if (depth >= max_cutbacks_) {
      std::ostringstream msg;
      msg << "static Newton did not converge at t = " << t_try << " after " << max_cutbacks_
          << " cut-backs of the load increment (last residual " << nr.residual_final << " from "
          << nr.residual_initial
          << "); the load may exceed what the model can carry (St Venant-Kirchhoff softens and inverts "
             "elements "
             "under strong compression)";
      throw Error(msg.str());
    }
    h *= 0.5;
    ++depth;
    ++report.cutbacks;
  }
  return report;
}

}  // namespace tmlab::tm
