// The reference solver proper (deal.II types): quasi-static, total-Lagrangian, finite-strain
// equilibrium of a hyperelastic (optionally Prony-viscoelastic) body, solved by Newton's method with
// the consistent tangent and a backtracking line search, distributed with MPI.
//
// It knows nothing about case files: a driver (reference_runner.cpp, or a test) builds the serial
// coarse mesh, constructs a Solid, asks it for its DoFHandler to resolve boundary conditions and
// loads into prescribed DoFs, point forces, pressure faces and body forces, then calls advance().
//
// Weak form (reference configuration Omega_0, boundary Gamma_0, test functions v):
//   R(u; v) = int_Omega0 S(E(u)) : sym(F^T Grad v) dV - int_Omega0 b0 . v dV
//             + int_Gamma_p p(t) N . v dA - sum_points f_i . v(X_i) = 0,
// F = I + Grad u, E = (F^T F - I)/2. Its derivative in direction du is the tangent
//   K(u)[du, v] = int ( sym(F^T Grad v) : D : sym(F^T Grad du) + Grad v S : Grad du ) dV
// (material plus geometric stiffness); the external loads are dead loads (independent of u).
//
// Mean dilatation (Discretisation::mean_dilatation; the fast model's p2_mean_dilatation element,
// docs/elements.md): per cell, one volume change Jbar = int J dV / int dV replaces each point's, and
// the law sees Fbar = (Jbar / J)^{1/3} F (F-bar). The cell energy int W(Ebar) dV is then a function of
// all the cell's DoFs at once, so force and tangent are assembled per cell (solid.cpp, "Mean
// dilatation"; the tangent is dense in the cell's DoFs, and the sparsity pattern stays the element's).
#pragma once

#include "core/config/line_search.hpp"
#include "core/config/time_function.hpp"
#include "reference_fem/dealii/materials.hpp"
#include "reference_fem/dealii/reference_options.hpp"

#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/quadrature_point_data.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace tmlab::ref {

using dealii::types::global_dof_index;

/// Discretisation: element family and degree.
struct Discretisation {
  bool simplex = true;  ///< FE_SimplexP + QGaussSimplex + MappingFE; false: FE_Q + QGauss + MappingQ1
  unsigned degree = 1;  ///< 1 or 2
  /// F-bar with one mean dilatation per cell (the fast model's p2_mean_dilatation); elastic only (no
  /// Prony history). For P1 tets F is constant per cell, so it changes nothing there.
  bool mean_dilatation = false;
};

/// Newton and linear-solver parameters (step-44 keeps these in parameter structs; so do we).
struct NewtonParameters {
  int max_iterations = 25;
  double rtol = 1e-10;  ///< |R_free| <= rtol * max(|R_0|, |f_ext|, |R after moving the constraints|) + atol
  double atol = 1e-14;  ///< newtons
  /// Energy (default): Armijo on the potential Pi = int W dV - f_ext . u where one exists (no Prony
  /// history; the loads here are dead), a falling |R| accepted too, else full steps; Residual:
  /// sufficient decrease of |R_free| only; None: full steps (core/config/line_search.hpp).
  LineSearch line_search = LineSearch::Energy;
  int max_backtracks = 12;
  double stagnation_tol = 1e-13;  ///< relative step below which a stalled |R| is round-off
  int max_cutbacks = 8;           ///< halvings of a load increment whose Newton solve fails
  LinearSolver linear_solver = LinearSolver::Direct;  ///< direct | direct_klu | cg_amg
  double cg_rtol = 1e-8;  ///< CG: |r| <= cg_rtol |b| (inexact Newton: the Newton test decides)
};

