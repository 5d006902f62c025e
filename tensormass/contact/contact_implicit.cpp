#include "tensormass/contact/contact_implicit.hpp"

#include "core/base/error.hpp"

#include <cmath>
#include <sstream>

namespace tmlab::tm {

ContactImplicitDynamics::ContactImplicitDynamics(const MechanicalSystem& system, const Mesh& mesh,
                                                 std::vector<RigidBody> bodies, ContactOptions options,
                                                 ImplicitScheme scheme, NewtonOptions newton, double dt,
                                                 const QuadraticMesh* quadratic)
    : system_(system),
      mesh_(mesh),
      quadratic_(quadratic),
      bodies_(std::move(bodies)),
      options_(options),
      scheme_(scheme),
      newton_(newton),
      dt_(dt) {}

void ContactImplicitDynamics::initialize(double t0, const VecX& u0, const VecX& v0) {
  t_ = t0;
  u_ = u0;
  v_ = v0;
  // The bodies touch without force at t0, so the initial acceleration is the plain one.
  implicit_initial_state(system_, t0, u_, v_, a_);
  contact_ = std::make_unique<ContactStaticSolver>(system_, mesh_, quadratic_, bodies_, options_, newton_, t0,
                                                   u_, 0);
  contact_->add_mass_scale(implicit_coefficients(scheme_, dt_).ca);
}

ContactStepReport ContactImplicitDynamics::step(double t, double dt) {
  if (!contact_) throw Error("ContactImplicitDynamics::step before initialize");
  if (!(dt > 0.0)) throw Error("implicit time step dt must be > 0");
  const ImplicitCoefficients c = implicit_coefficients(scheme_, dt);
  const InnerResidualFactory inner = [&](double t1, const VecX&) {
    return std::make_unique<ImplicitStepResidual>(system_, t1, c, u_, v_, a_);
  };
  system_.model().begin_step(dt);
  VecX u = u_ + dt * v_;  // predictor: constant velocity
  ContactStepReport report;
  const bool ok = contact_->solve(t + dt, t, u, report, inner);
  if (!ok) {
    std::ostringstream msg;
    msg << to_string(scheme_) << " step with contact from t = " << t << " s with dt = " << dt
        << " s did not converge (outer iterations " << report.outer_iterations << ", natural residual "
        << report.natural_residual << " m against gap_tol " << contact_->gap_tol()
        << " m, last Newton residual " << report.solver.newton.residual_final << "; bodies:";
    for (const RigidBody& b : contact_->bodies()) msg << " " << b.label();
    msg << "); reduce solver.dt or raise contact.max_outer_iterations";
    throw Error(msg.str());
  }
  system_.model().commit_step(u);
  ImplicitStepResidual res(system_, t + dt, c, u_, v_, a_);
  VecX a, v;
  res.acc_vel(u, a, v);
  contact_->accept(t + dt, u);
  u_.swap(u);
  v_.swap(v);
  a_.swap(a);
  t_ = t + dt;
  report.solver.sub_increments = 1;
  report.bodies = contact_->state();
  return report;
}

}  // namespace tmlab::tm
