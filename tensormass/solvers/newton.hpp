// Newton's method with a backtracking line search for R(u) = 0 under Dirichlet constraints, shared
// by the static solver and the implicit time integrators.
//
// Line search (docs/theory/newton.md). Where the system has a potential Pi with R = dPi/du
// (hyperelastic models under dead loads, and the incremental potential of an implicit step), the
// step length alpha is chosen by Armijo backtracking on Pi:
//   Pi(u + alpha du) <= Pi(u) + c1 alpha R(u).du + 16 eps (|Pi(u)| + |Pi(u + alpha du)|),
// or |R(u + alpha du)| <= (1 - c1 alpha) |R(u)| (near the solution the decrease of Pi is below its
// round-off, while |R| still falls quadratically), with quadratic interpolation of Pi for the next
// trial, clamped to [0.1, 0.5] alpha. The residual norm is
// not a merit function for large rotations: a good first Newton step of a bending beam raises |R|
// by orders of magnitude while lowering Pi, and backtracking on |R| rejects it. Without a potential
// (history-dependent forces, follower loads) the full step is taken unless the residual is
// non-finite (an element inverted), in which case the step is halved. The older residual-norm
// search is kept as an option (LineSearch::Residual).
//
// Round-off: when an iteration lowers |R| by less than a factor 2 and its step is below
// stagnation_tol * |u|_inf, the iteration has reached the round-off floor of the residual: it stops,
// as converged (at_roundoff = true) when |R| is within 1e3 of the target, else as not converged
// (stalled), instead of iterating to the limit either way.
//
// Constraints are imposed by elimination in place: the first iteration moves the constrained DOFs
// to their prescribed values (du_c = g(t) - u_c) and carries K_fc du_c to the right-hand side;
// rows and columns of constrained DOFs become identity rows, so the system stays symmetric and a
// sparse LDL^T factorisation applies (sparse LU for non-symmetric tangents, e.g. follower pressure).
#pragma once

#include "core/config/line_search.hpp"
#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/system/dirichlet.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include <memory>
#include <string>
#include <vector>

namespace tmlab::tm {

/// A nonlinear system R(u) = 0 with Jacobian dR/du (full size; constrained rows are ignored).
class NonlinearSystem {
 public:
  virtual ~NonlinearSystem() = default;
  virtual void residual(const VecX& u, VecX& r) = 0;
  virtual void jacobian(const VecX& u, SpMat& J) = 0;
  virtual bool symmetric() const = 0;
  /// A force scale for the relative tolerance when R(u0) happens to be ~0 (e.g. |f_ext|).
  virtual double force_scale() const = 0;
  /// A potential Pi(u) with R = dPi/du, when one exists: sets value and returns true. The default
  /// (no potential) makes the line search take full steps.
  virtual bool potential(const VecX& /*u*/, double& /*value*/) { return false; }
};

/// The linear solver of the Newton steps (a case's solver.linear; docs/performance.md, "Implicit
/// steps: CHOLMOD").
enum class NewtonLinearSolver {
  Direct,             ///< Eigen's SimplicialLDLT (SparseLU for non-symmetric tangents): the default
  ConjugateGradient,  ///< incomplete-Cholesky preconditioned CG (symmetric tangents only)
  /// SuiteSparse CHOLMOD's supernodal LL^T (Eigen's CholmodSupport), symbolic analysis reused while
  /// the pattern is unchanged. LL^T exists only for positive definite matrices: a tangent that is
  /// not (CHOLMOD meets a non-positive pivot: a buckling or softening state) is solved by the
  /// Direct LDL^T instead and counted (ConstrainedLinearSolver::fallbacks()); non-symmetric tangents
  /// (follower pressure) go to SparseLU as with Direct.
  Cholmod,
};

struct NewtonOptions {
  int max_iterations = 25;
  double rtol = 1e-10;                          ///< |R_free| <= rtol * max(|R_0|, force scale)
  double atol = 1e-14;                          ///< absolute floor on |R_free|, newtons
  LineSearch line_search = LineSearch::Energy;  ///< core/config/line_search.hpp
  int max_backtracks = 12;
  double stagnation_tol = 1e-13;  ///< relative step size below which a stalled residual is round-off
  NewtonLinearSolver linear_solver = NewtonLinearSolver::Direct;  ///< what StaticSolver/ImplicitDynamics use
};

struct NewtonResult {
  bool converged = false;
  int iterations = 0;
  int backtracks = 0;
  double residual_initial = 0.0;
  double residual_final = 0.0;
  double target = 0.0;          ///< the convergence threshold rtol * scale + atol that applied
  bool at_roundoff = false;     ///< converged by the round-off stagnation test, above target
  bool stalled = false;         ///< stopped because a step changed nothing (converged or not)
  std::vector<double> history;  ///< |R_free| per iteration (history[0] before the first step)
  std::vector<double> alphas;   ///< accepted step length per iteration
};

/// Solves J du = rhs on the free DOFs with du prescribed on the constrained ones. Direct (the
/// default): sparse LDL^T (LU for non-symmetric tangents), reusing the symbolic factorisation while
/// the sparsity pattern is unchanged. Conjugate gradients: incomplete-Cholesky preconditioned CG to
/// |r| <= cg_rtol |b|, for symmetric tangents too large to factorise (LDL^T fill-in grows fast in
/// 3-D beyond ~2e4 DOFs); inexact Newton: Newton's own test decides convergence.
class ConstrainedLinearSolver {
 public:
  using Kind = NewtonLinearSolver;
  ConstrainedLinearSolver();
  explicit ConstrainedLinearSolver(Kind kind, double cg_rtol = 1e-12);
  ~ConstrainedLinearSolver();
  ConstrainedLinearSolver(const ConstrainedLinearSolver&) = delete;  // Eigen's factorisations are not
  ConstrainedLinearSolver& operator=(const ConstrainedLinearSolver&) = delete;

  /// Throws tmlab::Error when the factorisation fails (singular: e.g. an unconstrained body), when
  /// CG does not converge, or when CG is asked to solve a non-symmetric system.
  void solve(const SpMat& J, const VecX& rhs, const DirichletSet& bc, const VecX& du_c, bool symmetric,
             VecX& du);
  /// CG iterations of the last solve (0 for the direct solver).
  int last_iterations() const { return last_iterations_; }
  Kind kind() const { return kind_; }
  /// Cholmod: how many solves found the tangent not positive definite and used LDL^T instead.
  int fallbacks() const { return fallbacks_; }

 private:
  struct Cholmod;  // CHOLMOD's factor (newton.cpp: cholmod.h stays out of this header)
  Kind kind_ = Kind::Direct;
  double cg_rtol_ = 1e-12;
  int last_iterations_ = 0;
  int fallbacks_ = 0;
  SpMat A_;
  Eigen::SimplicialLDLT<SpMat> ldlt_;
  Eigen::SparseLU<SpMat> lu_;
  std::unique_ptr<Cholmod> cholmod_;
  // The pattern (its number of non-zeros) each factorisation last analysed: the symbolic analysis
  // is reused while it is unchanged.
  Eigen::Index ldlt_nnz_ = -1, lu_nnz_ = -1;
};

/// Newton iteration from u (overwritten with the solution). `t` is the time at which the
/// constraints are evaluated. Throws tmlab::Error on a non-finite residual; returns
/// converged = false (with the history) when the iteration limit is reached.
NewtonResult newton_solve(NonlinearSystem& system, const DirichletSet& bc, double t, VecX& u,
                          const NewtonOptions& options, ConstrainedLinearSolver& linear);

}  // namespace tmlab::tm