/// Constraints at the mesh vertices imposed by a method with an outer loop around Newton (the nodal
/// augmented-Lagrangian contact, contact.hpp). During advance() the Solid adds their terms to every
/// residual, tangent and potential of its Newton solves, and runs the outer loop of each
/// (sub-)increment: begin_increment(), then Newton and update() until update() says done.
class NodalConstraints {
 public:
  virtual ~NodalConstraints() = default;
  /// At the ghosted displacement u: r += dPhi/du (rows this rank owns); with K, the 3x3 blocks
  /// d^2Phi/du^2 and -dPhi/du through `constraints` into K and rhs (as the cell terms).
  virtual void add_terms(const dealii::TrilinosWrappers::MPI::Vector& u_ghost, double t,
                         dealii::TrilinosWrappers::MPI::Vector& r,
                         const dealii::AffineConstraints<double>* constraints,
                         dealii::TrilinosWrappers::SparseMatrix* K,
                         dealii::TrilinosWrappers::MPI::Vector* rhs) const = 0;
  /// Phi(u), summed over ranks (added to the potential of the energy line search).
  virtual double energy(const dealii::TrilinosWrappers::MPI::Vector& u_ghost, double t) const = 0;
  /// A new (sub-)increment starts from the committed multipliers.
  virtual void begin_increment() = 0;
  /// After a converged Newton solve at t: the multiplier update; true when the stopping test holds.
  virtual bool update(const dealii::TrilinosWrappers::MPI::Vector& u_ghost, double t) = 0;
  /// The (sub-)increment to t is accepted at u.
  virtual void commit(const dealii::TrilinosWrappers::MPI::Vector& u_ghost, double t) = 0;
  virtual int max_outer_iterations() const = 0;
  /// What the constraints are, for the error when an increment does not converge (names the case
  /// file's key).
  virtual std::string describe() const = 0;
};

/// Per-step statistics, for the summary and docs/performance.md.
struct StepStats {
  double t = 0.0;
  int newton_iterations = 0;
  int linear_iterations = 0;  ///< CG iterations (0 for the direct solver)
  int backtracks = 0;
  int cutbacks = 0;
  int sub_increments = 0;         ///< accepted (sub-)increments (1 without cut-backs)
  int outer_iterations = 0;       ///< Newton solves of the nodal constraints' outer loops (0 without)
  bool at_roundoff = false;       ///< a sub-increment converged by the round-off stagnation test
  double assembly_seconds = 0.0;  ///< tangent + residual assembly
  double solve_seconds = 0.0;     ///< linear solves (factorisation or AMG setup included)
  double newton_seconds = 0.0;    ///< the whole step
  std::vector<double> residuals;  ///< |R_free| per iteration of the last (sub-)increment
};

class Solid {
 public:
  /// Partitions `coarse` (the same on every rank; METIS) into a fully distributed triangulation on
  /// `comm`, distributes DoFs and allocates the quadrature-point history when `prony` is given.
  Solid(MPI_Comm comm, dealii::Triangulation<3>& coarse, const Discretisation& disc, const Material& material,
        std::optional<PronySeries> prony, const NewtonParameters& newton, std::ostream* log = nullptr);
  ~Solid();

  MPI_Comm communicator() const { return comm_; }
  const dealii::DoFHandler<3>& dof_handler() const { return dof_handler_; }
  const dealii::Triangulation<3>& triangulation() const { return tria_; }
  const dealii::FESystem<3>& fe() const { return *fe_; }
  const dealii::Mapping<3>& mapping() const { return *mapping_; }
  const Discretisation& discretisation() const { return disc_; }
  const dealii::IndexSet& locally_owned_dofs() const { return owned_; }
  const dealii::IndexSet& locally_relevant_dofs() const { return relevant_; }
  global_dof_index n_dofs() const { return dof_handler_.n_dofs(); }
  const Material& material() const { return material_; }

  // ---- Problem definition (call before the first advance(); every rank for its own DoFs). ----
  /// A Dirichlet condition u_d(t) = value_d * f(t) for its DoFs; returns its index.
  int add_condition(const std::string& name, const TimeFunction& f);
  /// Prescribes DoF `dof` (component `component`) under condition k. Call for every locally relevant
  /// DoF of the condition; a DoF already prescribed keeps its first condition.
  void prescribe(global_dof_index dof, unsigned component, int condition, double value);
  /// A load time function; returns its index for the load entries below.
  int add_load_function(const TimeFunction& f);
  /// A point force f * value on a locally owned DoF.
  void add_point_force(global_dof_index dof, int load, double value);
  /// Dead pressure p * f(t) on a face of a locally owned cell (positive into the body).
  void add_pressure(const dealii::CellId& cell, unsigned face, int load, double pressure);
  /// Dead traction vector t * f(t) (per unit reference area) on a face of a locally owned cell.
  void add_traction(const dealii::CellId& cell, unsigned face, int load,
                    const dealii::Tensor<1, 3>& traction);
  /// Body force per unit reference volume b0(X) * f(t) (gravity: rho g).
  void add_body_force(std::function<dealii::Tensor<1, 3>(const dealii::Point<3>&)> b0, int load);
  /// Nodal constraints (contact) for the following advance() calls; null removes them. Not owned.
  void set_nodal_constraints(NodalConstraints* c) { nodal_ = c; }
  /// Builds the constraints and the sparsity pattern; called by the first advance() if needed.
  void finalize_setup();

