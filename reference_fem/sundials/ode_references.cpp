// Reference problems for the SUNDIALS integrators: SDOF closed forms and the semi-discrete
// viscoelastic tensor-mass ODE (internal-variable form). See ode_references.hpp.
#include "reference_fem/sundials/ode_references.hpp"

#include "core/base/error.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <complex>

namespace tmlab::tm {
namespace {

/// 2 mu (E - tr(E)/3 I)
Mat3 deviator_stress(double mu, const Mat3& E) {
  return 2.0 * mu * (E - (E.trace() / 3.0) * Mat3::Identity());
}

// A (3x3) y, element by element: the Eigen expression A * y with a dynamic y makes GCC 12 at -O3 with
// AVX-512 warn about an 8-double packet load from a 3-double temporary (-Warray-bounds; the packet
// path is never taken at size 3, but the warning would hide real ones).
VecX times_A(const Eigen::Matrix3d& A, const VecX& y) {
  VecX r(3);
  for (int i = 0; i < 3; ++i) r[i] = A(i, 0) * y[0] + A(i, 1) * y[1] + A(i, 2) * y[2];
  return r;
}

}  // namespace

// ================================================================== SlsOscillator

SlsOscillator::SlsOscillator(double mass, double stiffness, double alpha, double tau, double x0, double v0) {
  if (!(mass > 0) || !(stiffness > 0) || !(alpha >= 0) || !(tau > 0))
    throw Error("SlsOscillator: need mass > 0, stiffness > 0, alpha >= 0, tau > 0");
  // y' = A y:  x' = v,  v' = -(k x + alpha h)/m,  h' = k v - h/tau
  A_ << 0.0, 1.0, 0.0, -stiffness / mass, 0.0, -alpha / mass, 0.0, stiffness, -1.0 / tau;
  y0_ << x0, v0, 0.0;
  Eigen::EigenSolver<Eigen::Matrix3d> es(A_);
  V_ = es.eigenvectors();
  lambda_ = es.eigenvalues();
  Vinv_ = V_.inverse();
}

void SlsOscillator::rhs(double /*t*/, const VecX& y, VecX& ydot) { ydot = times_A(A_, y); }
void SlsOscillator::jacobian_times(double /*t*/, const VecX& /*y*/, const VecX& v, VecX& Jv) {
  Jv = times_A(A_, v);
}
VecX SlsOscillator::initial_state() const { return y0_; }

void SlsOscillator::rhs_explicit(double /*t*/, const VecX& y, VecX& ydot) {
  ydot = times_A(A_, y);
  ydot[2] -= A_(2, 2) * y[2];  // everything but -h/tau
}
void SlsOscillator::rhs_implicit(double /*t*/, const VecX& y, VecX& ydot) {
  ydot = VecX::Zero(3);
  ydot[2] = A_(2, 2) * y[2];  // -h/tau
}
void SlsOscillator::rhs_slow(double /*t*/, const VecX& y, VecX& ydot) {
  ydot = VecX::Zero(3);
  ydot[2] = A_(2, 1) * y[1] + A_(2, 2) * y[2];  // h' = k v - h/tau
}
void SlsOscillator::rhs_fast(double /*t*/, const VecX& y, VecX& ydot) {
  ydot = times_A(A_, y);
  ydot[2] = 0.0;  // x' = v, v' = -(k x + alpha h)/m
}
void SlsOscillator::jacobian_times_implicit(double /*t*/, const VecX& /*y*/, const VecX& v, VecX& Jv) {
  Jv = VecX::Zero(3);
  Jv[2] = A_(2, 2) * v[2];
}

Eigen::Vector3d SlsOscillator::exact(double t) const {
  // y(t) = V diag(exp(lambda_i t)) V^{-1} y0
  Eigen::Vector3cd e;
  for (int i = 0; i < 3; ++i) e[i] = std::exp(lambda_[i] * t);
  const Eigen::Vector3cd y = V_ * e.asDiagonal() * (Vinv_ * y0_.cast<std::complex<double>>());
  return y.real();
}

// ================================================================== SlsCreep

SlsCreep::SlsCreep(double stiffness, double alpha, double tau, double force_amplitude, double omega)
    : k_(stiffness), alpha_(alpha), tau_(tau), f0_(force_amplitude), omega_(omega) {
  if (!(stiffness > 0) || !(alpha >= 0) || !(tau > 0))
    throw Error("SlsCreep: need stiffness > 0, alpha >= 0, tau > 0");
}

double SlsCreep::phi(double t) const { return f0_ / k_ * std::sin(omega_ * t); }

double SlsCreep::exact_H(double t) const {
  // H = phi0 omega / (1+alpha) [cos(w t)/tc + w sin(w t) - exp(-t/tc)/tc] / (1/tc^2 + w^2),  tc = tau
  // (1+alpha)
  const double tc = tau_ * (1.0 + alpha_), w = omega_, phi0 = f0_ / k_;
  const double conv =
      (std::cos(w * t) / tc + w * std::sin(w * t) - std::exp(-t / tc) / tc) / (1.0 / (tc * tc) + w * w);
  return phi0 * w / (1.0 + alpha_) * conv;
}

double SlsCreep::exact_x(double t) const { return phi(t) - alpha_ * exact_H(t); }

void SlsCreep::residual(double t, const VecX& y, const VecX& yp, VecX& r) {
  r.resize(2);
  r[0] = (1.0 + alpha_) * y[0] - alpha_ * y[1] - phi(t);  // equilibrium: x + alpha (x - z) = phi
  r[1] = yp[1] - (y[0] - y[1]) / tau_;                    // z' = (x - z)/tau
}

VecX SlsCreep::differential() const {
  VecX id(2);
  id << 0.0, 1.0;
  return id;
}

std::vector<double> SlsCreep::recursion(ViscoelasticOptions::Integration scheme, double dt, int steps) const {
  const RecursionFactors f = recursion_factors(scheme, dt, tau_);
  std::vector<double> xs;
  xs.reserve(static_cast<std::size_t>(steps));
  double x = 0.0, H = 0.0;
  for (int n = 1; n <= steps; ++n) {
    // x' + alpha (a H + c (x' - x)) = phi(t_{n+1})  =>  x' (1 + alpha c) = phi - alpha (a H - c x)
    const double xn = (phi(n * dt) - alpha_ * (f.a * H - f.c * x)) / (1.0 + alpha_ * f.c);
    H = f.a * H + f.c * (xn - x);
    x = xn;
    xs.push_back(x);
  }
  return xs;
}

// ================================================================== TensorMassViscoelasticOde

TensorMassViscoelasticOde::TensorMassViscoelasticOde(const Mesh& mesh, const StVenantKirchhoff& long_term,
                                                     PronySeries prony, ViscoelasticOptions options,
                                                     const MechanicalSystem& system)
    : tl_(mesh, long_term),
      tm_(mesh, long_term),
      mat_(long_term),
      prony_(std::move(prony)),
      options_(options),
      system_(system) {
  if (!pk2() && deviatoric())
    throw Error(
        "TensorMassViscoelasticOde: deviatoric relaxation needs the pk2 history (a nodal force has no "
        "deviator)");
  ndof_ = 3 * tl_.num_nodes();
  if (system.num_dofs() != ndof_)
    throw Error("TensorMassViscoelasticOde: the mechanical system has a different DOF count");
  ntets_ = tl_.num_tets();
  width_ = pk2() ? 6 : 12;
  nz_ = ntets_ * static_cast<Index>(prony_.size()) * width_;
  alpha_sum_ = prony_.alpha_sum();
  u_.resize(ndof_);
}

void TensorMassViscoelasticOde::tet_driver(Index t, const VecX& u, double* x) const {
  if (!pk2()) {  // X_e = the 12 nodal elastic forces of the tet (global axes)
    const TensorMassStVK::Mat34 f = tm_.tet_force(t, u);
    for (int p = 0; p < 4; ++p)
      for (int c = 0; c < 3; ++c) x[3 * p + c] = f(c, p);
    return;
  }
  const Mat3 E = tl_.green_strain(t, u);
  to_voigt(deviatoric() ? deviator_stress(mat_.mu, E) : mat_.pk2_stress(E), x);
}

void TensorMassViscoelasticOde::force(const VecX& u, const double* z, VecX& f) const {
  f.setZero(ndof_);
  const std::size_t J = prony_.size();
  const int w = width_;
  for (Index t = 0; t < ntets_; ++t) {
    const double* zt = z + static_cast<std::size_t>(t) * J * w;
    const Tet& tet = tl_.tets()[static_cast<std::size_t>(t)];
    if (pk2()) {
      // S_tot = (1 + A) S_e - sum alpha_j z_j   (deviatoric: S_e + A S_dev - sum alpha_j z_j);  f_p = V F
      // S_tot a_p
      const Mat3 F = tl_.deformation_gradient(t, u);
      const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
      const Mat3 Se = mat_.pk2_stress(E);
      Mat3 S =
          deviatoric() ? Mat3(Se + alpha_sum_ * deviator_stress(mat_.mu, E)) : Mat3((1.0 + alpha_sum_) * Se);
      for (std::size_t j = 0; j < J; ++j) S -= prony_.alpha(j) * from_voigt(zt + j * w);
      const Mat34 fp = tl_.tet_force_from_stress(t, F, S);
      for (int p = 0; p < 4; ++p) f.segment<3>(3 * tet[p]) += fp.col(p);
    } else {
      // f = (1 + A) f_e - sum alpha_j z_j
      const TensorMassStVK::Mat34 fe = tm_.tet_force(t, u);
      for (int p = 0; p < 4; ++p)
        for (int c = 0; c < 3; ++c) {
          double v = (1.0 + alpha_sum_) * fe(c, p);
          for (std::size_t j = 0; j < J; ++j) v -= prony_.alpha(j) * zt[j * w + 3 * p + c];
          f[3 * tet[p] + c] += v;
        }
    }
  }
}

void TensorMassViscoelasticOde::rhs(double t, const VecX& y, VecX& ydot) {
  ydot.resize(size());
  u_ = y.head(ndof_);
  system_.bc().apply(t, u_);  // u = g(t) on the constrained DOFs
  const double* z = y.data() + 2 * ndof_;
  force(u_, z, f_);
  system_.loads().assemble(u_, t, fext_);
  const VecX v = y.segment(ndof_, ndof_);
  const RayleighDamping& d = system_.damping();
  if (d.alpha != 0.0 || d.beta != 0.0)
    system_.damping_force(v, cv_);
  else
    cv_.setZero(ndof_);
  // u' = v,  v' = M^{-1} (f_ext - f_int - C v)
  ydot.head(ndof_) = v;
  ydot.segment(ndof_, ndof_) = (fext_ - f_ - cv_).cwiseQuotient(system_.mass());
  for (Index k : system_.bc().dofs()) {
    ydot[k] = 0.0;
    ydot[ndof_ + k] = 0.0;
  }
  // z_j' = (X_e(u) - z_j) / tau_j
  const std::size_t J = prony_.size();
  const int w = width_;
  double x[12];
  for (Index e = 0; e < ntets_; ++e) {
    tet_driver(e, u_, x);
    const std::size_t base = static_cast<std::size_t>(2 * ndof_) + static_cast<std::size_t>(e) * J * w;
    for (std::size_t j = 0; j < J; ++j) {
      const double inv_tau = 1.0 / prony_.tau(j);
      for (int k = 0; k < w; ++k) {
        const std::size_t i = base + j * w + k;
        ydot[static_cast<Index>(i)] = (x[k] - y[static_cast<Index>(i)]) * inv_tau;
      }
    }
  }
}

void TensorMassViscoelasticOde::linearise(const VecX& u, const double* z, const VecX& du, const double* dz,
                                          VecX& df, VecX& dxv) const {
  const std::size_t J = prony_.size();
  const int w = width_;
  df.setZero(ndof_);
  dxv.resize(ntets_ * w);
  for (Index e = 0; e < ntets_; ++e) {
    const std::size_t base = static_cast<std::size_t>(e) * J * w;
    const Tet& tet = tl_.tets()[static_cast<std::size_t>(e)];
    double* dx = dxv.data() + e * w;
    if (pk2()) {
      // dF = sum_p du_p a_p^T, dE = sym(F^T dF), dS_e = C : dE,
      // dS_tot = (1 + A) dS_e - sum alpha dz_j (dev: dS_e + A dS_dev - ...), df_p = V (dF S_tot + F dS_tot)
      // a_p
      const TetRest& r = tl_.rest(e);
      const Mat3 F = tl_.deformation_gradient(e, u);
      Mat3 dF = Mat3::Zero();
      for (int p = 0; p < 4; ++p) dF += du.segment<3>(3 * tet[p]) * r.grad[p].transpose();
      const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
      const Mat3 FtdF = F.transpose() * dF;
      const Mat3 dE = 0.5 * (FtdF + FtdF.transpose());
      const Mat3 Se = mat_.pk2_stress(E), dSe = mat_.pk2_stress(dE);
      Mat3 S, dS;
      if (deviatoric()) {
        S = Se + alpha_sum_ * deviator_stress(mat_.mu, E);
        const Mat3 dSd = deviator_stress(mat_.mu, dE);
        dS = dSe + alpha_sum_ * dSd;
        to_voigt(dSd, dx);
      } else {
        S = (1.0 + alpha_sum_) * Se;
        dS = (1.0 + alpha_sum_) * dSe;
        to_voigt(dSe, dx);
      }
      for (std::size_t j = 0; j < J; ++j) {
        S -= prony_.alpha(j) * from_voigt(z + base + j * w);
        dS -= prony_.alpha(j) * from_voigt(dz + base + j * w);
      }
      const Mat34 dfe = tl_.tet_force_from_stress(e, dF, S) + tl_.tet_force_from_stress(e, F, dS);
      for (int p = 0; p < 4; ++p) df.segment<3>(3 * tet[p]) += dfe.col(p);
    } else {
      // dX_e = K_e(u) du (12x12 tet stiffness), df = (1 + A) dX_e - sum alpha dz_j
      const TensorMassStVK::Mat12 K = tm_.tet_stiffness(e, u);
      Eigen::Matrix<double, 12, 1> dul;
      for (int p = 0; p < 4; ++p) dul.segment<3>(3 * p) = du.segment<3>(3 * tet[p]);
      const Eigen::Matrix<double, 12, 1> dfe = K * dul;
      for (int k = 0; k < 12; ++k) dx[k] = dfe[k];
      for (int p = 0; p < 4; ++p)
        for (int c = 0; c < 3; ++c) {
          double v = (1.0 + alpha_sum_) * dfe[3 * p + c];
          for (std::size_t j = 0; j < J; ++j) v -= prony_.alpha(j) * dz[base + j * w + 3 * p + c];
          df[3 * tet[p] + c] += v;
        }
    }
  }
}

void TensorMassViscoelasticOde::jacobian_times(double t, const VecX& y, const VecX& w_in, VecX& Jw) {
  Jw.resize(size());
  u_ = y.head(ndof_);
  system_.bc().apply(t, u_);
  du_ = w_in.head(ndof_);
  system_.bc().zero_constrained(du_);  // the prescribed u does not depend on the state
  const VecX dv = w_in.segment(ndof_, ndof_);
  const double* dz = w_in.data() + 2 * ndof_;
  VecX dx;
  linearise(u_, y.data() + 2 * ndof_, du_, dz, f_, dx);  // f_ = df_int
  // d z_j' = (dX_e - dz_j) / tau_j
  const std::size_t J = prony_.size();
  const int w = width_;
  for (Index e = 0; e < ntets_; ++e)
    for (std::size_t j = 0; j < J; ++j)
      for (int k = 0; k < w; ++k) {
        const Index i = static_cast<Index>((static_cast<std::size_t>(e) * J + j) * w) + k;
        Jw[2 * ndof_ + i] = (dx[e * w + k] - dz[i]) / prony_.tau(j);
      }
  const RayleighDamping& d = system_.damping();
  if (d.alpha != 0.0 || d.beta != 0.0)
    system_.damping_force(dv, cv_);
  else
    cv_.setZero(ndof_);
  Jw.head(ndof_) = dv;
  Jw.segment(ndof_, ndof_) = -(f_ + cv_).cwiseQuotient(system_.mass());
  for (Index k : system_.bc().dofs()) {
    Jw[k] = 0.0;
    Jw[ndof_ + k] = 0.0;
  }
}

void TensorMassViscoelasticOde::rhs_explicit(double t, const VecX& y, VecX& ydot) {
  rhs(t, y, ydot);
  ydot.tail(nz_).setZero();  // f_E: the mechanics only
}

void TensorMassViscoelasticOde::rhs_implicit(double t, const VecX& y, VecX& ydot) {
  // f_I: z_j' = (X_e(u) - z_j)/tau_j, zero on u and v
  ydot = VecX::Zero(size());
  u_ = y.head(ndof_);
  system_.bc().apply(t, u_);
  const std::size_t J = prony_.size();
  const int w = width_;
  double x[12];
  for (Index e = 0; e < ntets_; ++e) {
    tet_driver(e, u_, x);
    const Index base = 2 * ndof_ + static_cast<Index>(static_cast<std::size_t>(e) * J * w);
    for (std::size_t j = 0; j < J; ++j)
      for (int k = 0; k < w; ++k) {
        const Index i = base + static_cast<Index>(j * w) + k;
        ydot[i] = (x[k] - y[i]) / prony_.tau(j);
      }
  }
}

void TensorMassViscoelasticOde::jacobian_times_implicit(double t, const VecX& y, const VecX& v, VecX& Jv) {
  jacobian_times(t, y, v, Jv);  // rows of z are those of df_I/dy; the u, v rows of f_I are zero
  Jv.head(2 * ndof_).setZero();
}

VecX TensorMassViscoelasticOde::initial_state(double t0, const VecX& u0, const VecX& v0) const {
  VecX y = VecX::Zero(size());
  VecX u = u0;
  system_.bc().apply(t0, u);
  y.head(ndof_) = u;
  y.segment(ndof_, ndof_) = v0;
  const std::size_t J = prony_.size();
  double x[12];
  for (Index e = 0; e < ntets_; ++e) {
    tet_driver(e, u, x);
    for (std::size_t j = 0; j < J; ++j)
      for (int k = 0; k < width_; ++k)
        y[2 * ndof_ + static_cast<Index>((static_cast<std::size_t>(e) * J + j) * width_ + k)] = x[k];
  }
  return y;
}

VecX TensorMassViscoelasticOde::absolute_tolerances(double u_scale, double v_scale, double x_scale) const {
  VecX a(size());
  a.head(ndof_).setConstant(u_scale);
  a.segment(ndof_, ndof_).setConstant(v_scale);
  a.tail(nz_).setConstant(x_scale);
  return a;
}

VecX TensorMassViscoelasticOde::displacement(double t, const VecX& y) const {
  VecX u = y.head(ndof_);
  system_.bc().apply(t, u);
  return u;
}

VecX TensorMassViscoelasticOde::elastic_driver(const VecX& u) const {
  VecX x(ntets_ * width_);
  for (Index e = 0; e < ntets_; ++e) tet_driver(e, u, x.data() + e * width_);
  return x;
}

VecX TensorMassViscoelasticOde::total_driver(double t, const VecX& y) const {
  const VecX u = displacement(t, y);
  const std::size_t J = prony_.size();
  const int w = width_;
  VecX out(ntets_ * w);
  double x[12];
  for (Index e = 0; e < ntets_; ++e) {
    double* o = out.data() + e * w;
    tet_driver(e, u, x);
    if (deviatoric()) {
      // S_e + A S_dev - sum alpha_j z_j
      to_voigt(mat_.pk2_stress(tl_.green_strain(e, u)), o);
      for (int k = 0; k < w; ++k) o[k] += alpha_sum_ * x[k];
    } else {
      for (int k = 0; k < w; ++k) o[k] = (1.0 + alpha_sum_) * x[k];
    }
    const double* z = y.data() + 2 * ndof_ + static_cast<std::size_t>(e) * J * w;
    for (std::size_t j = 0; j < J; ++j)
      for (int k = 0; k < w; ++k) o[k] -= prony_.alpha(j) * z[j * w + k];
  }
  return out;
}

VecX TensorMassViscoelasticOde::history_sum(double t, const VecX& y) const {
  const VecX u = displacement(t, y);
  const std::size_t J = prony_.size();
  const int w = width_;
  VecX out = VecX::Zero(ntets_ * w);
  double x[12];
  for (Index e = 0; e < ntets_; ++e) {
    tet_driver(e, u, x);
    const double* z = y.data() + 2 * ndof_ + static_cast<std::size_t>(e) * J * w;
    for (std::size_t j = 0; j < J; ++j)
      for (int k = 0; k < w; ++k) out[e * w + k] += prony_.alpha(j) * (x[k] - z[j * w + k]);  // alpha_j h_j
  }
  return out;
}

void TensorMassViscoelasticOde::internal_force(double t, const VecX& y, VecX& f) const {
  const VecX u = displacement(t, y);
  force(u, y.data() + 2 * ndof_, f);
}

// ================================================================== TensorMassQuasiStaticDae

TensorMassQuasiStaticDae::TensorMassQuasiStaticDae(const Mesh& mesh, const StVenantKirchhoff& long_term,
                                                   PronySeries prony, ViscoelasticOptions options,
                                                   const MechanicalSystem& system)
    : ode_(mesh, long_term, std::move(prony), options, system), system_(system) {}

void TensorMassQuasiStaticDae::jacobian_times(double /*t*/, const VecX& y, const VecX& /*yp*/, const VecX& v,
                                              double cj, VecX& Jv) {
  // rows: free u: d f_int = K_u du - sum alpha_j G dz_j (dead loads); constrained u: du_c;
  //       z_j: cj dz_j - (D du - dz_j)/tau_j
  const Index n = ode_.num_dofs();
  Jv.resize(size());
  u_ = y.head(n);
  g_ = v.head(n);
  VecX dx;
  ode_.linearise(u_, y.data() + n, g_, v.data() + n, f_, dx);
  Jv.head(n) = f_;
  for (Index k : system_.bc().dofs()) Jv[k] = v[k];
  const PronySeries& p = ode_.prony();
  const std::size_t J = p.size();
  const int w = ode_.width();
  const Index T = dx.size() / w;
  for (Index e = 0; e < T; ++e)
    for (std::size_t j = 0; j < J; ++j)
      for (int k = 0; k < w; ++k) {
        const Index i = n + static_cast<Index>((static_cast<std::size_t>(e) * J + j) * w) + k;
        Jv[i] = cj * v[i] - (dx[e * w + k] - v[i]) / p.tau(j);
      }
}

void TensorMassQuasiStaticDae::residual(double t, const VecX& y, const VecX& yp, VecX& r) {
  const Index n = ode_.num_dofs();
  r.resize(size());
  u_ = y.head(n);
  const double* z = y.data() + n;
  // equilibrium on the free DOFs: f_int(u, z) - f_ext(u, t)
  ode_.internal_force_at(u_, z, f_);
  system_.loads().assemble(u_, t, fext_);
  r.head(n) = f_ - fext_;
  // prescribed DOFs: u_c - g_c(t)
  g_ = u_;
  system_.bc().apply(t, g_);
  for (Index k : system_.bc().dofs()) r[k] = u_[k] - g_[k];
  // z_j' - (X_e(u) - z_j)/tau_j
  const VecX X = ode_.elastic_driver(u_);
  const PronySeries& p = ode_.prony();
  const std::size_t J = p.size();
  const int w = ode_.width();
  const Index T = X.size() / w;
  for (Index e = 0; e < T; ++e)
    for (std::size_t j = 0; j < J; ++j)
      for (int k = 0; k < w; ++k) {
        const Index i = n + static_cast<Index>((static_cast<std::size_t>(e) * J + j) * w + k);
        r[i] = yp[i] - (X[e * w + k] - y[i]) / p.tau(j);
      }
}

VecX TensorMassQuasiStaticDae::differential() const {
  VecX id = VecX::Zero(size());
  id.tail(ode_.num_history()).setOnes();
  return id;
}

VecX TensorMassQuasiStaticDae::initial_state(double t0, const VecX& u0) const {
  const VecX y_ode = ode_.initial_state(t0, u0, VecX::Zero(ode_.num_dofs()));
  VecX y(size());
  y.head(ode_.num_dofs()) = y_ode.head(ode_.num_dofs());
  y.tail(ode_.num_history()) = y_ode.tail(ode_.num_history());
  return y;
}

VecX TensorMassQuasiStaticDae::absolute_tolerances(double u_scale, double x_scale) const {
  VecX a(size());
  a.head(ode_.num_dofs()).setConstant(u_scale);
  a.tail(ode_.num_history()).setConstant(x_scale);
  return a;
}

}  // namespace tmlab::tm
