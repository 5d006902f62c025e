// Node-to-rigid contact in the deal.II reference (docs/reference-fem.md, "Contact"; docs/contact.md):
// the rule of the fast model's ContactStaticSolver (tensormass/contact/contact_solver.hpp), applied
// at the mesh vertices of the reference's discretisation, so that on P1 tets both models solve the
// same discrete problem with the same algorithm:
//
//   frictionless vertex i, body b:  g_i(u) >= 0, lambda_i >= 0, lambda_i g_i = 0, through
//     Phi_k(u) = sum_i 1/(2 eps) (<lambda_i^k - eps g_i(u)>_+^2 - (lambda_i^k)^2)
//     added to the potential of the Newton solve, then lambda_i^{k+1} = <lambda_i^k - eps g_i(u_k)>_+;
//   bonded vertex i:  c_i(u) = x_i - (a_i + c(t)) = 0 through Phi_k = lambda_i^k . c_i + eps/2 |c_i|^2,
//     then lambda_i^{k+1} = lambda_i^k + eps c_i(u_k).
// The outer (Uzawa) loop stops on the fast model's test: natural complementarity residual
// max |lambda^{k+1} - lambda^k| / eps (|c|_inf bonded) <= gap_tol and no active-set change (ignoring
// multipliers below eps gap_tol in both iterations). eps and gap_tol have the fast model's
// defaults: eps = stiffness_factor * mean diagonal of the reference tangent K_0 over the boundary
// vertex DoFs, gap_tol = 1e-8 * mean boundary edge. Penalty: one solve with lambda = 0.
//
// Differences from the fast model, none of which changes the converged answer: every boundary
// vertex is evaluated in every iteration (no candidate grid; the fast model's detection test (3)
// therefore always holds), and the contact forces do not enter reactions() (the Dirichlet
// reactions are f_int - f_ext on the condition's DoFs).
//
// P2: the rule constrains the vertices only (the same nodes and tributary areas as P1); the edge
// nodes are free, so between vertices the P2 surface may bulge into the body by O(h^2 curvature).
// It is the P1 rule on the P2 field, not a consistent quadratic contact discretisation.
//
// MPI: every rank holds the whole boundary but evaluates only the vertices whose DoFs it owns;
// counts, residuals and body totals are reduced over ranks.
#pragma once

#include "core/config/contact_spec.hpp"
#include "core/mesh/mesh.hpp"
#include "reference_fem/dealii/contact_geometry.hpp"
#include "reference_fem/dealii/solid.hpp"

#include <array>
#include <string>
#include <vector>

namespace tmlab::ref {

/// The contact outputs of one body at one time (the fast model's ContactBodyState totals).
struct ContactBodyOutput {
  std::string name;
  Vec3 position = Vec3::Zero();  ///< c(t)
  Vec3 force = Vec3::Zero();     ///< force the sample exerts on the body, N
  Vec3 moment = Vec3::Zero();    ///< of that force about c(t), N m
  int active_nodes = 0;
  double area = 0.0;               ///< projected reference tributary area of the active vertices, m^2
  double radius_equivalent = 0.0;  ///< sqrt(area / pi) (sphere, punch; 0 for the plane)
  double radius_max = 0.0;         ///< largest distance of an active contact point from the axis, m
  double max_pressure = 0.0;       ///< largest (f . n) / projected tributary area, Pa
  double max_penetration = 0.0;    ///< max(0, -g) over the active vertices, m
  double complementarity = 0.0;    ///< max lambda |g|, N m
  double min_multiplier = 0.0;
};

class NodalContact final : public NodalConstraints {
 public:
  /// `node_dofs[i]`: the three DoFs of mesh node i's vertex where they are locally relevant (else
  /// numbers::invalid_dof_index); `owned[i]`: this rank owns them. `file` names the case in messages.
  NodalContact(const ContactSpec& spec, const std::string& file, const Mesh& mesh,
               std::vector<std::array<global_dof_index, 3>> node_dofs, std::vector<char> owned,
               MPI_Comm comm);

  /// eps from the unconstrained reference tangent K_0 of `solid` (or spec.stiffness), then the
  /// start at t0 with all vertex displacements U0 (every rank the same): a body penetrating by more
  /// than initial_gap_tol, or farther than max_initial_gap from the sample, or larger than its mesh
  /// (the fast model's check_contact_rig: a punch whose radius, or a sphere whose Hertz contact
  /// radius sqrt(R d_max) at its deepest travel over [t0, t_end], reaches the sample's extent from
  /// the body's axis) is refused (tmlab::Error naming the case, the body's key, and the node and
  /// distance or the sizes); vertices touching a bonded body are glued.
  void start(Solid& solid, double t0, double t_end, const std::vector<double>& U0);

  void add_terms(const dealii::TrilinosWrappers::MPI::Vector& u_ghost, double t,
                 dealii::TrilinosWrappers::MPI::Vector& r,
                 const dealii::AffineConstraints<double>* constraints,
                 dealii::TrilinosWrappers::SparseMatrix* K,
                 dealii::TrilinosWrappers::MPI::Vector* rhs) const override;
  double energy(const dealii::TrilinosWrappers::MPI::Vector& u_ghost, double t) const override;
  void begin_increment() override { trial_ = committed_; }
  bool update(const dealii::TrilinosWrappers::MPI::Vector& u_ghost, double t) override;
  void commit(const dealii::TrilinosWrappers::MPI::Vector& u_ghost, double t) override;
  int max_outer_iterations() const override { return spec_.max_outer_iterations; }
  /// "case.json: key 'contact' (key 'contact.bodies[0]' (sphere 'indenter')): the augmented-Lagrangian
  /// outer loop (at most N outer iterations per increment, gap_tol G m, last natural residual R m)".
  std::string describe() const override;

  /// Per body, reduced over ranks, at u (the committed state after commit()).
  std::vector<ContactBodyOutput> outputs(const dealii::TrilinosWrappers::MPI::Vector& u_ghost,
                                         double t) const;
  double stiffness() const { return eps_; }
  double gap_tol() const { return gap_tol_; }
  double natural_residual() const { return natural_; }  ///< of the last update()

 private:
  struct BodyData {
    std::vector<double> lambda;  ///< normal multiplier per boundary vertex
    std::vector<Vec3> lambda_b;  ///< bonded multiplier
    std::vector<char> bonded;
    std::vector<Vec3> anchor;  ///< glued point relative to c(t)
  };
  Vec3 position(const dealii::TrilinosWrappers::MPI::Vector& u_ghost, std::size_t k) const;
  /// Refuses a punch or sphere larger than the mesh (see start()); g0 the body's smallest gap at t0.
  void check_extent(const ContactBodySpec& body, double g0, double t0, double t_end,
                    const std::vector<double>& U0) const;

  ContactSpec spec_;
  std::string file_;
  const Mesh& mesh_;
  std::vector<std::array<global_dof_index, 3>> node_dofs_;
  std::vector<char> owned_;
  MPI_Comm comm_;
  ContactBoundary boundary_;
  std::vector<std::size_t> mine_;  ///< boundary-local indices of the vertices this rank owns
  double eps_ = 0.0, gap_tol_ = 0.0, natural_ = 0.0;
  std::vector<BodyData> committed_, trial_;
};

}  // namespace tmlab::ref
