// Contact with rigid bodies in the deal.II reference (docs/reference-fem.md, "Contact";
// docs/contact.md). The vertex rule is the fast model's ContactStaticSolver
// (tensormass/contact/contact_solver.hpp), applied at the mesh vertices of the reference's
// discretisation, so that on P1 tets both models solve the same discrete problem with the same
// algorithm:
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
// Two rules place the constraint (ContactRule; the runner uses Vertices for P1, FacePoints for P2):
//
//   Vertices (above): one gap per boundary vertex, lambda_i a force (N), eps in N/m. On P1 it is the
//     fast model's discrete problem. On P2 it leaves the edge nodes free, so between vertices the
//     quadratic surface bulges into the body and a uniform pressure is carried by the corners alone
//     (the consistent P2 load puts it on the midside nodes): measured on the seed-like indentation,
//     26.4 mN (8 cells) and 28.2 mN (16) against a converged 36.4 mN.
//   FacePoints: one constraint per boundary triangle f (P2: 3 corners + 3 midsides), evaluated at its
//     quadrature points q (Witherden-Vincent, 6 points, degree 4; w_q = reference area weights) at the
//     interpolated surface points x_q = sum_a N_a(xi_q) x_a: the face's weighted (mean) gap
//     g_f = sum_q w_q g_q / A_f (A_f = sum_q w_q) and one multiplier lambda_f, the face's contact
//     PRESSURE (Pa) (a mortar-style rule with a face-constant pressure, the fast model's):
//       Phi_k(u) = sum_f A_f/(2 eps_a) (<lambda_f - eps_a g_f(u)>_+^2 - lambda_f^2),
//     node a of f gets -p_f G_a, G_a = sum_q w_q N_a n_q, the tangent (eps_a/A_f) G_a G_b^T -
//     p_f sum_q w_q N_a N_b H_g (within the face's cell); update lambda_f <- <lambda_f - eps_a g_f>_+,
//     stopping test and gap_tol per face. eps_a = nodal * N_b / S, S = sum_f sum_a (sum_q w_q N_a)^2 /
//     A_f, N_b the boundary-face nodes, nodal = stiffness_factor x the mean K_0 diagonal over their
//     DoFs (or contact.stiffness, N/m). A uniform pressure gives the consistent load (P2: nothing on
//     the corners, a third of each face's force on each midside node). (One multiplier per point, 6
//     per face, three times the face nodes, made the constraints redundant: the Uzawa loop did not
//     settle on a sphere; docs/contact.md.) Bonded faces glue their points: per point
//     w_q (lambda_q . c_q + eps_a/2 |c_q|^2). Body force = sum_f lambda_f sum_q w_q n_q. The initial
//     checks (penetration, a body not touching, a rig larger than its mesh) stay on the vertices;
//     faces whose points all touch a bonded body at the start (the solid's current solution) are glued.
//
// MPI: every rank holds the whole boundary but evaluates only the vertices whose DoFs it owns (face
// points: those of the boundary faces of its own cells); counts, residuals and body totals are
// reduced over ranks.
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
  Vec3 position = Vec3::Zero();    ///< c(t)
  Vec3 force = Vec3::Zero();       ///< force the sample exerts on the body, N
  Vec3 moment = Vec3::Zero();      ///< of that force about c(t), N m
  int active_nodes = 0;            ///< active vertices (face rule: active face points)
  double area = 0.0;               ///< projected reference tributary area of the active vertices
                                   ///< (face rule: sum of w_q max(0, -N . n) over active points), m^2
  double radius_equivalent = 0.0;  ///< sqrt(area / pi) (sphere, punch; 0 for the plane)
  double radius_max = 0.0;         ///< largest distance of an active contact point from the axis, m
  double max_pressure = 0.0;       ///< largest (f . n) / projected tributary area, Pa
  double max_penetration = 0.0;    ///< max(0, -g) over the active vertices (points), m
  double complementarity = 0.0;    ///< max w lambda |g| (vertex: w = 1), N m
  double min_multiplier = 0.0;     ///< min w lambda, N
};

/// Where the constraint acts (see above).
enum class ContactRule { Vertices, FacePoints };
inline std::string to_string(ContactRule r) {
  return r == ContactRule::Vertices ? "vertices" : "face quadrature points";
}

