// Newton's method with backtracking line search for R(u) = 0 under Dirichlet constraints, shared
// by the static solver and the implicit time integrators.
//
// Constraints are imposed by elimination in place: the first iteration moves the constrained DOFs
// to their prescribed values (du_c = g(t) - u_c) and carries K_fc du_c to the right-hand side;
// rows and columns of constrained DOFs become identity rows, so the system stays symmetric and a
// sparse LDL^T factorisation applies (sparse LU for non-symmetric tangents, e.g. follower pressure).
#pragma once

#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/system/dirichlet.hpp"

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
};

struct NewtonOptions {
  int max_iterations = 25;
  double rtol = 1e-10;  ///< |R_free| <= rtol * max(|R_0|, force scale)
  double atol = 1e-14;  ///< absolute floor on |R_free|, newtons
  bool line_search = true;
  int max_backtracks = 12;
};

struct NewtonResult {
  bool converged = false;
  int iterations = 0;
  int backtracks = 0;
  double residual_initial = 0.0;
  double residual_final = 0.0;
  std::vector<double> history;  ///< |R_free| per iteration
};

/// Solves J du = rhs on the free DOFs with du prescribed on the constrained ones; reuses the
/// symbolic factorisation while the sparsity pattern is unchanged.
class ConstrainedLinearSolver {
 public:
  /// Throws tmlab::Error when the factorisation fails (singular: e.g. an unconstrained body).
  void solve(const SpMat& J, const VecX& rhs, const DirichletSet& bc, const VecX& du_c, bool symmetric,
             VecX& du);

 private:
  SpMat A_;
  Eigen::SimplicialLDLT<SpMat> ldlt_;
  Eigen::SparseLU<SpMat> lu_;
  Eigen::Index analysed_nnz_ = -1;
  bool analysed_symmetric_ = false;
};

/// Newton iteration from u (overwritten with the solution). `t` is the time at which the
/// constraints are evaluated. Throws tmlab::Error on a non-finite residual; returns
/// converged = false (with the history) when the iteration limit is reached.
NewtonResult newton_solve(NonlinearSystem& system, const DirichletSet& bc, double t, VecX& u,
                          const NewtonOptions& options, ConstrainedLinearSolver& linear);

}  // namespace tmlab::tm
