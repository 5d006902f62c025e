#include "tensormass/solvers/explicit_dynamics.hpp"

#include "core/base/error.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>

namespace tmlab::tm {

StabilityEstimate estimate_critical_time_step(const MechanicalSystem& system, int max_iterations) {
  const SpMat& K = system.reference_tangent();
  const VecX& m = system.mass();
  const auto& mask = system.bc().mask();
  const Eigen::Index n = m.size();
  StabilityEstimate est;

  // Gershgorin: lambda_max(M^{-1}K) <= max_i sum_j |K_ij| / m_i over free rows.
  VecX rowsum = VecX::Zero(n);
  for (Eigen::Index c = 0; c < K.outerSize(); ++c)
    for (SpMat::InnerIterator it(K, c); it; ++it)
      if (!mask[it.row()] && !mask[c]) rowsum[it.row()] += std::abs(it.value());
  double gersh = 0.0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (!mask[i]) gersh = std::max(gersh, rowsum[i] / m[i]);

  // Power iteration on the symmetric form A = M^{-1/2} K M^{-1/2} restricted to free DOFs, from a
  // deterministic pseudo-random start (rich in the high-frequency modes that limit the step), until
  // the eigen-residual |A x - lambda x| <= 1e-4 lambda.
  const VecX minv_sqrt = m.cwiseSqrt().cwiseInverse();
  VecX x(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::uint64_t h = (static_cast<std::uint64_t>(i) + 1) * 0x9E3779B97F4A7C15ULL;
    x[i] = mask[i] ? 0.0 : static_cast<double>((h >> 11) % 1000003) / 1000003.0 - 0.5;
  }
  x.normalize();
  double lambda = 0.0;
  VecX y;
  for (int k = 0; k < max_iterations; ++k) {
    y = minv_sqrt.cwiseProduct(K * minv_sqrt.cwiseProduct(x));
    for (Eigen::Index i = 0; i < n; ++i)
      if (mask[i]) y[i] = 0.0;
    lambda = x.dot(y);
    const double ny = y.norm();
    est.iterations = k + 1;
    if (ny == 0.0) break;
    const double residual = (y - lambda * x).norm();
    x = y / ny;
    if (k >= 30 && residual <= 1e-4 * lambda) break;
  }
  est.omega_max = std::sqrt(std::max(lambda, 0.0));
  est.omega_bound = std::sqrt(std::max(gersh, 0.0));
  const double beta = system.damping().beta;
  auto limit = [beta](double omega) {
    if (omega <= 0.0) return std::numeric_limits<double>::infinity();
    const double xi = beta * omega / 2.0;
    return (2.0 / omega) * (std::sqrt(1.0 + xi * xi) - xi);
  };
  est.dt_critical = limit(est.omega_max);
  est.dt_guaranteed = limit(est.omega_bound);
  return est;
}

CentralDifference::CentralDifference(const MechanicalSystem& system, double dt, bool check_stability)
    : system_(system), dt_(dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw Error("explicit time step dt must be > 0");
  stability_ = estimate_critical_time_step(system_);
  if (check_stability && dt > stability_.dt_critical) {
    std::ostringstream msg;
    msg << "explicit time step dt = " << dt << " s exceeds the critical time step " << stability_.dt_critical
        << " s (omega_max = " << stability_.omega_max
        << " rad/s; guaranteed-stable dt = " << stability_.dt_guaranteed
        << " s): reduce solver.dt, or use the implicit solver";
    throw Error(msg.str());
  }
}

void CentralDifference::initialize(double t0, const VecX& u0, const VecX& v0) {
  const Index n = system_.num_dofs();
  if (u0.size() != n || v0.size() != n) throw Error("initial state has the wrong size");
  t_ = t0;
  n_ = 0;
  u_ = u0;
  system_.bc().apply(t0, u_);
  v_ = v0;
  system_.model().begin_step(0.0);
  system_.model().commit_step(u_);
  // v^{-1/2} = v^0 - dt/2 a^0 so that the first leapfrog update gives v^{1/2} = v^0 + dt/2 a^0.
  system_.model().internal_force(u_, fint_);
  system_.loads().assemble(u_, t_, fext_);
  system_.damping_force(v_, fdamp_);
  const VecX a0 = (fext_ - fint_ - fdamp_).cwiseQuotient(system_.mass());
  v_half_ = v_ - 0.5 * dt_ * a0;
}

void CentralDifference::step(double t, double dt) {
  if (std::abs(t - t_) > 1e-9 * std::max(1.0, std::abs(t_)) || std::abs(dt - dt_) > 1e-12 * dt_)
    throw Error("CentralDifference::step called with (t, dt) inconsistent with its state");
  const double a = system_.damping().alpha;
  // History models: the force at u^n uses the history advanced over the step that reached t_n,
  // which is then committed (explicit stepping accepts every step).
  if (n_ > 0 && system_.model().has_history()) {
    system_.model().begin_step(dt_);
    system_.model().force_and_commit(u_, fint_);  // one pass: trial force and history update
  } else {
    system_.model().internal_force(u_, fint_);
  }
  system_.loads().assemble(u_, t_, fext_);
  // The update into buffers kept across steps (no allocation per step). Without stiffness damping
  // f_damp = 0 is left out: x - 0 is x, so the result is the same to the bit.
  if (system_.damping().beta != 0.0) {
    fdamp_ = system_.damping().beta * (system_.reference_tangent() * v_half_);
    v_new_ =
        ((1.0 - 0.5 * a * dt_) * v_half_ + dt_ * (fext_ - fint_ - fdamp_).cwiseQuotient(system_.mass())) /
        (1.0 + 0.5 * a * dt_);
  } else {
    v_new_ = ((1.0 - 0.5 * a * dt_) * v_half_ + dt_ * (fext_ - fint_).cwiseQuotient(system_.mass())) /
             (1.0 + 0.5 * a * dt_);
  }
  // Prescribed DOFs follow g(t): their half-step velocity is the finite difference of g (apply
  // writes only the prescribed entries of g_, which are the only ones read).
  g_.resize(u_.size());
  system_.bc().apply(t_ + dt_, g_);
  for (Index d : system_.bc().dofs()) v_new_[d] = (g_[d] - u_[d]) / dt_;
  u_ += dt_ * v_new_;
  v_ = 0.5 * (v_half_ + v_new_);
  v_half_.swap(v_new_);
  t_ += dt_;
  ++n_;
  // x - x is 0 for every finite x and NaN otherwise: one vectorised sum finds a non-finite entry
  // (allFinite() tests entry by entry, measured at a third of this function outside the force).
  const double non_finite = (u_ - u_).sum() + (v_half_ - v_half_).sum();
  if (non_finite != 0.0 || u_.lpNorm<Eigen::Infinity>() > displacement_limit_) {
    std::ostringstream msg;
    msg << "explicit dynamics became unstable at step " << n_ << " (t = " << t_
        << " s): displacement non-finite or beyond " << displacement_limit_
        << " m; reduce solver.dt (critical estimate " << stability_.dt_critical
        << " s) — the material stiffens under large strain";
    throw Error(msg.str());
  }
}

void CentralDifference::correct(const VecX& du) {
  if (du.size() != u_.size()) throw Error("CentralDifference::correct: correction has the wrong size");
  u_ += du;
  v_half_ += du / dt_;
  v_ += 0.5 * du / dt_;  // v^{n+1} = (v^{n-1/2} + v^{n+1/2}) / 2
}

void CentralDifference::restore(double t, long steps, const VecX& u, const VecX& v_half, const VecX& v) {
  const Index n = system_.num_dofs();
  if (u.size() != n || v_half.size() != n || v.size() != n)
    throw Error("checkpoint: explicit state of the wrong size (a checkpoint of another mesh?)");
  t_ = t;
  n_ = steps;
  u_ = u;
  v_half_ = v_half;
  v_ = v;
}

double CentralDifference::kinetic_energy() const { return 0.5 * v_.dot(system_.mass().cwiseProduct(v_)); }

}  // namespace tmlab::tm