class RigidContact final : public NodalConstraints {
 public:
  /// `node_dofs[i]`: the three DoFs of mesh node i's vertex where they are locally relevant (else
  /// numbers::invalid_dof_index); `owned[i]`: this rank owns them. `file` names the case in messages.
  RigidContact(const ContactSpec& spec, const std::string& file, const Mesh& mesh,
               std::vector<std::array<global_dof_index, 3>> node_dofs, std::vector<char> owned, MPI_Comm comm,
               ContactRule rule = ContactRule::Vertices);

  /// Face rule: the points of the boundary faces of the solid's own cells. Then eps from the
  /// unconstrained reference tangent K_0 of `solid` (or spec.stiffness; face rule: over the mean
  /// boundary area per vertex), then the
  /// start at t0 with all vertex displacements U0 (every rank the same): a body penetrating by more
  /// than initial_gap_tol, or farther than max_initial_gap from the sample, or larger than its mesh
  /// (the fast model's check_contact_rig: a punch whose radius, or a sphere whose Hertz contact
  /// radius sqrt(R d_max) at its deepest travel over [t0, t_end], reaches the sample's extent from
  /// the body's axis) is refused (tmlab::Error naming the case, the body's key, and the node and
  /// distance or the sizes); vertices (face points, at the solid's solution) touching a bonded body
  /// are glued.
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
  /// eps: N/m (vertices) or Pa/m (face points).
  double stiffness() const { return eps_; }
  ContactRule rule() const { return rule_; }
  /// The evaluation points of this rank (vertices it owns, or its face points).
  std::size_t n_points() const { return points_.size(); }
  double gap_tol() const { return gap_tol_; }
  double natural_residual() const { return natural_; }  ///< of the last update()

 private:
  /// One place the constraint acts: x = X + sum_a N[a] u(dofs[3a .. 3a+2]). Vertex: one node,
  /// N = {1}, w = 1; face point: the face's nodes, w = w_q.
  struct Site {
    std::vector<global_dof_index> dofs;
    std::vector<double> N;
    Vec3 X = Vec3::Zero();
    double w = 1.0;
    Vec3 normal = Vec3::Zero();  ///< face point: outward reference normal (for the projected area)
    std::size_t vertex = 0;      ///< vertex rule: boundary-local index (for the tributary area)
  };
  struct BodyData {
    std::vector<double> lambda;  ///< normal multiplier per vertex (N) or per face (face rule: Pa)
    std::vector<Vec3> lambda_b;  ///< bonded multiplier per point
    std::vector<char> bonded;    ///< per vertex or face
    std::vector<Vec3> anchor;    ///< glued point relative to c(t), per point
  };
  Vec3 position(const dealii::TrilinosWrappers::MPI::Vector& u_ghost, const Site& p) const;
  /// The face rule's points on the boundary faces of the solid's locally owned cells.
  void build_face_points(const Solid& solid);
  /// Face rule: the weighted (mean) gap of face f, m, and its terms (see the header comment).
  double face_gap(const ContactBodySpec& body, const dealii::TrilinosWrappers::MPI::Vector& u, double t,
                  std::size_t f) const;
  void add_face_terms(const ContactBodySpec& body, const BodyData& d, double t, std::size_t f,
                      const dealii::TrilinosWrappers::MPI::Vector& u,
                      dealii::TrilinosWrappers::MPI::Vector& r,
                      const dealii::AffineConstraints<double>* constraints,
                      dealii::TrilinosWrappers::SparseMatrix* K,
                      dealii::TrilinosWrappers::MPI::Vector* rhs) const;
  void allocate();
  /// eps of the vertex rule (N/m) and of the face rule (Pa/m); see the header comment.
  double vertex_stiffness(Solid& solid, double t0) const;
  double face_stiffness(Solid& solid, double t0) const;
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
  ContactRule rule_;
  std::vector<Site> points_;
  /// Face rule: face f (one constraint) holds the points group_[f] .. group_[f+1], of area group_area_[f].
  std::vector<std::size_t> group_;
  std::vector<double> group_area_;
  double eps_ = 0.0, gap_tol_ = 0.0, natural_ = 0.0;
  std::vector<BodyData> committed_, trial_;
};

}  // namespace tmlab::ref
