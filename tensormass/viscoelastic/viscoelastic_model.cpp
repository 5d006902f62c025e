// Prony-series viscoelastic St VK tensor-mass model; equations in viscoelastic_model.hpp and
// docs/theory/viscoelasticity.md (seed eqs. 9-21 as corrected in docs/theory/seed-errata.md).
#include "tensormass/viscoelastic/viscoelastic_model.hpp"
#include "tensormass/viscoelastic/committed_state.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"

#include <Eigen/Eigenvalues>

#include <cassert>
#include <cmath>

namespace tmlab::tm {

namespace {

using Opt = ViscoelasticOptions;
using Mat12 = Eigen::Matrix<double, 12, 12>;

// Voigt order of a symmetric 3x3 tensor: xx, yy, zz, xy, xz, yz.
/// A : A for a Voigt-stored symmetric tensor.
inline double voigt_dot(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}

}  // namespace

// ---------------------------------------------------------------- options

Opt::History Opt::parse_history(const std::string& s) {
  if (const auto h = prony_history_from_string(s)) return *h;
  throw Error("viscoelastic history '" + s + "' is unknown (use " + choice_list(prony_history_names(), "\"") +
              ")");
}
Opt::Integration Opt::parse_integration(const std::string& s) {
  if (const auto i = prony_integration_from_string(s)) return *i;
  throw Error("viscoelastic integration '" + s + "' is unknown (use " +
              choice_list(prony_integration_names(), "\"") + ")");
}
Opt::Relaxation Opt::parse_relaxation(const std::string& s) {
  if (const auto r = prony_relaxation_from_string(s)) return *r;
  throw Error("viscoelastic relaxation '" + s + "' is unknown (use " +
              choice_list(prony_relaxation_names(), "\"") + ")");
}

// ---------------------------------------------------------------- construction

ViscoelasticStVK::ViscoelasticStVK(const Mesh& mesh, const StVenantKirchhoff& long_term, PronySeries prony,
                                   ViscoelasticOptions options)
    : elastic_(mesh, long_term), material_(long_term), prony_(std::move(prony)), options_(options) {
  if (deviatoric() && !pk2()) {
    throw Error(
        "viscoelastic: relaxation 'deviatoric' requires history 'pk2' (the seed's nodal-force history has no "
        "deviatoric part)");
  }
  elastic_only_ = prony_.is_elastic();
  width_ = pk2() ? 6 : 12;
  if (options_.fast_threads < 0)
    throw Error("viscoelastic: fast_threads = " + std::to_string(options_.fast_threads) + " must be >= 0");
  if (options_.fast_threads > 0)
    fast_ = std::make_shared<const FastTetForce>(mesh, FastLaw::StVK, long_term.lambda, long_term.mu,
                                                 options_.fast_threads);
  const std::size_t nt = static_cast<std::size_t>(num_tets());
  const std::size_t nj = prony_.size();
  hist_.assign(nt * nj * static_cast<std::size_t>(width_), 0.0);
  driver_.assign(nt * static_cast<std::size_t>(width_), 0.0);
  if (pk2()) {
    rest_ = compute_tet_rest(mesh);
    s_hist_.assign(6 * nt, 0.0);
  } else {
    f_hist_ = VecX::Zero(num_dofs());
    // Pseudo-inverse of each tet's rest stiffness K_0 (rank 6: the 6 rigid modes removed), the
    // compliance used for the energy of the nodal-force branches.
    kpinv_.resize(144 * nt);
    const VecX zero = VecX::Zero(num_dofs());
    for (std::size_t t = 0; t < nt; ++t) {
      const Mat12 K0 = elastic_.tet_stiffness(static_cast<Index>(t), zero);
      Eigen::SelfAdjointEigenSolver<Mat12> es(0.5 * (K0 + K0.transpose()));
      const auto& ev = es.eigenvalues();
      const double cut = 1e-10 * ev.cwiseAbs().maxCoeff();
      Mat12 P = Mat12::Zero();
      for (int k = 0; k < 12; ++k)
        if (ev[k] > cut)
          P.noalias() += (1.0 / ev[k]) * es.eigenvectors().col(k) * es.eigenvectors().col(k).transpose();
      Eigen::Map<Mat12> dst(&kpinv_[144 * t]);
      dst = P;
    }
  }
  begin_step(0.0);  // trial = instantaneous response of the (empty) committed state
}

// ---------------------------------------------------------------- per-tet helpers

Mat3 ViscoelasticStVK::displacement_gradient(Index t, const VecX& u) const {
  const Tet& tet = elastic_.tets()[static_cast<std::size_t>(t)];
  const TetRest& r = rest_[static_cast<std::size_t>(t)];
  // grad u = sum_{j=1..3} (U_j - U_0) (x) a_j   (relative form, exact since sum_j a_j = 0)
  const Vec3 u0 = u.segment<3>(3 * static_cast<Eigen::Index>(tet[0]));
  Mat3 H = Mat3::Zero();
  for (int j = 1; j < 4; ++j)
    H.noalias() += (u.segment<3>(3 * static_cast<Eigen::Index>(tet[j])) - u0) * r.grad[j].transpose();
  return H;
}

void ViscoelasticStVK::driver(Index t, const VecX& u, double* x) const {
  if (!pk2()) {  // seed eq. 20: X_e = the tet's 12 nodal elastic forces, global axes
    const TensorMassStVK::Mat34 f = elastic_.tet_force(t, u);
    for (int p = 0; p < 4; ++p)
      for (int c = 0; c < 3; ++c) x[3 * p + c] = f(c, p);
    return;
  }
  const Mat3 H = displacement_gradient(t, u);
  const Mat3 E = 0.5 * (H + H.transpose() + H.transpose() * H);  // Green-Lagrange strain (eq. 1)
  driver_from_strain(E, x);
}

void ViscoelasticStVK::driver_from_strain(const Mat3& E, double* x) const {
  if (deviatoric()) {
    // S_dev = 2 mu (E - tr(E)/3 I)
    const Mat3 Ed = E - (E.trace() / 3.0) * Mat3::Identity();
    to_voigt(2.0 * material_.mu * Ed, x);
  } else {
    to_voigt(material_.pk2_stress(E), x);  // S_e = lambda tr(E) I + 2 mu E
  }
}

double ViscoelasticStVK::branch_form(Index t, const double* h, double* rate) const {
  // Psi = sum_j alpha_j/2 h_j : M : h_j,  D = sum_j alpha_j h_j : M : h_j / tau_j
  // pk2 full: M = V C^{-1}, h:C^{-1}:h = (h:h - lambda/(3 lambda + 2 mu) (tr h)^2) / (2 mu)
  // pk2 dev:  M = V (2 mu)^{-1} on deviators;  nodal_force: M = K_0^+ (12x12)
  const std::size_t w = static_cast<std::size_t>(width_);
  double psi = 0.0, d = 0.0;
  for (std::size_t j = 0; j < prony_.size(); ++j) {
    const double* hj = h + j * w;
    double q = 0.0;
    if (pk2()) {
      const double V = rest_[static_cast<std::size_t>(t)].volume;
      const double hh = voigt_dot(hj, hj);
      if (deviatoric()) {
        q = V * hh / (2.0 * material_.mu);
      } else {
        const double tr = hj[0] + hj[1] + hj[2];
        const double lam = material_.lambda, mu = material_.mu;
        q = V * (hh - lam / (3.0 * lam + 2.0 * mu) * tr * tr) / (2.0 * mu);
      }
    } else {
      const Eigen::Map<const Mat12> P(&kpinv_[144 * static_cast<std::size_t>(t)]);
      const Eigen::Map<const Eigen::Matrix<double, 12, 1>> hv(hj);
      q = hv.dot(P * hv);
    }
    psi += 0.5 * prony_.alpha(j) * q;
    d += prony_.alpha(j) * q / prony_.tau(j);
  }
  *rate = d;
  return psi;
}

// ---------------------------------------------------------------- steps

void ViscoelasticStVK::update_trial() const {
  // X_hist = sum_j alpha_j (a_j h_j^c - c_j X_e^c)   (the u-independent part of eqs. 20-21)
  const std::size_t nt = static_cast<std::size_t>(num_tets()), nj = prony_.size();
  const std::size_t w = static_cast<std::size_t>(width_);
  double loc[12];
  if (!pk2()) f_hist_.setZero();
  for (std::size_t t = 0; t < nt; ++t) {
    const double* X = &driver_[w * t];
    for (std::size_t k = 0; k < w; ++k) loc[k] = 0.0;
    for (std::size_t j = 0; j < nj; ++j) {
      const double al = prony_.alpha(j), a = factors_[j].a, c = factors_[j].c;
      const double* h = &hist_[(t * nj + j) * w];
      for (std::size_t k = 0; k < w; ++k) loc[k] += al * (a * h[k] - c * X[k]);
    }
    if (pk2()) {
      for (std::size_t k = 0; k < 6; ++k) s_hist_[6 * t + k] = loc[k];
    } else {
      const Tet& tet = elastic_.tets()[t];
      for (int p = 0; p < 4; ++p)
        for (int c = 0; c < 3; ++c) f_hist_[3 * static_cast<Eigen::Index>(tet[p]) + c] += loc[3 * p + c];
    }
  }
  trial_stale_ = false;
}

void ViscoelasticStVK::begin_step(double dt) {
  if (!(dt >= 0.0) || !std::isfinite(dt))
    throw Error("viscoelastic: step size dt = " + std::to_string(dt) + " must be >= 0");
  dt_ = dt;
  factors_.resize(prony_.size());
  gain_ = 0.0;
  for (std::size_t j = 0; j < prony_.size(); ++j) {
    factors_[j] = recursion_factors(options_.integration, dt, prony_.tau(j));
    gain_ += prony_.alpha(j) * factors_[j].c;  // g = sum_j alpha_j c_j
  }
  if (elastic_only_) {
    gain_ = 0.0;
    return;
  }
  trial_stale_ = true;  // the constant trial parts are recomputed on first use (ensure_trial)
}

void ViscoelasticStVK::commit_tet(std::size_t t, const double* x, bool book, double& psi, double& rate) {
  const std::size_t nj = prony_.size(), w = static_cast<std::size_t>(width_);
  double* X = &driver_[w * t];
  for (std::size_t j = 0; j < nj; ++j) {
    // h_j^{n+1} = a_j h_j^n + c_j (X_e^{n+1} - X_e^n)   (eq. 20 family)
    double* h = &hist_[(t * nj + j) * w];
    const double a = factors_[j].a, c = factors_[j].c;
    for (std::size_t k = 0; k < w; ++k) h[k] = a * h[k] + c * (x[k] - X[k]);
  }
  for (std::size_t k = 0; k < w; ++k) X[k] = x[k];
  if (book) {
    double r = 0.0;
    psi += branch_form(static_cast<Index>(t), &hist_[t * nj * w], &r);
    rate += r;
  }
}

void ViscoelasticStVK::finish_commit(bool book, double psi, double rate) {
  if (book) {
    // Trapezoidal quadrature of the dissipation rate over the step (>= 0: both rates are >= 0).
    step_dissipation_ = 0.5 * dt_ * (committed_rate_ + rate);
    total_dissipation_ += step_dissipation_;
    committed_rate_ = rate;
    committed_branch_ = psi;
  }
  // Trial at dt = 0: internal_force(u) is now the committed total force. begin_step(0) without its
  // pass over the tets, which ensure_trial() makes on first use.
  dt_ = 0.0;
  gain_ = 0.0;
  for (std::size_t j = 0; j < prony_.size(); ++j) {
    factors_[j] = recursion_factors(options_.integration, 0.0, prony_.tau(j));
    gain_ += prony_.alpha(j) * factors_[j].c;
  }
  trial_stale_ = true;
}

void ViscoelasticStVK::commit_step(const VecX& u) {
  assert(u.size() == num_dofs());
  const bool book = options_.energy_bookkeeping;
  if (book) defer_spring_energy(u);  // long-term spring W_e(u), computed when asked for
  if (elastic_only_) {
    step_dissipation_ = 0.0;
    dt_ = 0.0;
    return;
  }
  const std::size_t nt = static_cast<std::size_t>(num_tets());
  double x[12];
  double psi = 0.0, rate = 0.0;
  for (std::size_t t = 0; t < nt; ++t) {
    driver(static_cast<Index>(t), u, x);
    commit_tet(t, x, book, psi, rate);
  }
  finish_commit(book, psi, rate);
}

void ViscoelasticStVK::force_and_commit(const VecX& u, VecX& f) {
  const bool book = options_.energy_bookkeeping;
  if (fast_ && pk2() && !book && !elastic_only_ &&
      prony_.size() <= static_cast<std::size_t>(FastTetForce::PronyStep::kMaxTerms)) {
    // The fast kernel's fused pass: force with S = S_e + sum_j alpha_j h_j^{n+1} and the history
    // update together; the trial parts S_hist are not needed (equal to the reference to round-off).
    FastTetForce::PronyStep step;
    step.terms = static_cast<int>(prony_.size());
    step.deviatoric = deviatoric();
    for (std::size_t j = 0; j < prony_.size(); ++j) {
      step.alpha[j] = prony_.alpha(j);
      step.a[j] = factors_[j].a;
      step.c[j] = factors_[j].c;
    }
    fast_->force_and_commit_pk2(u, step, hist_.data(), driver_.data(), f);
    finish_commit(false, 0.0, 0.0);
    return;
  }
  if (elastic_only_ || fast_) {
    internal_force(u, f);
    commit_step(u);
    return;
  }
  assert(u.size() == num_dofs());
  ensure_trial();
  if (book) defer_spring_energy(u);  // long-term spring W_e(u), as commit_step
  const std::size_t nt = static_cast<std::size_t>(num_tets());
  const auto& tets = elastic_.tets();
  double x[12];
  double psi = 0.0, rate = 0.0;
  f.setZero(num_dofs());
  if (!pk2()) {
    // One tensor-mass evaluation per tet: assembled as TensorMassStVK::internal_force does and kept
    // per tet as TensorMassStVK::tet_force does (the driver), so both match the separate calls bit
    // for bit.
    double* F = f.data();
    double g[9];
    for (std::size_t t = 0; t < nt; ++t) {
      const Tet& tet = tets[t];
      elastic_.tet_gradient(static_cast<Index>(t), u, g);
      double* f0 = F + 3 * static_cast<std::ptrdiff_t>(tet[0]);
      for (int j = 0; j < 3; ++j) {
        double* fj = F + 3 * static_cast<std::ptrdiff_t>(tet[j + 1]);
        for (int c = 0; c < 3; ++c) {
          fj[c] += g[3 * j + c];
          f0[c] -= g[3 * j + c];
        }
      }
      TensorMassStVK::Mat34 ft;
      for (int j = 0; j < 3; ++j) ft.col(j + 1) = Vec3(g[3 * j], g[3 * j + 1], g[3 * j + 2]);
      ft.col(0) = -(ft.col(1) + ft.col(2) + ft.col(3));
      for (int p = 0; p < 4; ++p)
        for (int c = 0; c < 3; ++c) x[3 * p + c] = ft(c, p);
      commit_tet(t, x, book, psi, rate);
    }
    f = (1.0 + gain_) * f + f_hist_;  // as internal_force: f = (1 + g) f_e + f_hist
  } else {
    // One strain per tet: the trial force of internal_force and the driver of commit_step.
    const StVenantKirchhoff eff = trial_elasticity();
    const double lam_eff = eff.lambda, mu_eff = eff.mu;
    for (std::size_t t = 0; t < nt; ++t) {
      const TetRest& r = rest_[t];
      const Mat3 H = displacement_gradient(static_cast<Index>(t), u);
      const Mat3 E = 0.5 * (H + H.transpose() + H.transpose() * H);
      Mat3 S = from_voigt(&s_hist_[6 * t]);
      S.diagonal().array() += lam_eff * E.trace();
      S.noalias() += (2.0 * mu_eff) * E;
      const Mat3 VP = r.volume * ((Mat3::Identity() + H) * S);
      for (int p = 0; p < 4; ++p)
        f.segment<3>(3 * static_cast<Eigen::Index>(tets[t][p])).noalias() += VP * r.grad[p];
      driver_from_strain(E, x);
      commit_tet(t, x, book, psi, rate);
    }
  }
  finish_commit(book, psi, rate);
}

// ---------------------------------------------------------------- trial evaluation

double ViscoelasticStVK::trial_potential(const VecX& u) const {
  if (elastic_only_) return elastic_.energy(u);
  ensure_trial();
  if (!pk2()) return (1.0 + gain_) * elastic_.energy(u) + f_hist_.dot(u);  // (1+g) W_e + f_hist . u
  // sum_t V [ lambda_eff/2 (tr E)^2 + mu_eff E:E + S_hist : E ]
  const StVenantKirchhoff eff = trial_elasticity();
  const double lam_eff = eff.lambda, mu_eff = eff.mu;
  double w = 0.0;
  for (Index t = 0; t < num_tets(); ++t) {
    const Mat3 H = displacement_gradient(t, u);
    const Mat3 E = 0.5 * (H + H.transpose() + H.transpose() * H);
    const double tr = E.trace();
    double e6[6];
    to_voigt(E, e6);
    w += rest_[static_cast<std::size_t>(t)].volume *
         (0.5 * lam_eff * tr * tr + mu_eff * E.cwiseProduct(E).sum() +
          voigt_dot(&s_hist_[6 * static_cast<std::size_t>(t)], e6));
  }
  return w;
}

double ViscoelasticStVK::energy(const VecX& u) const {
  const double we = elastic_.energy(u);
  if (elastic_only_) return we;
  ensure_trial();
  // + branch energies of the trial histories h_j(u) = a_j h_j^c + c_j (X_e(u) - X_e^c)
  const std::size_t nt = static_cast<std::size_t>(num_tets()), nj = prony_.size();
  const std::size_t w = static_cast<std::size_t>(width_);
  std::vector<double> h(nj * w);
  double x[12], psi = 0.0, rate = 0.0;
  for (std::size_t t = 0; t < nt; ++t) {
    driver(static_cast<Index>(t), u, x);
    const double* X = &driver_[w * t];
    for (std::size_t j = 0; j < nj; ++j) {
      const double* hc = &hist_[(t * nj + j) * w];
      for (std::size_t k = 0; k < w; ++k)
        h[j * w + k] = factors_[j].a * hc[k] + factors_[j].c * (x[k] - X[k]);
    }
    psi += branch_form(static_cast<Index>(t), h.data(), &rate);
  }
  return we + psi;
}

void ViscoelasticStVK::internal_force(const VecX& u, VecX& f) const {
  if (elastic_only_) {
    elastic_.internal_force(u, f);
    return;
  }
  ensure_trial();
  if (!pk2()) {
    // f = (1 + g) f_e(u) + f_hist   (eqs. 20-21 on nodal forces)
    if (fast_)
      fast_->internal_force(u, f);
    else
      elastic_.internal_force(u, f);
    f = (1.0 + gain_) * f + f_hist_;
    return;
  }
  if (fast_) {  // S_total = lambda_eff tr(E) I + 2 mu_eff E + S_hist in the fast kernel
    const StVenantKirchhoff eff = trial_elasticity();
    fast_->trial_force_pk2(u, eff.lambda, eff.mu, s_hist_.data(), f);
    return;
  }
  assert(u.size() == num_dofs());
  f.setZero(num_dofs());
  // S_total = lambda_eff tr(E) I + 2 mu_eff E + S_hist, f_p = V F S_total a_p
  const StVenantKirchhoff eff = trial_elasticity();
  const double lam_eff = eff.lambda, mu_eff = eff.mu;
  const auto& tets = elastic_.tets();
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const TetRest& r = rest_[t];
    const Mat3 H = displacement_gradient(static_cast<Index>(t), u);
    const Mat3 E = 0.5 * (H + H.transpose() + H.transpose() * H);
    Mat3 S = from_voigt(&s_hist_[6 * t]);
    S.diagonal().array() += lam_eff * E.trace();
    S.noalias() += (2.0 * mu_eff) * E;
    const Mat3 VP = r.volume * ((Mat3::Identity() + H) * S);
    for (int p = 0; p < 4; ++p)
      f.segment<3>(3 * static_cast<Eigen::Index>(tets[t][p])).noalias() += VP * r.grad[p];
  }
}

