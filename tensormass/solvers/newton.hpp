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

/// The linear solver of the Newton steps (a case's solver.linear; docs/theory/newton.md, "Linear
/// solves", and docs/performance.md, "Implicit steps: CHOLMOD").
enum class NewtonLinearSolver {
  Direct,             ///< Eigen's SimplicialLDLT (SparseLU for non-symmetric tangents)
  ConjugateGradient,  ///< incomplete-Cholesky preconditioned CG (symmetric tangents only)
  /// The default (a case's "auto"; "cholmod" names it too): SuiteSparse CHOLMOD's supernodal LL^T
  /// (Eigen's CholmodSupport), its symbolic analysis done once per sparsity pattern and reused across
  /// Newton iterations and steps. LL^T exists only for positive definite matrices: a tangent that is
  /// not (CHOLMOD meets a non-positive pivot) is solved by the Direct LDL^T instead, and counted by
  /// reason (LinearSolveStats); non-symmetric tangents (follower pressure) go to SparseLU as with
  /// Direct.
  Cholmod,
};

/// What the solves of a ConstrainedLinearSolver did (summary.json's solver.linear_solver block).
struct LinearSolveStats {
  long solves = 0;          ///< every solve
  long cholmod_solves = 0;  ///< by CHOLMOD's LL^T
  long ldlt_solves = 0;     ///< by Eigen's LDL^T (Direct, or a Cholmod fallback)
  long lu_solves = 0;       ///< non-symmetric tangents (SparseLU)
  long cg_solves = 0;       ///< conjugate gradients
  /// Symbolic analyses (orderings, elimination trees): one per sparsity pattern met, per factorisation.
  long cholmod_analyses = 0, ldlt_analyses = 0, lu_analyses = 0;
  /// Cholmod fallbacks to LDL^T, by reason. `indefinite`: LDL^T's D has negative entries, so the
  /// tangent itself has that many negative eigenvalues (Sylvester's law of inertia); `round_off`:
  /// D is positive, CHOLMOD met a non-positive pivot of a (nearly singular) positive definite matrix.
  long fallbacks_indefinite = 0, fallbacks_round_off = 0;
  Eigen::Index max_negative_pivots = 0;  ///< the most negative pivots of one fallback's LDL^T
  /// Fallbacks by the Newton iteration that asked for the solve: [0] the first iteration of a solve,
  /// [1] the second, ...; the last entry counts that iteration and every later one.
  std::vector<long> fallbacks_by_iteration = std::vector<long>(4, 0);

  long fallbacks() const { return fallbacks_indefinite + fallbacks_round_off; }
};

struct NewtonOptions {
  int max_iterations = 25;
  double rtol = 1e-10;                          ///< |R_free| <= rtol * max(|R_0|, force scale)
  double atol = 1e-14;                          ///< absolute floor on |R_free|, newtons
  LineSearch line_search = LineSearch::Energy;  ///< core/config/line_search.hpp
  int max_backtracks = 12;
  double stagnation_tol = 1e-13;  ///< relative step size below which a stalled residual is round-off
  /// What StaticSolver, ImplicitDynamics and the contact solvers use: CHOLMOD with the LDL^T fallback.
  NewtonLinearSolver linear_solver = NewtonLinearSolver::Cholmod;
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

/// Solves J du = rhs on the free DOFs with du prescribed on the constrained ones. Cholmod (the
/// default): CHOLMOD's supernodal LL^T, Eigen's LDL^T where the tangent is not positive definite,
/// sparse LU for non-symmetric tangents. Direct: sparse LDL^T (LU for non-symmetric tangents). Each
/// reuses its symbolic factorisation while the sparsity pattern (row and column indices, compared in
/// full) is unchanged. Conjugate gradients: incomplete-Cholesky preconditioned CG to
/// |r| <= cg_rtol |b|, for symmetric tangents too large to factorise (LDL^T fill-in grows fast in
/// 3-D beyond ~2e4 DOFs); inexact Newton: Newton's own test decides convergence.
class ConstrainedLinearSolver {
 public:
  using Kind = NewtonLinearSolver;
  ConstrainedLinearSolver();  ///< Kind::Cholmod, the default
  explicit ConstrainedLinearSolver(Kind kind, double cg_rtol = 1e-12);
  ~ConstrainedLinearSolver();
  ConstrainedLinearSolver(const ConstrainedLinearSolver&) = delete;  // Eigen's factorisations are not
  ConstrainedLinearSolver& operator=(const ConstrainedLinearSolver&) = delete;

  /// Throws tmlab::Error when the factorisation fails (singular: e.g. an unconstrained body), when
  /// CG does not converge, or when CG is asked to solve a non-symmetric system. `newton_iteration`
  /// (0 for the first of a Newton solve; -1 unknown) files a fallback under its iteration.
  void solve(const SpMat& J, const VecX& rhs, const DirichletSet& bc, const VecX& du_c, bool symmetric,
             VecX& du, int newton_iteration = -1);
  /// CG iterations of the last solve (0 for the direct solver).
  int last_iterations() const { return last_iterations_; }
  Kind kind() const { return kind_; }
  /// Cholmod: how many solves found the tangent not positive definite and used LDL^T instead.
  int fallbacks() const { return static_cast<int>(stats_.fallbacks()); }
  /// Every solve so far, by solver, the symbolic analyses and the fallbacks by reason.
  const LinearSolveStats& stats() const { return stats_; }

 private:
  struct Cholmod;  // CHOLMOD's factor (newton.cpp: cholmod.h stays out of this header)
  /// The sparsity pattern a factorisation last analysed: its symbolic analysis is reused while A_'s
  /// pattern equals it.
  struct Pattern {
    std::vector<SpMat::StorageIndex> outer, inner;
    bool matches(const SpMat& A) const;
    void take(const SpMat& A);
  };
  void solve_ldlt(const VecX& b, VecX& du, bool fallback, int newton_iteration);
  Kind kind_ = Kind::Cholmod;
  double cg_rtol_ = 1e-12;
  int last_iterations_ = 0;
  LinearSolveStats stats_;
  SpMat A_;
  Eigen::SimplicialLDLT<SpMat> ldlt_;
  Eigen::SparseLU<SpMat> lu_;
  std::unique_ptr<Cholmod> cholmod_;
  Pattern ldlt_pattern_, lu_pattern_;
};

/// Newton iteration from u (overwritten with the solution). `t` is the time at which the
/// constraints are evaluated. Throws tmlab::Error on a non-finite residual; returns
/// converged = false (with the history) when the iteration limit is reached.
NewtonResult newton_solve(NonlinearSystem& system, const DirichletSet& bc, double t, VecX& u,
                          const NewtonOptions& options, ConstrainedLinearSolver& linear);

}  // namespace tmlab::tm
