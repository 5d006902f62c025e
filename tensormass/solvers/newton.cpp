#include "tensormass/solvers/newton.hpp"

#include "core/base/error.hpp"

#include <Eigen/CholmodSupport>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tmlab::tm {

struct ConstrainedLinearSolver::Cholmod {
  Cholmod() {
    // Failures are reported through info() and handled here (LDL^T fallback); CHOLMOD's own
    // warning on stderr ("not positive definite") would only confuse a run's log.
    llt.cholmod().print = 0;
  }
  Eigen::CholmodSupernodalLLT<SpMat, Eigen::Lower> llt;
  Pattern pattern;  ///< the pattern last analysed
};

bool ConstrainedLinearSolver::Pattern::matches(const SpMat& A) const {
  const auto n_outer = static_cast<std::size_t>(A.outerSize()) + 1;
  const auto nnz = static_cast<std::size_t>(A.nonZeros());
  return outer.size() == n_outer && inner.size() == nnz &&
         std::equal(outer.begin(), outer.end(), A.outerIndexPtr()) &&
         std::equal(inner.begin(), inner.end(), A.innerIndexPtr());
}

void ConstrainedLinearSolver::Pattern::take(const SpMat& A) {
  outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
  inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
}

ConstrainedLinearSolver::ConstrainedLinearSolver() = default;
ConstrainedLinearSolver::ConstrainedLinearSolver(Kind kind, double cg_rtol)
    : kind_(kind), cg_rtol_(cg_rtol) {}
ConstrainedLinearSolver::~ConstrainedLinearSolver() = default;

void ConstrainedLinearSolver::solve(const SpMat& J, const VecX& rhs, const DirichletSet& bc, const VecX& du_c,
                                    bool symmetric, VecX& du, int newton_iteration) {
  const auto& mask = bc.mask();
  // Right-hand side of the free rows: rhs_f - J_fc du_c; constrained rows carry du_c itself.
  VecX b = rhs;
  A_ = J;
  A_.makeCompressed();  // the pattern comparisons read the compressed index arrays
  for (Eigen::Index col = 0; col < A_.outerSize(); ++col) {
    for (SpMat::InnerIterator it(A_, col); it; ++it) {
      const Eigen::Index row = it.row();
      if (mask[col] && !mask[row]) b[row] -= it.value() * du_c[col];
      if (mask[col] || mask[row]) it.valueRef() = (row == col) ? 1.0 : 0.0;
    }
  }
  for (Index d : bc.dofs()) b[d] = du_c[d];

  ++stats_.solves;
  last_iterations_ = 0;
  if (kind_ == Kind::ConjugateGradient) {
    if (!symmetric)
      throw Error(
          "the conjugate-gradient linear solver needs a symmetric tangent (follower pressure is not): "
          "use the direct solver");
    // The constrained rows and columns are identity rows: A stays symmetric positive definite.
    Eigen::ConjugateGradient<SpMat, Eigen::Lower | Eigen::Upper, Eigen::IncompleteCholesky<double>> cg;
    cg.setTolerance(cg_rtol_);
    cg.setMaxIterations(static_cast<Eigen::Index>(std::max<Eigen::Index>(1000, 4 * A_.rows())));
    cg.compute(A_);
    if (cg.info() != Eigen::Success)
      throw Error("incomplete Cholesky preconditioner failed (tangent not positive definite?)");
    du = cg.solve(b);
    last_iterations_ = static_cast<int>(cg.iterations());
    ++stats_.cg_solves;
    if (cg.info() != Eigen::Success)
      throw Error("conjugate gradients did not reach |r| <= " + std::to_string(cg_rtol_) + " |b| in " +
                  std::to_string(cg.iterations()) + " iterations (error " + std::to_string(cg.error()) + ")");
    if (!du.allFinite()) throw Error("conjugate gradients produced non-finite values");
    return;
  }
  if (symmetric && kind_ == Kind::Cholmod) {
    if (!cholmod_) cholmod_ = std::make_unique<Cholmod>();
    Cholmod& c = *cholmod_;
    if (!c.pattern.matches(A_)) {
      c.llt.analyzePattern(A_);
      c.pattern.take(A_);
      ++stats_.cholmod_analyses;
    }
    c.llt.factorize(A_);
    if (c.llt.info() == Eigen::Success) {
      du = c.llt.solve(b);
      if (c.llt.info() != Eigen::Success) throw Error("CHOLMOD solve failed");
      ++stats_.cholmod_solves;
      if (!du.allFinite())
        throw Error("linear solve produced non-finite values (singular or ill-conditioned tangent)");
      return;
    }
    // Not positive definite: the LDL^T below handles indefinite tangents and tells why.
    solve_ldlt(b, du, true, newton_iteration);
    return;
  }
  if (symmetric) {
    solve_ldlt(b, du, false, newton_iteration);
    return;
  }
  if (!lu_pattern_.matches(A_)) {
    lu_.analyzePattern(A_);
    lu_pattern_.take(A_);
    ++stats_.lu_analyses;
  }
  lu_.factorize(A_);
  if (lu_.info() != Eigen::Success)
    throw Error("sparse LU factorisation failed (singular tangent: " + lu_.lastErrorMessage() + ")");
  du = lu_.solve(b);
  ++stats_.lu_solves;
  if (!du.allFinite())
    throw Error("linear solve produced non-finite values (singular or ill-conditioned tangent)");
}