StVenantKirchhoff ViscoelasticStVK::trial_elasticity() const {
  // Full: (1 + g) C.  Deviatoric: C + g 2 mu (I_sym - 1/3 I (x) I), i.e. mu (1 + g), lambda - 2 g mu / 3.
  const double g = gain_, lam = material_.lambda, mu = material_.mu;
  return {deviatoric() ? lam - 2.0 * g * mu / 3.0 : (1.0 + g) * lam, (1.0 + g) * mu};
}

void ViscoelasticStVK::tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const {
  if (elastic_only_) {
    elastic_.tangent_apply(u, v, Kv);
    return;
  }
  ensure_trial();
  if (!pk2()) {
    elastic_.tangent_apply(u, v, Kv);
    Kv *= (1.0 + gain_);  // K = (1 + g) K_e
    return;
  }
  assert(u.size() == num_dofs() && v.size() == num_dofs());
  Kv.setZero(num_dofs());
  const StVenantKirchhoff eff = trial_elasticity();
  const double lam_eff = eff.lambda, mu_eff = eff.mu;
  const auto& tets = elastic_.tets();
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const TetRest& r = rest_[t];
    const Mat3 H = displacement_gradient(static_cast<Index>(t), u);
    const Mat3 dF = displacement_gradient(static_cast<Index>(t), v);
    const Mat3 F = Mat3::Identity() + H;
    const Mat3 E = 0.5 * (H + H.transpose() + H.transpose() * H);
    Mat3 S = from_voigt(&s_hist_[6 * t]);
    S.diagonal().array() += lam_eff * E.trace();
    S.noalias() += (2.0 * mu_eff) * E;
    // dE = sym(F^T dF), dS = lambda_eff tr(dE) I + 2 mu_eff dE, dP = dF S + F dS
    const Mat3 FtdF = F.transpose() * dF;
    const Mat3 dE = 0.5 * (FtdF + FtdF.transpose());
    Mat3 dS = (2.0 * mu_eff) * dE;
    dS.diagonal().array() += lam_eff * dE.trace();
    const Mat3 VdP = r.volume * (dF * S + F * dS);
    for (int p = 0; p < 4; ++p)
      Kv.segment<3>(3 * static_cast<Eigen::Index>(tets[t][p])).noalias() += VdP * r.grad[p];
  }
}

