// Static equilibrium with node-to-rigid contact (docs/contact.md).
//
// The constraints are imposed on the boundary nodes of the mesh against rigid analytic bodies
// (rigid_body.hpp) by the augmented Lagrangian method with Uzawa multiplier updates, around the
// unchanged static Newton solver (newton_solve with its energy line search):
//
//   frictionless node i, body b:   g_i(u) >= 0,  lambda_i >= 0,  lambda_i g_i = 0,
//       Pi_k(u) = Pi(u) + sum_i 1/(2 eps) ( <lambda_i^k - eps g_i(u)>_+^2 - (lambda_i^k)^2 ),
//       force on the sample at i:  <lambda_i^k - eps g_i>_+ n_i,
//       update:  lambda_i^{k+1} = <lambda_i^k - eps g_i(u_k)>_+       (u_k minimises Pi_k)
//   bonded node i (glued):          c_i(u) = x_i - (a_i + c(t)) = 0 (a_i its anchor in the body frame),
//       Pi_k(u) = Pi(u) + sum_i ( lambda_i^k . c_i + eps/2 |c_i|^2 ),  update lambda += eps c_i(u_k).
//
// For fixed multipliers Pi_k is a potential (C1, piecewise C2), so the Newton solver's Armijo line
// search applies unchanged; its tangent adds eps n n^T - <.>_+ d^2 g/dx^2 (eps I when bonded) to
// the nodal 3x3 diagonal blocks, which the mesh-graph pattern already holds. The multipliers at the
// end are the nodal contact forces: the equilibrium of u_k holds with lambda^{k+1} exactly.
//
// Stopping test of the outer (Uzawa) loop, all of:
//   (1) the natural complementarity residual  max_i |lambda_i^{k+1} - lambda_i^k| / eps
//       = max_i |min(lambda_i^k / eps, g_i)|  (|c_i|_inf when bonded) is <= gap_tol, metres;
//   (2) the active set {lambda^{k+1} > 0} equals the previous one, ignoring nodes whose multiplier
//       stays below eps gap_tol in both (weakly active: force and gap both within tolerance);
//   (3) a search over all boundary nodes (grid, margin 0) finds no node outside the candidate set
//       with g < -gap_tol.
// Then lambda >= 0 exactly, g >= -gap_tol, and lambda |g| <= lambda_max gap_tol on every node.
//
// Penalty (option): the multipliers stay 0, one outer iteration; the force is eps <-g>_+, the
// penetration O(force/eps) is reported, and so is eps.
//
// Bonded bodies: a node that touches (g <= gap_tol at the start, or active at the end of an
// accepted increment) is glued from then on to the body point it touched; it is never released.
//
// Contact points (contact_points.hpp). The constraint carrier is a contact point, a weighted
// combination of nodes x_q = sum_a N_a x_a with a weight w_q. On linear tets a point is a boundary
// node (N = 1, w = 1: the rule above, bit for bit). On quadratic tets (a QuadraticMesh given) the
// points are the 6 quadrature points of each boundary 6-node triangle (degree-4 rule), w_q the rest
// area weight, and the constraint is one per FACE f (mortar-style, a face-constant pressure): its
// weighted gap  g_f = sum_q w_q g_q / A_f  (A_f = sum_q w_q, the face's mean gap) and one multiplier
// lambda_f, the face's contact pressure (Pa):
//   Phi = sum_f A_f/(2 eps_a) (<lambda_f - eps_a g_f>_+^2 - lambda_f^2),
//   force on node a  -p_f G_a,  G_a = sum_q w_q N_a(xi_q) n_q,  p_f = <lambda_f - eps_a g_f>_+,
//   tangent  (eps_a/A_f) G_a G_b^T - p_f sum_q w_q N_a N_b H_q   (the face's 6 nodes share a tet),
//   update  lambda_f <- <lambda_f - eps_a g_f(u_k)>_+ ; the stopping test and gap_tol per face.
// One multiplier per face (about 2 per boundary vertex) against about 4 face nodes per vertex: the
// constraints are not redundant, as one per quadrature point (6 per face, 3x the nodes) were, whose
// Uzawa loop did not settle on curved contact (docs/contact.md). eps_a (Pa/m) = eps N_b / S with
// S = sum_f sum_a |G_a|^2 / A_f at rest and N_b the face nodes: the penalty's nodal stiffness is then
// on average the nodal eps (from K_0 over the face nodes' DOFs, or contact.stiffness in N/m). Bonded
// faces glue their 6 points: w_q (lambda_q . c_q + eps_a/2 |c_q|^2) per point (a traction). A face
// is glued at t0 when all its points touch, or at the end of an increment in which it was active.
// The body force is sum_f lambda_f sum_q w_q n_q. Initial penetration is checked at the points.
#pragma once

#include "core/mesh/quadratic_mesh.hpp"
#include "tensormass/contact/contact_points.hpp"
#include "tensormass/contact/rigid_body.hpp"
#include "tensormass/contact/surface_grid.hpp"
#include "tensormass/solvers/static_solver.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tmlab::tm {