void ConstrainedLinearSolver::solve_ldlt(const VecX& b, VecX& du, bool fallback, int newton_iteration) {
  if (!ldlt_pattern_.matches(A_)) {
    ldlt_.analyzePattern(A_);
    ldlt_pattern_.take(A_);
    ++stats_.ldlt_analyses;
  }
  ldlt_.factorize(A_);
  if (ldlt_.info() != Eigen::Success)
    throw Error(
        "sparse LDL^T factorisation failed (singular tangent: is the body constrained against rigid "
        "motion?)");
  du = ldlt_.solve(b);
  ++stats_.ldlt_solves;
  if (fallback) {
    // Without pivoting A = P^T L D L^T P is a congruence: D has as many negative entries as A has
    // negative eigenvalues (Sylvester). None: CHOLMOD failed on round-off of a positive definite A.
    const Eigen::Index negative = (ldlt_.vectorD().array() < 0.0).count();
    if (negative > 0)
      ++stats_.fallbacks_indefinite;
    else
      ++stats_.fallbacks_round_off;
    stats_.max_negative_pivots = std::max(stats_.max_negative_pivots, negative);
    auto& by = stats_.fallbacks_by_iteration;
    if (newton_iteration >= 0) ++by[std::min(static_cast<std::size_t>(newton_iteration), by.size() - 1)];
  }
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

namespace {
std::string where(int k, double t) {
  return "Newton iteration " + std::to_string(k + 1) + " at t = " + std::to_string(t);
}

/// One trial point of the line search: u + du_c + alpha (du - du_c), its residual and norm.
struct Trial {
  VecX u, r;
  double rnorm = 0.0;
  double pi = 0.0;  ///< potential, when used
};
}  // namespace

NewtonResult newton_solve(NonlinearSystem& system, const DirichletSet& bc, double t, VecX& u,
                          const NewtonOptions& options, ConstrainedLinearSolver& linear) {
  NewtonResult result;
  // Prescribed increments of the constrained DOFs, applied in the first iteration only.
  VecX target = u;
  bc.apply(t, target);
  VecX du_c = target - u;

  VecX r, du, u_ref, r_ref;
  SpMat J;
  Trial trial;
  system.residual(u, r);
  double rnorm = free_norm(r, bc);
  if (!std::isfinite(rnorm))
    throw Error("non-finite residual at the start of the Newton iteration (t = " + std::to_string(t) + ")");
  result.residual_initial = rnorm;
  result.history.push_back(rnorm);
  bool constraints_pending = du_c.lpNorm<Eigen::Infinity>() > 0.0;
  double scale = std::max(rnorm, system.force_scale());
  const double eps = std::numeric_limits<double>::epsilon();
  const double c1 = 1e-4;

  auto evaluate = [&](double alpha, Trial& tr, bool with_potential) {
    tr.u = u_ref + alpha * (du - du_c);
    system.residual(tr.u, tr.r);
    tr.rnorm = free_norm(tr.r, bc);
    if (with_potential && std::isfinite(tr.rnorm) && !system.potential(tr.u, tr.pi))
      tr.pi = std::numeric_limits<double>::quiet_NaN();
  };

  for (int k = 0; k < options.max_iterations; ++k) {
    result.target = options.rtol * scale + options.atol;
    if (!constraints_pending && rnorm <= result.target) {
      result.converged = true;
      break;
    }
    system.jacobian(u, J);
    VecX rhs = -r;
    linear.solve(J, rhs, bc, du_c, system.symmetric(), du, k);

    // The line search scales the free part of the step from u_ref = u + du_c (the constrained DOFs
    // move to their prescribed values in full). Reference residual and potential at u_ref.
    u_ref = u + du_c;
    double rref = rnorm;
    if (constraints_pending) {
      system.residual(u_ref, r_ref);
      rref = free_norm(r_ref, bc);
      scale = std::max(scale, rref);
    } else {
      r_ref = r;
    }
    double pi_ref = 0.0, slope = 0.0;
    bool energy = options.line_search == LineSearch::Energy && std::isfinite(rref) &&
                  system.potential(u_ref, pi_ref) && std::isfinite(pi_ref);
    if (energy) {
      // Directional derivative of Pi along the free step: R(u_ref) . (du - du_c) over the free DOFs.
      const auto& mask = bc.mask();
      for (Eigen::Index i = 0; i < du.size(); ++i)
        if (!mask[i]) slope += r_ref[i] * (du[i] - du_c[i]);
      energy = slope < 0.0;  // not a descent direction (indefinite tangent): full step
    }

    double alpha = 1.0;
    int backtracks = 0;
    while (true) {
      evaluate(alpha, trial, energy);
      bool ok;
      if (!std::isfinite(trial.rnorm)) {
        ok = false;  // an element inverted or the model broke down: always shorten the step
      } else if (options.line_search == LineSearch::None) {
        ok = true;
      } else if (energy) {
        // Armijo on Pi; near the solution the decrease of Pi drowns in its round-off (Pi is a
        // difference of large sums), where a decreasing residual norm is accepted instead.
        ok = (std::isfinite(trial.pi) &&
              trial.pi <=
                  pi_ref + c1 * alpha * slope + 16.0 * eps * (std::abs(pi_ref) + std::abs(trial.pi))) ||
             trial.rnorm <= (1.0 - c1 * alpha) * rref;
      } else if (options.line_search == LineSearch::Residual) {
        ok = trial.rnorm <= (1.0 - c1 * alpha) * rref || !std::isfinite(rref);
      } else {
        ok = true;  // energy merit requested but no potential: full step
      }
      if (ok) break;
      if (backtracks >= options.max_backtracks) {
        if (!std::isfinite(trial.rnorm))
          throw Error("non-finite residual in " + where(k, t) + " after " + std::to_string(backtracks) +
                      " step halvings (step too large or element inversion)");
        break;  // take the shortest step tried; the iteration limit or the cut-backs decide
      }
      double next = 0.5 * alpha;
      if (energy && std::isfinite(trial.pi)) {
        // Minimiser of the quadratic through Pi(0), Pi'(0) = slope and Pi(alpha).
        const double curvature = trial.pi - pi_ref - slope * alpha;
        if (curvature > 0.0)
          next = std::clamp(-slope * alpha * alpha / (2.0 * curvature), 0.1 * alpha, 0.5 * alpha);
      }
      alpha = next;
      ++backtracks;
    }
    result.backtracks += backtracks;
    result.alphas.push_back(alpha);
    const double step_inf = (trial.u - u).lpNorm<Eigen::Infinity>();
    const double rprev = rnorm;
    u.swap(trial.u);
    r.swap(trial.r);
    rnorm = trial.rnorm;
    const bool was_pending = constraints_pending;
    du_c.setZero();
    constraints_pending = false;
    result.iterations = k + 1;
    result.history.push_back(rnorm);
    // Round-off stagnation: the residual stalled while the step is at the round-off of u.
    if (!was_pending && k >= 1 && rnorm > 0.5 * rprev &&
        step_inf <= options.stagnation_tol * std::max(u.lpNorm<Eigen::Infinity>(), 1e-300)) {
      // Within three orders of the target: the round-off floor of this residual, converged. Far
      // above it: stalled, and further iterations cannot help (the caller cuts back or fails).
      result.stalled = true;
      result.converged = rnorm <= 1e3 * result.target;
      result.at_roundoff = result.converged && rnorm > result.target;
      break;
    }
  }
  result.target = options.rtol * scale + options.atol;
  if (!result.converged && rnorm <= result.target && !constraints_pending) result.converged = true;
  result.residual_final = rnorm;
  return result;
}

}  // namespace tmlab::tm
