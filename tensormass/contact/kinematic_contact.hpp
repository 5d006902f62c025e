// Node-to-rigid contact for explicit central differences (docs/contact.md, "Explicit dynamics"):
// a kinematic (predictor-corrector) constraint, exact for rigid bodies with a lumped mass matrix.
//
// After the leapfrog predictor has moved the nodes to x* at t_{n+1} without contact forces, every
// boundary node that a body penetrates (g(x*) < 0) is moved back onto the body's surface,
//   frictionless:  dx = -g(x*) n   (the closest point: g is a signed distance),
//   bonded:        dx = (a_i + c(t_{n+1})) - x*   (glued nodes follow the body; a node is glued,
//                  at its closest point, in the step in which it first penetrates),
// and the contact force that does so over the step is  f_i = m_i dx / dt^2  (m_i the node's lumped
// mass): with a diagonal mass and a rigid master each node's constraint is independent, so this is
// the exact discrete contact force of the central-difference step (Taylor & Flanagan 1989's
// kinematic contact, specialised to a rigid master). The half-step velocity becomes
// v^{n+1/2} += dx / dt (the normal approach velocity is removed: a perfectly inelastic impact, and
// a node in persistent contact moves with the body). No stiffness is added, so the stable time step
// is that of the sample alone. A frictionless force is compressive (f.n >= 0) by construction; a
// node separates as soon as its predictor leaves the body.
//
// Prescribed DOFs are not moved: the correction acts on the free components of the node, along
// n_f / |n_f|^2 (n_f = n with the constrained components zeroed) so that the linearised gap closes;
// a node whose free components cannot close it (|n_f|^2 < 1e-6) is an error naming it.
#pragma once

#include "tensormass/contact/contact_solver.hpp"
#include "tensormass/contact/rigid_body.hpp"
#include "tensormass/contact/surface_grid.hpp"
#include "tensormass/system/mechanical_system.hpp"

#include <vector>

namespace tmlab::tm {

class KinematicContact {
 public:
  /// Builds the surface and its grid once, checks the bodies against (t0, u0) (penetration beyond
  /// initial_gap_tol is refused, naming the body and node) and glues the nodes touching bonded
  /// bodies. The mesh and system must outlive it.
  KinematicContact(const MechanicalSystem& system, const Mesh& mesh, std::vector<RigidBody> bodies,
                   const ContactOptions& options, double t0, const VecX& u0);

  /// The correction of the predicted displacement u at time t of a step dt: du (zero on prescribed
  /// DOFs); the outputs (state()) hold the contact forces m du / dt^2 of the step.
  VecX correct(double t, double dt, const VecX& u);

  const std::vector<ContactBodyState>& state() const { return state_; }
  const std::vector<RigidBody>& bodies() const { return bodies_; }
  const ContactSurface& surface() const { return surface_; }
  double gap_tol() const { return gap_tol_; }

  /// Checkpoints (issue 12): the glued nodes and their anchors per body as one array, exact; the
  /// restore also sets the outputs of the step it was taken after (state()).
  std::vector<double> committed_state() const;
  void restore_committed_state(const std::vector<double>& data, std::vector<ContactBodyState> outputs);

 private:
  Vec3 position(const VecX& u, Index k) const;

  const MechanicalSystem& system_;
  const Mesh& mesh_;
  std::vector<RigidBody> bodies_;
  ContactSurface surface_;
  SurfaceGrid grid_;
  double gap_tol_ = 0.0;
  std::vector<std::vector<char>> bonded_;  ///< per body, per surface node
  std::vector<std::vector<Vec3>> anchor_;  ///< glued point relative to c(t)
  std::vector<ContactBodyState> state_;
};

}  // namespace tmlab::tm