enum class ContactMethod {
  AugmentedLagrangian,  ///< exact to gap_tol (Uzawa updates until the stopping test holds)
  Penalty,              ///< one solve with lambda = 0; penetration O(force / eps)
};

struct ContactOptions {
  ContactMethod method = ContactMethod::AugmentedLagrangian;
  /// eps = stiffness_factor * (mean diagonal entry of the reference tangent K_0 over the boundary
  /// DOFs), a nodal stiffness scale of the sample itself: the Uzawa loop then shrinks the
  /// constraint error by roughly that factor per outer iteration.
  double stiffness_factor = 100.0;
  double stiffness = 0.0;        ///< > 0: eps in N/m, overriding stiffness_factor
  double gap_tol = 0.0;          ///< metres; 0: 1e-8 * mean boundary edge length
  double initial_gap_tol = 0.0;  ///< penetration refused at t0, metres; 0: gap_tol
  /// A body whose smallest gap to the sample at t0 exceeds this is refused (it would not touch),
  /// metres; 0: 1e-3 * the mesh's bounding-box diagonal (check_contact_rig in contact_checks.hpp; the case
  /// runner calls it).
  double max_initial_gap = 0.0;
  int max_outer_iterations = 30;
  double search_margin = 0.0;  ///< metres; 0: max(2 * body travel in the increment, 2 * mean edge)
};

/// The contact outputs of one body at one time.
struct ContactBodyState {
  std::string name;
  Vec3 position = Vec3::Zero();  ///< reference point c(t)
  Vec3 force = Vec3::Zero();     ///< total force the sample exerts on the body, N
  Vec3 moment = Vec3::Zero();    ///< moment of that force about c(t), N m
  int active_nodes = 0;          ///< active nodes (quadratic faces: active faces)
  double area = 0.0;  ///< sum over active nodes of the reference tributary area projected on n, m^2
  double radius_equivalent = 0.0;  ///< sqrt(area / pi) (axisymmetric bodies; 0 for the plane)
  double radius_max = 0.0;         ///< largest radial distance of an active contact point from the axis
  double max_penetration = 0.0;    ///< max(0, -g) over the active nodes (faces: their points), m
  double complementarity = 0.0;    ///< max over nodes of lambda |g| (faces: A_f lambda_f |g_f|), N m
  double min_multiplier = 0.0;     ///< smallest normal multiplier (>= 0 for frictionless contact)
  std::vector<Index> nodes;        ///< active nodes (mesh indices), increasing
  std::vector<Vec3> nodal_force;   ///< force on the sample at each active node, N
  std::vector<double> gap;         ///< gap at each active node, m
  std::vector<double> pressure;    ///< (f . n) / projected tributary area (0 where that is 0), Pa
};

struct ContactStepReport {
  StaticStepReport solver;          ///< Newton iterations summed over outer iterations, cut-backs
  int outer_iterations = 0;         ///< of the last sub-increment
  int outer_iterations_total = 0;   ///< summed over sub-increments
  std::vector<int> active_changes;  ///< per outer iteration of the last sub-increment
  std::vector<int> active_counts;   ///< active nodes (all bodies) per outer iteration, same
  double natural_residual = 0.0;    ///< final value of stopping test (1), metres
  std::vector<ContactBodyState> bodies;
};

/// Builds the nonlinear system of one solve at time t from the starting state u, to which the
/// contact terms are added: a StaticResidual for static equilibrium, an ImplicitStepResidual in
/// implicit dynamics.
using InnerResidualFactory = std::function<std::unique_ptr<NonlinearSystem>(double t, const VecX& u)>;

class ContactStaticSolver {
 public:
  /// Builds the contact surface and its grid, sets eps, and checks the bodies against the
  /// configuration u0 at t0: a body that penetrates a boundary node by more than initial_gap_tol
  /// is refused (tmlab::Error naming the body, the node and the depth). Nodes touching a bonded
  /// body at t0 are glued. The mesh and system must outlive the solver.
  ContactStaticSolver(const MechanicalSystem& system, const Mesh& mesh, std::vector<RigidBody> bodies,
                      ContactOptions options, NewtonOptions newton, double t0, const VecX& u0,
                      int max_cutbacks = 8);
  /// The same on the quadratic mesh `quadratic` of `mesh` when it is not null (the model's nodes are
  /// its points; contact at face quadrature points), else on `mesh`'s nodes. Both must outlive it.
  ContactStaticSolver(const MechanicalSystem& system, const Mesh& mesh, const QuadraticMesh* quadratic,
                      std::vector<RigidBody> bodies, ContactOptions options, NewtonOptions newton, double t0,
                      const VecX& u0, int max_cutbacks = 8);

  /// Equilibrium with contact at t_next from the accepted state at t_prev (u overwritten); the
  /// increment is halved up to max_cutbacks times when Newton or the outer loop fails, then
  /// tmlab::Error names the time reached.
  ContactStepReport advance(double t_prev, double t_next, VecX& u);

