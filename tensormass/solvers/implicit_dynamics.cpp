#include "tensormass/solvers/implicit_dynamics.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tmlab::tm {

ImplicitCoefficients implicit_coefficients(ImplicitScheme s, double dt) {
  if (s == ImplicitScheme::BackwardEuler) {
    // v = (u - un)/dt, a = (v - vn)/dt.
    return {1.0 / (dt * dt), 1.0 / dt, 0.0, 1.0 / dt, 0.0, 0.0};
  }
  const double beta = 0.25, gamma = 0.5;
  return {1.0 / (beta * dt * dt), 1.0 / (beta * dt),  1.0 / (2.0 * beta) - 1.0,
          gamma / (beta * dt),    1.0 - gamma / beta, dt * (1.0 - gamma / (2.0 * beta))};
}

ImplicitStepResidual::ImplicitStepResidual(const MechanicalSystem& s, double t1,
                                           const ImplicitCoefficients& c, const VecX& un, const VecX& vn,
                                           const VecX& an)
    : s_(s), t1_(t1), c_(c), un_(un), vn_(vn), an_(an) {
  VecX f, fi;
  s_.loads().assemble(un_, t1_, f);
  s_.model().internal_force(un_, fi);
  scale_ = std::max({f.norm(), fi.norm(), s_.mass().cwiseProduct(an_).norm()});
}

void ImplicitStepResidual::acc_vel(const VecX& u, VecX& a, VecX& v) const {
  a = c_.ca * (u - un_) - c_.cv * vn_ - c_.caa * an_;
  v = c_.du * (u - un_) + c_.dv * vn_ + c_.da * an_;
}

void ImplicitStepResidual::residual(const VecX& u, VecX& r) {
  VecX a, v, cv, fext;
  acc_vel(u, a, v);
  s_.model().internal_force(u, r);
  s_.damping_force(v, cv);
  s_.loads().assemble(u, t1_, fext);
  r += s_.mass().cwiseProduct(a) + cv - fext;
}

void ImplicitStepResidual::jacobian(const VecX& u, SpMat& J) {
  s_.model().tangent(u, J);
  const double mass_coef = c_.ca + c_.du * s_.damping().alpha;
  for (Eigen::Index i = 0; i < J.rows(); ++i) J.coeffRef(i, i) += mass_coef * s_.mass()[i];
  if (s_.damping().beta != 0.0) J += (c_.du * s_.damping().beta) * s_.reference_tangent();
  s_.add_load_stiffness(u, t1_, J);
}

bool ImplicitStepResidual::symmetric() const { return !s_.loads().has_follower(); }

bool ImplicitStepResidual::potential(const VecX& u, double& value) {
  if (s_.loads().has_follower() || !s_.model().energy_is_potential()) return false;
  const VecX d = u - un_;
  const VecX a_half = 0.5 * c_.ca * d - c_.cv * vn_ - c_.caa * an_;
  const VecX v_half = 0.5 * c_.du * d + c_.dv * vn_ + c_.da * an_;
  VecX cv, fext;
  s_.damping_force(v_half, cv);
  s_.loads().assemble(u, t1_, fext);
  value = s_.model().energy(u) + d.dot(s_.mass().cwiseProduct(a_half)) + d.dot(cv) - fext.dot(u);
  return true;
}

ImplicitDynamics::ImplicitDynamics(const MechanicalSystem& system, ImplicitScheme scheme,
                                   NewtonOptions options)
    : system_(system), scheme_(scheme), options_(options), linear_(options.linear_solver) {}

void implicit_initial_state(const MechanicalSystem& system, double t0, VecX& u, const VecX& v, VecX& a) {
  system.bc().apply(t0, u);
  // The initial state is the committed one: an initial displacement is applied instantaneously.
  system.model().begin_step(0.0);
  system.model().commit_step(u);
  VecX fint, fext, fd;
  system.model().internal_force(u, fint);
  system.loads().assemble(u, t0, fext);
  system.damping_force(v, fd);
  a = (fext - fint - fd).cwiseQuotient(system.mass());
  for (Index d : system.bc().dofs()) a[d] = 0.0;
}

void ImplicitDynamics::initialize(double t0, const VecX& u0, const VecX& v0) {
  t_ = t0;
  u_ = u0;
  v_ = v0;
  implicit_initial_state(system_, t0, u_, v_, a_);
}

void ImplicitDynamics::restore(double t, const VecX& u, const VecX& v, const VecX& a) {
  const Index n = system_.num_dofs();
  if (u.size() != n || v.size() != n || a.size() != n)
    throw Error("checkpoint: implicit state of the wrong size (a checkpoint of another mesh?)");
  t_ = t;
  u_ = u;
  v_ = v;
  a_ = a;
}

NewtonResult ImplicitDynamics::step(double t, double dt) {
  if (!(dt > 0.0)) throw Error("implicit time step dt must be > 0");
  if (std::abs(t - t_) > 1e-9 * std::max(1.0, std::abs(t_)))
    throw Error("ImplicitDynamics::step called with t inconsistent with its state");
  const ImplicitCoefficients c = implicit_coefficients(scheme_, dt);
  ImplicitStepResidual res(system_, t + dt, c, u_, v_, a_);
  system_.model().begin_step(dt);
  // Predictor: constant velocity.
  VecX u = u_ + dt * v_;
  NewtonResult nr = newton_solve(res, system_.bc(), t + dt, u, options_, linear_);
  if (!nr.converged) {
    std::ostringstream msg;
    msg << to_string(scheme_) << " step from t = " << t << " s with dt = " << dt
        << " s: Newton did not converge in " << nr.iterations << " iterations (residual " << nr.residual_final
        << " from " << nr.residual_initial << "); reduce solver.dt";
    throw Error(msg.str());
  }
  system_.model().commit_step(u);
  VecX a, v;
  res.acc_vel(u, a, v);
  u_.swap(u);
  v_.swap(v);
  a_.swap(a);
  t_ = t + dt;
  return nr;
}

}  // namespace tmlab::tm