void ViscoelasticStVK::tangent(const VecX& u, SpMat& K) const {
  if (elastic_only_) {
    elastic_.tangent(u, K);
    return;
  }
  ensure_trial();
  if (!pk2()) {
    elastic_.tangent(u, K);  // K = (1 + g) K_e (the history part of the force is constant in u)
    const double s = 1.0 + gain_;
    double* v = K.valuePtr();
    for (Eigen::Index k = 0; k < K.nonZeros(); ++k) v[k] *= s;
    return;
  }
  assert(u.size() == num_dofs());
  const TangentPattern& pattern = elastic_.pattern();
  if (!pattern.matches(K))
    pattern.reset(K);
  else
    std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
  double* values = K.valuePtr();
  const StVenantKirchhoff eff = trial_elasticity();
  const double lam_eff = eff.lambda, mu_eff = eff.mu;
  const auto& tets = elastic_.tets();
  Mat12 Kt;
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const TetRest& r = rest_[t];
    const Mat3 H = displacement_gradient(static_cast<Index>(t), u);
    const Mat3 F = Mat3::Identity() + H;
    const Mat3 E = 0.5 * (H + H.transpose() + H.transpose() * H);
    Mat3 S = from_voigt(&s_hist_[6 * t]);
    S.diagonal().array() += lam_eff * E.trace();
    S.noalias() += (2.0 * mu_eff) * E;
    const Mat3 FFt = F * F.transpose();
    Vec3 b[4];
    for (int p = 0; p < 4; ++p) b[p] = F * r.grad[p];
    // K_pq = V [ (a_p . S_total a_q) I + lambda_eff b_p b_q^T + mu_eff b_q b_p^T + mu_eff (a_p . a_q) F F^T ]
    for (int p = 0; p < 4; ++p) {
      const Vec3 Sap = S * r.grad[p];
      for (int q = p; q < 4; ++q) {
        const double geo = Sap.dot(r.grad[q]);
        const double apaq = r.grad[p].dot(r.grad[q]);
        Mat3 B = (lam_eff * b[p]) * b[q].transpose();
        B.noalias() += (mu_eff * b[q]) * b[p].transpose();
        B.noalias() += (mu_eff * apaq) * FFt;
        B.diagonal().array() += geo;
        B *= r.volume;
        Kt.block<3, 3>(3 * p, 3 * q) = B;
        if (q != p) Kt.block<3, 3>(3 * q, 3 * p) = B.transpose();
      }
    }
    pattern.scatter(static_cast<Index>(t), tets[t], Kt, values);
  }
}

// ---------------------------------------------------------------- checkpoints

double ViscoelasticStVK::committed_elastic_energy() const {
  if (spring_stale_) {
    committed_elastic_ = elastic_.energy(committed_u_);
    spring_stale_ = false;
  }
  return committed_elastic_;
}

std::vector<double> ViscoelasticStVK::committed_state() const {
  return pack_committed_state(hist_, driver_,
                              {committed_elastic_energy(), committed_branch_, committed_rate_,
                               step_dissipation_, total_dissipation_});
}

void ViscoelasticStVK::restore_committed_state(const std::vector<double>& s) {
  const CommittedEnergies e = unpack_committed_state(s, hist_, driver_);
  committed_elastic_ = e.elastic;
  spring_stale_ = false;
  committed_branch_ = e.branch;
  committed_rate_ = e.rate;
  step_dissipation_ = e.step_dissipation;
  total_dissipation_ = e.total_dissipation;
  begin_step(0.0);  // the trial state commit_step leaves behind
}

}  // namespace tmlab::tm
