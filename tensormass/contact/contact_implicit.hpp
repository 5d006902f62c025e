// Implicit dynamics (backward Euler, Newmark) with node-to-rigid contact (docs/contact.md): the
// same augmented-Lagrangian outer loop as the static solver (ContactStaticSolver::solve), around
// the Newton solve of the implicit step's residual (ImplicitStepResidual) instead of the static one.
// The step is otherwise ImplicitDynamics::step: predictor u^n + dt v^n, the model's begin_step /
// commit_step around the accepted solve, and a, v from the Newmark/backward-Euler update. The
// automatic eps is raised by c_a M (add_mass_scale) so the Uzawa loop contracts as in statics. A
// step whose outer loop does not converge is an error naming the time (no cut-backs in dynamics:
// reduce solver.dt).
#pragma once

#include "core/config/implicit_scheme.hpp"
#include "tensormass/contact/contact_solver.hpp"
#include "tensormass/solvers/implicit_dynamics.hpp"

#include <memory>

namespace tmlab::tm {

class ContactImplicitDynamics {
 public:
  /// The mesh and system must outlive it; `dt` sets the mass scale of eps. `quadratic` (when not
  /// null, the quadratic mesh of `mesh` the model runs on) puts the contact at face quadrature points.
  ContactImplicitDynamics(const MechanicalSystem& system, const Mesh& mesh, std::vector<RigidBody> bodies,
                          ContactOptions options, ImplicitScheme scheme, NewtonOptions newton, double dt,
                          const QuadraticMesh* quadratic = nullptr);

  /// Initial state at t0 (the bodies are checked against it); a0 solves M a0 = f_ext - f_int - C v0.
  void initialize(double t0, const VecX& u0, const VecX& v0);
  /// Advances from t (= time()) to t + dt.
  ContactStepReport step(double t, double dt);

  double time() const { return t_; }
  const VecX& displacement() const { return u_; }
  const VecX& velocity() const { return v_; }
  const VecX& acceleration() const { return a_; }
  /// Checkpoints (issue 12): after initialize(), continues from a saved step boundary (the contact
  /// state is restored through contact()).
  void restore(double t, const VecX& u, const VecX& v, const VecX& a) {
    t_ = t;
    u_ = u;
    v_ = v;
    a_ = a;
  }
  const ContactStaticSolver& contact() const { return *contact_; }
  ContactStaticSolver& contact() { return *contact_; }

 private:
  const MechanicalSystem& system_;
  const Mesh& mesh_;
  const QuadraticMesh* quadratic_ = nullptr;
  std::vector<RigidBody> bodies_;
  ContactOptions options_;
  ImplicitScheme scheme_;
  NewtonOptions newton_;
  double dt_;
  std::unique_ptr<ContactStaticSolver> contact_;
  double t_ = 0.0;
  VecX u_, v_, a_;
};

}  // namespace tmlab::tm
