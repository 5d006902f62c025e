// Prony-series viscoelastic St VK tensor-mass model; equations in viscoelastic_model.hpp and
// docs/theory/viscoelasticity.md (seed eqs. 9-21 as corrected in docs/theory/seed-errata.md).
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include "core/base/error.hpp"

#include <Eigen/Eigenvalues>

#include <cassert>
#include <cmath>

namespace tmlab::tm {

namespace {

using Mat12 = Eigen::Matrix<double, 12, 12>;

// Voigt order of a symmetric 3x3 tensor: xx, yy, zz, xy, xz, yz.
/// A : A for a Voigt-stored symmetric tensor.
inline double voigt_dot(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}

}  // namespace

// ---------------------------------------------------------------- construction

ViscoelasticStVK::ViscoelasticStVK(const Mesh& mesh, const StVenantKirchhoff& long_term, PronySeries prony,
                                   ViscoelasticOptions options)
    : ViscoelasticBase(std::move(prony), options), elastic_(mesh, long_term), material_(long_term) {
  if (deviatoric() && !pk2()) {
    throw Error(
        "viscoelastic: relaxation 'deviatoric' requires history 'pk2' (the seed's nodal-force history has no "
        "deviatoric part)");
  }
  if (options.fast_threads < 0)
    throw Error("viscoelastic: fast_threads = " + std::to_string(options.fast_threads) + " must be >= 0");
  if (options.fast_threads > 0)
    fast_ = std::make_shared<const FastTetForce>(mesh, FastLaw::StVK, long_term.lambda, long_term.mu,
                                                 options.fast_threads);
  const std::size_t nt = static_cast<std::size_t>(num_tets());
  allocate_history(nt, pk2() ? 6 : 12);
  // The fused pass streams the pk2 history in the fast kernel's lane order (docs/performance.md).
  if (fast_ && pk2()) use_lane_order(FastTetForce::kLanes, fast_->tet_slots(), fast_->num_slots());
  if (pk2()) {
    rest_ = compute_tet_rest(mesh);
    s_hist_.assign(6 * nt, 0.0);
    if (fast_) s_hist_lanes_.assign(driver_size(), 0.0);  // the driver's lane order, zero padding
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

void ViscoelasticStVK::driver(std::size_t t, const VecX& u, double* x) const {
  if (!pk2()) {  // seed eq. 20: X_e = the tet's 12 nodal elastic forces, global axes
    const TensorMassStVK::Mat34 f = elastic_.tet_force(static_cast<Index>(t), u);
    for (int p = 0; p < 4; ++p)
      for (int c = 0; c < 3; ++c) x[3 * p + c] = f(c, p);
    return;
  }
  const Mat3 H = displacement_gradient(static_cast<Index>(t), u);
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

double ViscoelasticStVK::branch_form(std::size_t t, const double* h, double* rate) const {
  // Psi = sum_j alpha_j/2 h_j : M : h_j,  D = sum_j alpha_j h_j : M : h_j / tau_j
  // pk2 full: M = V C^{-1}, h:C^{-1}:h = (h:h - lambda/(3 lambda + 2 mu) (tr h)^2) / (2 mu)
  // pk2 dev:  M = V (2 mu)^{-1} on deviators;  nodal_force: M = K_0^+ (12x12)
  return branch_sums(h, rate, [&](const double* hj) {
    double q = 0.0;
    if (pk2()) {
      const double V = rest_[t].volume;
      const double hh = voigt_dot(hj, hj);
      if (deviatoric()) {
        q = V * hh / (2.0 * material_.mu);
      } else {
        const double tr = hj[0] + hj[1] + hj[2];
        const double lam = material_.lambda, mu = material_.mu;
        q = V * (hh - lam / (3.0 * lam + 2.0 * mu) * tr * tr) / (2.0 * mu);
      }
    } else {
      const Eigen::Map<const Mat12> P(&kpinv_[144 * t]);
      const Eigen::Map<const Eigen::Matrix<double, 12, 1>> hv(hj);
      q = hv.dot(P * hv);
    }
    return q;
  });
}

// ---------------------------------------------------------------- steps

void ViscoelasticStVK::update_trial() const {
  // X_hist = sum_j alpha_j (a_j h_j^c - c_j X_e^c)   (the u-independent part of eqs. 20-21)
  const std::size_t nt = static_cast<std::size_t>(num_tets());
  double loc[12];
  if (!pk2()) f_hist_.setZero();
  for (std::size_t t = 0; t < nt; ++t) {
    if (pk2()) {
      history_part(t, &s_hist_[6 * t]);
      if (fast_)
        for (std::size_t k = 0; k < 6; ++k) s_hist_lanes_[driver_index(t, k)] = s_hist_[6 * t + k];
    } else {
      history_part(t, loc);
      const Tet& tet = elastic_.tets()[t];
      for (int p = 0; p < 4; ++p)
        for (int c = 0; c < 3; ++c) f_hist_[3 * static_cast<Eigen::Index>(tet[p]) + c] += loc[3 * p + c];
    }
  }
  trial_stale_ = false;
}

void ViscoelasticStVK::force_and_commit(const VecX& u, VecX& f) {
  const bool book = options().energy_bookkeeping;
  if (fast_ && pk2() && !book && !elastic_only() &&
      prony().size() <= static_cast<std::size_t>(FastTetForce::PronyStep::kMaxTerms)) {
    // The fast kernel's fused pass: force with S = S_e + sum_j alpha_j h_j^{n+1} and the history
    // update together; the trial parts S_hist are not needed (equal to the reference to round-off).
    FastTetForce::PronyStep step;
    step.terms = static_cast<int>(prony().size());
    step.deviatoric = deviatoric();
    for (std::size_t j = 0; j < prony().size(); ++j) {
      step.alpha[j] = prony().alpha(j);
      step.a[j] = factors(j).a;
      step.c[j] = factors(j).c;
    }
    fast_->force_and_commit_pk2(u, step, history_data(), driver_data(), f);
    finish_commit(false, 0.0, 0.0);
    return;
  }
  if (elastic_only() || fast_) {
    internal_force(u, f);
    commit_step(u);
    return;
  }
  assert(u.size() == num_dofs());
  ensure_trial();
  begin_commit(u);  // the long-term spring W_e(u) deferred, as commit_step
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
      commit_tet(t, x, psi, rate);
    }
    f = (1.0 + trial_gain()) * f + f_hist_;  // as internal_force: f = (1 + g) f_e + f_hist
  } else {
    // One strain per tet: the trial force of internal_force and the driver of commit_step.
    const StVenantKirchhoff eff = trial_elasticity();
    const double lam_eff = eff.lambda, mu_eff = eff.mu;
    for (std::size_t t = 0; t < nt; ++t) {
      driver_from_strain(add_trial_force(t, u, lam_eff, mu_eff, f), x);
      commit_tet(t, x, psi, rate);
    }
  }
  finish_commit(book, psi, rate);
}

// ---------------------------------------------------------------- trial evaluation

double ViscoelasticStVK::trial_potential(const VecX& u) const {
  if (elastic_only()) return elastic_.energy(u);
  ensure_trial();
  if (!pk2()) return (1.0 + trial_gain()) * elastic_.energy(u) + f_hist_.dot(u);  // (1+g) W_e + f_hist . u
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

void ViscoelasticStVK::internal_force(const VecX& u, VecX& f) const {
  if (elastic_only()) {
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
    f = (1.0 + trial_gain()) * f + f_hist_;
    return;
  }
  if (fast_) {  // S_total = lambda_eff tr(E) I + 2 mu_eff E + S_hist in the fast kernel
    const StVenantKirchhoff eff = trial_elasticity();
    fast_->trial_force_pk2(u, eff.lambda, eff.mu, s_hist_lanes_.data(), f);
    return;
  }
  assert(u.size() == num_dofs());
  f.setZero(num_dofs());
  // S_total = lambda_eff tr(E) I + 2 mu_eff E + S_hist, f_p = V F S_total a_p
  const StVenantKirchhoff eff = trial_elasticity();
  const double lam_eff = eff.lambda, mu_eff = eff.mu;
  for (std::size_t t = 0; t < elastic_.tets().size(); ++t) add_trial_force(t, u, lam_eff, mu_eff, f);
}

Mat3 ViscoelasticStVK::add_trial_force(std::size_t t, const VecX& u, double lam_eff, double mu_eff,
                                       VecX& f) const {
  const TetRest& r = rest_[t];
  const Mat3 H = displacement_gradient(static_cast<Index>(t), u);
  const Mat3 E = 0.5 * (H + H.transpose() + H.transpose() * H);
  Mat3 S = from_voigt(&s_hist_[6 * t]);
  S.diagonal().array() += lam_eff * E.trace();
  S.noalias() += (2.0 * mu_eff) * E;
  const Mat3 VP = r.volume * ((Mat3::Identity() + H) * S);
  const Tet& tet = elastic_.tets()[t];
  for (int p = 0; p < 4; ++p) f.segment<3>(3 * static_cast<Eigen::Index>(tet[p])).noalias() += VP * r.grad[p];
  return E;
}

StVenantKirchhoff ViscoelasticStVK::trial_elasticity() const {
  // Full: (1 + g) C.  Deviatoric: C + g 2 mu (I_sym - 1/3 I (x) I), i.e. mu (1 + g), lambda - 2 g mu / 3.
  const double g = trial_gain(), lam = material_.lambda, mu = material_.mu;
  return {deviatoric() ? lam - 2.0 * g * mu / 3.0 : (1.0 + g) * lam, (1.0 + g) * mu};
}

void ViscoelasticStVK::tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const {
  if (elastic_only()) {
    elastic_.tangent_apply(u, v, Kv);
    return;
  }
  ensure_trial();
  if (!pk2()) {
    elastic_.tangent_apply(u, v, Kv);
    Kv *= (1.0 + trial_gain());  // K = (1 + g) K_e
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
  if (elastic_only()) {
    elastic_.tangent(u, K);
    return;
  }
  ensure_trial();
  if (!pk2()) {
    elastic_.tangent(u, K);  // K = (1 + g) K_e (the history part of the force is constant in u)
    const double s = 1.0 + trial_gain();
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

}  // namespace tmlab::tm
