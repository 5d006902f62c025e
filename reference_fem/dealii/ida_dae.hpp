// The quasi-static viscoelastic reference problem as a differential-algebraic system, integrated by
// SUNDIALS IDA through deal.II 9.4's SUNDIALS::IDA<Vector<double>> (issue 5). The spatial
// discretisation, the material, the loads and the constraints are those of a Solid (solid.hpp); only
// the time discretisation differs from Solid::advance's fixed-step Prony recursion.
//
// State y = [U, Z]: U the displacement DoFs (algebraic), Z the internal variables z_j of every Prony
// term j at every quadrature point of every cell (six Voigt components each; differential). With
// S_r the relaxing stress of the Prony series (S_e, or S_dev = 2 mu dev E), the hereditary history
// of Solid is h_j = S_r - z_j, and the residual F(t, y, y') is
//
//   free DoF i:         F_i = int S_tot : sym(F^T Grad phi_i) dV - f_ext,i(t),
//                       S_tot = S_e(E) + sum_j alpha_j (S_r(E) - z_j)
//   prescribed DoF c:   F_c = U_c - g_c(t)
//   internal variable:  F_zj = z_j' - (S_r(E) - z_j) / tau_j      (per quadrature point, per term)
//
// (docs/reference-fem.md, "Time integration by IDA"). IDA's Newton matrix J = dF/dy + alpha dF/dy'
// has a diagonal Z-Z block ((alpha + 1/tau_j) I), so Z is eliminated exactly: the Schur complement
// on U is the reference's consistent tangent with D = D_e + sum_j alpha_j (1 - kappa_j) D_r,
// kappa_j = 1/(1 + alpha tau_j), factorised once per Jacobian setup by the reference's direct
// solver; each solve then back-substitutes the Z block. Serial only (one MPI rank).
#pragma once

#include "reference_fem/dealii/solid.hpp"

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/vector.h>

#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tmlab::ref {

/// IDA settings. The algebraic components (U) are left out of the local error test (they follow
/// from Z and t); their absolute tolerance still weights IDA's Newton convergence test.
struct IdaParameters {
  double rtol = 1e-6;
  double atol_u = 1e-9;       ///< m, on U
  double atol_z = 1e-3;       ///< Pa, on Z
  unsigned max_order = 5;     ///< BDF order limit
  unsigned max_newton = 4;    ///< Newton iterations per step attempt (the SUNDIALS default)
  double initial_step = 0.0;  ///< 0: the output interval / 100
  LinearSolver linear_solver = LinearSolver::Direct;  ///< direct (MUMPS) | direct_klu (direct solvers only)
};

/// What IDA did, counted in the callbacks: deal.II 9.4 keeps the IDA memory private, so the
/// numbers of IDAGetNumSteps & co. are reconstructed. A step attempt is a new time at which the
/// residual is evaluated; an attempt is accepted when the next one lies beyond it (after an error
/// test or convergence failure IDA retries a shorter step) and the last one is accepted when the
/// run completes. Newton iterations = solves with the Newton matrix (consistent initial values
/// included).
struct IdaStats {
  long steps = 0;
  long step_attempts = 0;
  long residual_evaluations = 0;
  long jacobian_setups = 0;
  long newton_iterations = 0;
  long recoverable_failures = 0;   ///< residuals refused (det F <= 0 or non-finite): IDA cuts the step
  long projection_iterations = 0;  ///< Newton iterations of the output projections (not IDA's)
  double residual_seconds = 0.0, jacobian_seconds = 0.0, solve_seconds = 0.0;  ///< IDA's callbacks
  double projection_seconds = 0.0;
};

class QuasiStaticDae {
 public:
  /// The DAE of `solid` (which must have Prony terms and run on one MPI rank; tmlab::Error
  /// otherwise). Builds the Newton matrix's sparsity; the solid's loads and constraints must be set.
  explicit QuasiStaticDae(Solid& solid);
  ~QuasiStaticDae();
  QuasiStaticDae(const QuasiStaticDae&) = delete;
  QuasiStaticDae& operator=(const QuasiStaticDae&) = delete;

  unsigned n_dofs() const { return n_dofs_; }
  std::size_t size() const { return n_dofs_ + n_z_; }