  // ---- Solution. ----
  /// Equilibrium at t1 from the committed equilibrium at t0, halving the increment up to
  /// max_cutbacks times when Newton fails; commits the history once per accepted (sub-)increment.
  StepStats advance(double t0, double t1);

  // ---- Quantities of the current (committed) state. ----
  const dealii::TrilinosWrappers::MPI::Vector& solution() const { return u_ghost_; }
  /// Stored energy, summed over ranks: int W(E) dV (long-term spring) plus, with Prony terms, the
  /// branch energies int sum_j alpha_j/2 h_j : C0^-1 : h_j dV of the committed history.
  double elastic_energy() const;
  /// int W(E(u)) dV over all ranks for any ghosted displacement u (no history terms): the
  /// hyperelastic part of the potential the Newton line search decreases.
  double hyperelastic_energy(const dealii::TrilinosWrappers::MPI::Vector& u_ghost) const;
  /// Smallest det F over the quadrature points of all ranks (the displacement's F, also with mean
  /// dilatation, whose Fbar needs every det F > 0).
  double min_volume_ratio() const;
  /// Reaction of each condition: sum over its DoFs of f_int - f_ext at time t (summed over ranks).
  std::vector<dealii::Tensor<1, 3>> reactions(double t) const;
  int n_conditions() const { return static_cast<int>(conditions_.size()); }
  const std::string& condition_name(int k) const { return conditions_[k].name; }
  /// Cell averages of det F and of the von Mises Cauchy stress, per active cell (for output; with mean
  /// dilatation the stress of Fbar, and the mean det F is Jbar).
  void cell_fields(dealii::Vector<float>& volume_ratio, dealii::Vector<float>& von_mises) const;

  /// Global residual f_int(u) - f_ext(t) (unconstrained) and, when K is given, the tangent
  /// (unconstrained, full). For tests: a finite-difference check of the consistent tangent.
  void residual_and_tangent(const dealii::TrilinosWrappers::MPI::Vector& u_owned, double t, double dt,
                            dealii::TrilinosWrappers::MPI::Vector& r,
                            dealii::TrilinosWrappers::SparseMatrix* K);
  const dealii::TrilinosWrappers::SparseMatrix& tangent_matrix() const { return K_; }
  /// Overwrites the current state (tests; the IDA driver's output).
  void set_solution(const dealii::TrilinosWrappers::MPI::Vector& u_owned);

  // ---- Access for other time integrators (ida_dae.hpp): the same problem, integrated elsewhere. ----
  const dealii::Quadrature<3>& quadrature() const { return qcell_; }
  const std::optional<PronySeries>& prony() const { return prony_; }
  /// f_ext(t): body forces, dead pressure and tractions, point forces (owned entries; compressed).
  void external_force(double t, dealii::TrilinosWrappers::MPI::Vector& f);
  /// The prescribed DoFs (one entry per DoF, the owning condition's value) and their values g(t).
  std::vector<std::pair<global_dof_index, double>> prescribed_values(double t);
  /// Overwrites the committed Prony history of every quadrature point of the owned cells with
  /// f(cell, q, state) (reactions(), elastic_energy() and cell_fields() then use it).
  void set_history(const std::function<void(const dealii::Triangulation<3>::active_cell_iterator&, unsigned,
                                            PronyState&)>& f);

 private:
  struct Condition {
    std::string name;
    TimeFunction f;
  };
  struct Prescribed {
    global_dof_index dof;
    unsigned component;
    int condition;
    double value;
  };
  struct PointForce {
    global_dof_index dof;
    int load;
    double value;
  };
  struct Pressure {
    dealii::CellId cell;
    unsigned face;
    int load;
    double p;                       ///< pressure (along -N)
    dealii::Tensor<1, 3> traction;  ///< plus a traction vector (zero for a pure pressure)
  };
  struct BodyForce {
    std::function<dealii::Tensor<1, 3>(const dealii::Point<3>&)> b0;
    int load;
  };
  struct QPData {
    PronyState prony;
  };
  /// int W(E(u)) dV over all ranks, plus the Maxwell-branch energies of the committed history when
  /// with_history (elastic_energy() and hyperelastic_energy() are this one loop).
  double stored_energy(const dealii::TrilinosWrappers::MPI::Vector& u_ghost, bool with_history) const;
  enum class Mode { Residual, ResidualAndTangent, External };