  /// One contact solve at t from the accepted state at t_from (no cut-backs; the model's
  /// begin_step/commit_step are the caller's): the outer loop around newton_solve of inner(t, u)
  /// plus the contact terms. Returns whether the stopping test held; then call accept(t, u).
  bool solve(double t, double t_from, VecX& u, ContactStepReport& report, const InnerResidualFactory& inner);
  /// Commits the multipliers (and glues the new contacts of bonded bodies) of the last successful
  /// solve at (t, u), and evaluates the outputs (state()).
  void accept(double t, const VecX& u);
  /// Implicit dynamics: the Newton matrix holds c_a M besides K, so an automatic eps is raised by
  /// stiffness_factor * c_a * (mean nodal mass over the boundary DOFs) to keep the Uzawa contraction
  /// (no effect when contact.stiffness is given).
  void add_mass_scale(double c_a);

  /// The linear solver of the Newton iterations: NewtonOptions::linear_solver at construction (a
  /// case's solver.linear: Eigen's LDL^T by default, or CHOLMOD with its LDL^T fallback), replaced here.
  void set_linear_solver(ConstrainedLinearSolver::Kind kind, double cg_rtol = 1e-12) {
    linear_ = std::make_unique<ConstrainedLinearSolver>(kind, cg_rtol);
  }
  /// Its kind and, for CHOLMOD, how many solves fell back to LDL^T (not positive definite).
  const ConstrainedLinearSolver& linear_solver() const { return *linear_; }
  double stiffness() const { return eps_; }  ///< eps, N/m (faces: eps_a, Pa/m)
  double gap_tol() const { return gap_tol_; }
  const ContactOptions& options() const { return options_; }
  const std::vector<RigidBody>& bodies() const { return bodies_; }
  const ContactSurface& surface() const { return surface_; }
  const ContactPoints& points() const { return points_; }
  const SurfaceGrid& grid() const { return grid_; }
  /// The outputs at the last accepted time (t0 before the first step: zero forces).
  const std::vector<ContactBodyState>& state() const { return state_; }

  /// Adds the contact terms at (u, t) with the trial multipliers: r += dPhi/du, J += d^2Phi/du^2,
  /// energy += Phi (each skipped when null). Used by the Newton residual; public for the tests.
  void add_contact_terms(const VecX& u, double t, VecX* r, SpMat* J, double* energy) const;

  /// Checkpoints (issue 12): the committed contact state (per body: multipliers, glued nodes,
  /// anchors and the candidate set, which the next increment's search keeps) as one array, exact.
  std::vector<double> committed_state() const;
  /// Restores what committed_state() returned, and the outputs at that time (state()); tmlab::Error
  /// when the array does not fit this surface and these bodies.
  void restore_committed_state(const std::vector<double>& data, std::vector<ContactBodyState> outputs);

 private:
  // Per constraint c (a node, or a quadratic face): lambda, bonded, candidates; per point q:
  // lambda_b, anchor (nodal: the constraint is its one point, so both are per node).
  struct BodyData {
    std::vector<double> lambda;     ///< normal multiplier per constraint (>= 0)
    std::vector<Vec3> lambda_b;     ///< bonded multiplier per contact point
    std::vector<char> bonded;       ///< glued constraints
    std::vector<Vec3> anchor;       ///< glued point in the body frame (relative to c(t)), per point
    std::vector<Index> candidates;  ///< constraints evaluated this outer iteration
  };

  void find_candidates(double t, double margin, const VecX& u);
  Vec3 position(const VecX& u, Index surface_local) const;
  std::vector<ContactBodyState> evaluate_state(double t, const VecX& u) const;
  void add_point_state(const RigidBody& body, const BodyData& d, double t, const VecX& u,
                       ContactBodyState& st) const;
  void check_initial(double t0, const VecX& u0);
  /// Quadratic faces: the terms of face c (see the header comment), as add_contact_terms.
  void add_face_terms(const RigidBody& body, const BodyData& d, double t, Index c, const VecX& u, VecX* r,
                      SpMat* J, double* energy) const;
  /// The weighted (mean) gap of face c, m.
  double face_gap(const RigidBody& body, double t, Index c, const VecX& u) const;

  const MechanicalSystem& system_;
  const Mesh& mesh_;
  const QuadraticMesh* quadratic_ = nullptr;
  std::vector<RigidBody> bodies_;
  ContactOptions options_;
  NewtonOptions newton_;
  int max_cutbacks_;
  ContactSurface surface_;
  ContactPoints points_;
  SurfaceGrid grid_;
  double eps_ = 0.0;
  double face_scale_ = 1.0;  ///< faces: eps_a = eps * face_scale_ (N_b / S, 1/m^2)
  double gap_tol_ = 0.0;
  std::vector<BodyData> committed_, trial_;
  std::vector<ContactBodyState> state_;
  std::unique_ptr<ConstrainedLinearSolver> linear_;
};

}  // namespace tmlab::tm