  /// y0 = [U0, Z0 = S_r(U0)] (no history) with U0 the solid's current solution.
  dealii::Vector<double> initial_state() const;
  /// F(t, y, y'); returns 0, or 1 (recoverable) when det F <= 0 or a value is not finite.
  int residual(double t, const dealii::Vector<double>& y, const dealii::Vector<double>& yp,
               dealii::Vector<double>& r);
  /// Assembles and factorises the Schur complement of dF/dy + alpha dF/dy' at (t, y).
  int setup_jacobian(double t, const dealii::Vector<double>& y, double alpha);
  /// x = J^{-1} b with the last setup's J.
  int solve_with_jacobian(const dealii::Vector<double>& b, dealii::Vector<double>& x);
  /// Equilibrium of U for the internal variables of y at time t (Z unchanged): Newton on the U rows
  /// until the correction is below 1e-3 of the displacement tolerance. Applied to IDA's output: IDA
  /// interpolates between its steps, and the algebraic U (out of the error test) then carries an
  /// uncontrolled interpolation error wherever the loads are not smooth (a ramp's end); Z's
  /// interpolant is error-controlled, and U(t) is a function of Z(t) and t.
  void project_to_equilibrium(double t, dealii::Vector<double>& y);
  /// Makes the solid's solution U and its committed history h_j = S_r(U) - z_j those of y, so that
  /// Solid::reactions(), elastic_energy() and cell_fields() report the state y.
  void apply_state(const dealii::Vector<double>& y);

  /// Integrates from t0 (state: initial_state(), made consistent by IDACalcIC) to t_end and calls
  /// output(k, t_k, y(t_k)) at t_k = t0 + k (t_end - t0) / n_outputs, k = 0..n_outputs, with y(t_k)
  /// IDA's interpolant projected to equilibrium (project_to_equilibrium).
  IdaStats integrate(double t0, double t_end, int n_outputs, const IdaParameters& parameters,
                     const std::function<void(int, double, const dealii::Vector<double>&)>& output);
  const IdaStats& stats() const { return stats_; }

 private:
  struct QpJacobian {  ///< what a solve needs of the last Jacobian setup, per quadrature point
    dealii::Tensor<2, 3> F;
    SymTensor4 D_r;
  };
  /// A factorised Newton matrix (Schur complement on U) with what its solves need. IDA's and the
  /// output projection's are kept apart, so that a projection never changes the matrix IDA uses.
  struct NewtonMatrix {
    dealii::TrilinosWrappers::SparseMatrix K;
    std::unique_ptr<dealii::TrilinosWrappers::SolverDirect> direct;
    std::vector<QpJacobian> qp;
    std::vector<double> kappa;  ///< 1 / (1 + alpha tau_j)
    double constrained_diagonal = 1.0;
  };
  void assemble_newton_matrix(const dealii::Vector<double>& y, double alpha, NewtonMatrix& m);
  void solve_newton(const NewtonMatrix& m, const dealii::Vector<double>& b, dealii::Vector<double>& x);
  std::size_t z_offset(unsigned cell, unsigned q, unsigned j) const {
    return n_dofs_ + ((static_cast<std::size_t>(cell) * n_q_ + q) * n_terms_ + j) * 6;
  }
  template <class Body>
  int guarded(Body&& body);

  Solid& solid_;
  const PronySeries prony_;
  unsigned n_dofs_ = 0, n_q_ = 0, n_terms_ = 0, n_cells_ = 0;
  std::size_t n_z_ = 0;
  double alpha_sum_ = 0.0;
  LinearSolver linear_solver_ = LinearSolver::Direct;
  dealii::TrilinosWrappers::MPI::Vector f_ext_, rhs_, du_;
  dealii::SolverControl control_;
  NewtonMatrix ida_matrix_, projection_matrix_;
  bool have_ida_matrix_ = false;
  double projection_tolerance_u_ = 1e-12, projection_rtol_ = 1e-9;  ///< set by integrate()
  double last_attempt_t_ = 0.0;
  bool have_attempt_ = false;
  double t0_ = 0.0;
  std::exception_ptr pending_;
  IdaStats stats_;
};

}  // namespace tmlab::ref