  /// Assembles r = f_int(u) - f_ext(t) and, in ResidualAndTangent mode, the tangent into K_ with
  /// `constraints` applied (and their inhomogeneities into rhs_ = -r). Updates the trial history.
  void assemble(const dealii::TrilinosWrappers::MPI::Vector& u_ghost, double t, double dt, Mode mode,
                const dealii::AffineConstraints<double>* constraints,
                dealii::TrilinosWrappers::MPI::Vector& r, dealii::TrilinosWrappers::SparseMatrix* K,
                dealii::TrilinosWrappers::MPI::Vector* rhs);
  double free_norm(const dealii::TrilinosWrappers::MPI::Vector& r) const;
  bool newton(double t, double dt, dealii::TrilinosWrappers::MPI::Vector& u_owned, StepStats& stats);
  /// Newton, or with nodal constraints their outer loop of Newton solves and updates.
  bool solve(double t, double dt, dealii::TrilinosWrappers::MPI::Vector& u_owned, StepStats& stats);
  /// The first iteration's constraints: du_c = g(t) - u on the Dirichlet DoFs (into `first` as
  /// inhomogeneities and into du_c); returns max |du_c| over all ranks.
  double prescribed_increments(double t, const dealii::TrilinosWrappers::MPI::Vector& u_ghost,
                               dealii::AffineConstraints<double>& first,
                               dealii::TrilinosWrappers::MPI::Vector& du_c) const;
  /// The Newton step du: K du = -R at u under `constraints` (their inhomogeneities applied).
  void newton_direction(double t, double dt, const dealii::TrilinosWrappers::MPI::Vector& u_owned,
                        const dealii::AffineConstraints<double>& constraints,
                        dealii::TrilinosWrappers::MPI::Vector& du, StepStats& stats);
  int linear_solve(dealii::TrilinosWrappers::MPI::Vector& du,
                   const dealii::TrilinosWrappers::MPI::Vector& rhs);
  void commit(double dt);
  double load_factor(int load, double t) const { return load_functions_[load](t); }

  MPI_Comm comm_;
  std::ostream* log_;
  dealii::parallel::fullydistributed::Triangulation<3> tria_;
  Discretisation disc_;
  std::unique_ptr<dealii::FESystem<3>> fe_;
  std::unique_ptr<dealii::Mapping<3>> mapping_;
  dealii::Quadrature<3> qcell_;
  dealii::Quadrature<2> qface_;
  dealii::DoFHandler<3> dof_handler_;
  dealii::IndexSet owned_, relevant_;
  Material material_;
  std::optional<PronySeries> prony_;
  NewtonParameters newton_;
  dealii::CellDataStorage<typename dealii::Triangulation<3>::cell_iterator, QPData> qp_data_;

  std::vector<Condition> conditions_;
  std::vector<Prescribed> prescribed_;  ///< locally relevant constrained DoFs
  std::vector<TimeFunction> load_functions_;
  std::vector<PointForce> point_forces_;
  std::vector<Pressure> pressures_;
  std::vector<BodyForce> body_forces_;
  bool setup_done_ = false;
  NodalConstraints* nodal_ = nullptr;
  bool nodal_active_ = false;  ///< inside advance(): the assembly adds the nodal terms

  dealii::AffineConstraints<double> hom_constraints_;  ///< du = 0 on the Dirichlet DoFs
  dealii::TrilinosWrappers::SparseMatrix K_;
  dealii::TrilinosWrappers::MPI::Vector u_, u_ghost_;  ///< committed state (owned / ghosted)
  double t_committed_ = 0.0;
};

/// Builds a serial coarse triangulation from linear tets (vertex i = point i, cell c = tet c,
/// tets positively oriented as in tmlab::Mesh). Points used by no tet stay unused vertices.
void build_tet_triangulation(const std::vector<dealii::Point<3>>& points,
                             const std::vector<std::array<unsigned, 4>>& tets,
                             dealii::Triangulation<3>& tria);

/// For each locally owned or ghost cell of `solid`, the coarse-mesh vertex index of each of its
/// vertices: the coarse (serial) triangulation's cell with the same coarse id, checked by coordinates.
/// Returns a map keyed by active_cell_index() (size n_active_cells, empty rows for artificial cells).
std::vector<std::vector<unsigned>> coarse_vertex_map(const Solid& solid,
                                                     const dealii::Triangulation<3>& coarse);

}  // namespace tmlab::ref
