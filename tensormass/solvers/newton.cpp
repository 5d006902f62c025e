#include "tensormass/solvers/newton.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cmath>

namespace tmlab::tm {

void ConstrainedLinearSolver::solve(const SpMat& J, const VecX& rhs, const DirichletSet& bc, const VecX& du_c,
                                    bool symmetric, VecX& du) {
  const auto& mask = bc.mask();
  // Right-hand side of the free rows: rhs_f - J_fc du_c; constrained rows carry du_c itself.
  VecX b = rhs;
  A_ = J;
  for (Eigen::Index col = 0; col < A_.outerSize(); ++col) {
    for (SpMat::InnerIterator it(A_, col); it; ++it) {
      const Eigen::Index row = it.row();
      if (mask[col] && !mask[row]) b[row] -= it.value() * du_c[col];
      if (mask[col] || mask[row]) it.valueRef() = (row == col) ? 1.0 : 0.0;
    }
  }
  for (Index d : bc.dofs()) b[d] = du_c[d];

  const bool reanalyse = analysed_nnz_ != A_.nonZeros() || analysed_symmetric_ != symmetric;
  if (symmetric) {
    if (reanalyse) ldlt_.analyzePattern(A_);
    ldlt_.factorize(A_);
    if (ldlt_.info() != Eigen::Success)
      throw Error(
          "sparse LDL^T factorisation failed (singular tangent: is the body constrained against rigid "
          "motion?)");
    du = ldlt_.solve(b);
  } else {
    if (reanalyse) lu_.analyzePattern(A_);
    lu_.factorize(A_);
    if (lu_.info() != Eigen::Success)
      throw Error("sparse LU factorisation failed (singular tangent: " + lu_.lastErrorMessage() + ")");
    du = lu_.solve(b);
  }
  analysed_nnz_ = A_.nonZeros();
  analysed_symmetric_ = symmetric;
  if (!du.allFinite())
    throw Error("linear solve produced non-finite values (singular or ill-conditioned tangent)");
}

namespace {
double free_norm(const VecX& r, const DirichletSet& bc) {
  double s = 0.0;
  const auto& mask = bc.mask();
  for (Eigen::Index i = 0; i < r.size(); ++i)
    if (!mask[i]) s += r[i] * r[i];
  return std::sqrt(s);
}
}  // namespace

NewtonResult newton_solve(NonlinearSystem& system, const DirichletSet& bc, double t, VecX& u,
                          const NewtonOptions& options, ConstrainedLinearSolver& linear) {
  NewtonResult result;
  // Prescribed increments of the constrained DOFs, applied in the first iteration only.
  VecX target = u;
  bc.apply(t, target);
  VecX du_c = target - u;

  VecX r, du, u_trial, r_trial;
  SpMat J;
  system.residual(u, r);
  double rnorm = free_norm(r, bc);
  if (!std::isfinite(rnorm))
    throw Error("non-finite residual at the start of the Newton iteration (t = " + std::to_string(t) + ")");
  result.residual_initial = rnorm;
  result.history.push_back(rnorm);
  bool constraints_pending = du_c.lpNorm<Eigen::Infinity>() > 0.0;
  double scale = std::max(rnorm, system.force_scale());

  for (int k = 0; k < options.max_iterations; ++k) {
    if (!constraints_pending && rnorm <= options.rtol * scale + options.atol) {
      result.converged = true;
      break;
    }
    system.jacobian(u, J);
    VecX rhs = -r;
    linear.solve(J, rhs, bc, du_c, system.symmetric(), du);

    // Reference residual for the line search: with pending constraints, the residual after the
    // constrained DOFs have moved (the free part of the step is what the search scales).
    double rref = rnorm;
    if (constraints_pending) {
      u_trial = u + du_c;
      system.residual(u_trial, r_trial);
      rref = free_norm(r_trial, bc);
      scale = std::max(scale, rref);
    }
    double alpha = 1.0;
    int backtracks = 0;
    while (true) {
      u_trial = u + du_c + alpha * (du - du_c);
      system.residual(u_trial, r_trial);
      const double rt = free_norm(r_trial, bc);
      const bool ok = std::isfinite(rt) && rt <= (1.0 - 1e-4 * alpha) * rref;
      if (ok || !options.line_search || backtracks >= options.max_backtracks || !std::isfinite(rref)) {
        if (!std::isfinite(rt))
          throw Error("non-finite residual in Newton iteration " + std::to_string(k + 1) +
                      " at t = " + std::to_string(t) + " (step too large or element inversion)");
        break;
      }
      alpha *= 0.5;
      ++backtracks;
    }
    result.backtracks += backtracks;
    u.swap(u_trial);
    r.swap(r_trial);
    rnorm = free_norm(r, bc);
    du_c.setZero();
    constraints_pending = false;
    result.iterations = k + 1;
    result.history.push_back(rnorm);
  }
  if (!result.converged && rnorm <= options.rtol * scale + options.atol && !constraints_pending)
    result.converged = true;
  result.residual_final = rnorm;
  return result;
}

}  // namespace tmlab::tm
