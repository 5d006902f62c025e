// Prony-series viscoelasticity on the PK2 stress of a general hyperelastic law; equations in
// viscoelastic_law.hpp.
#include "tensormass/viscoelastic/viscoelastic_law.hpp"
#include "tensormass/viscoelastic/committed_state.hpp"

#include "core/base/error.hpp"

#include <cassert>
#include <cmath>
#include <limits>

namespace tmlab::tm {

namespace {

inline double voigt_dot(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}
inline Mat3 green(const Mat3& F) { return 0.5 * (F.transpose() * F - Mat3::Identity()); }
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

ViscoelasticHyperelastic::ViscoelasticHyperelastic(const Mesh& mesh, Law long_term, PronySeries prony,
                                                   ViscoelasticOptions options)
    : elastic_(mesh, std::move(long_term)), prony_(std::move(prony)), options_(options) {
  using Opt = ViscoelasticOptions;
  const std::string law = elastic_.law().name();
  if (options_.history != Opt::History::Pk2)
    throw Error("viscoelastic history '" + Opt::to_string(options_.history) +
                "' is not available with law '" + law +
                "' (a general law relaxes its PK2 stress: use history \"pk2\")");
  if (options_.relaxation != Opt::Relaxation::Full)
    throw Error("viscoelastic relaxation '" + Opt::to_string(options_.relaxation) +
                "' is not available with the general-law model (law '" + law +
                "'): use \"full\" (deviatoric relaxation is defined for St VK only)");
  c0_ = elastic_.law().small_strain();
  elastic_only_ = prony_.is_elastic();
  const std::size_t nt = static_cast<std::size_t>(num_tets());
  hist_.assign(nt * prony_.size() * 6, 0.0);
  driver_.assign(nt * 6, 0.0);
  s_hist_.assign(nt * 6, 0.0);
  begin_step(0.0);
}

Mat3 ViscoelasticHyperelastic::total_stress(std::size_t t, const Mat3& S_e) const {
  return (1.0 + gain_) * S_e + from_voigt(&s_hist_[6 * t]);
}

double ViscoelasticHyperelastic::branch_form(std::size_t t, const double* h, double* rate) const {
  // Psi = sum_j alpha_j/2 V h_j : C_0^{-1} : h_j, h:C_0^{-1}:h = (h:h - lambda/(3 lambda + 2 mu) (tr h)^2)/(2
  // mu)
  const double V = elastic_.rest(static_cast<Index>(t)).volume, lam = c0_.lambda, mu = c0_.mu;
  double psi = 0.0, d = 0.0;
  for (std::size_t j = 0; j < prony_.size(); ++j) {
    const double* hj = h + 6 * j;
    const double tr = hj[0] + hj[1] + hj[2];
    const double q = V * (voigt_dot(hj, hj) - lam / (3.0 * lam + 2.0 * mu) * tr * tr) / (2.0 * mu);
    psi += 0.5 * prony_.alpha(j) * q;
    d += prony_.alpha(j) * q / prony_.tau(j);
  }
  *rate = d;
  return psi;
}

void ViscoelasticHyperelastic::update_trial() {
  const std::size_t nt = static_cast<std::size_t>(num_tets()), nj = prony_.size();
  for (std::size_t t = 0; t < nt; ++t) {
    const double* X = &driver_[6 * t];
    double* s = &s_hist_[6 * t];
    for (std::size_t k = 0; k < 6; ++k) s[k] = 0.0;
    for (std::size_t j = 0; j < nj; ++j) {
      const double al = prony_.alpha(j), a = factors_[j].a, c = factors_[j].c;
      const double* h = &hist_[(t * nj + j) * 6];
      for (std::size_t k = 0; k < 6; ++k) s[k] += al * (a * h[k] - c * X[k]);  // S_hist
    }
  }
}

void ViscoelasticHyperelastic::begin_step(double dt) {
  if (!(dt >= 0.0) || !std::isfinite(dt))
    throw Error("viscoelastic: step size dt = " + std::to_string(dt) + " must be >= 0");
  dt_ = dt;
  factors_.resize(prony_.size());
  gain_ = 0.0;
  for (std::size_t j = 0; j < prony_.size(); ++j) {
    factors_[j] = recursion_factors(options_.integration, dt, prony_.tau(j));
    gain_ += prony_.alpha(j) * factors_[j].c;
  }
  if (elastic_only_) {
    gain_ = 0.0;
    return;
  }
  update_trial();
}

void ViscoelasticHyperelastic::commit_step(const VecX& u) {
  assert(u.size() == num_dofs());
  const bool book = options_.energy_bookkeeping;
  if (book) {  // the long-term spring W_e(u): computed when asked for (committed_elastic_energy())
    committed_u_ = u;
    spring_stale_ = true;
  }
  if (elastic_only_) {
    step_dissipation_ = 0.0;
    dt_ = 0.0;
    return;
  }
  const std::size_t nt = static_cast<std::size_t>(num_tets()), nj = prony_.size();
  double x[6], psi = 0.0, rate = 0.0;
  for (std::size_t t = 0; t < nt; ++t) {
    const Mat3 F = elastic_.deformation_gradient(static_cast<Index>(t), u);
    to_voigt(elastic_.law().pk2_stress(green(F)), x);
    double* X = &driver_[6 * t];
    for (std::size_t j = 0; j < nj; ++j) {
      double* h = &hist_[(t * nj + j) * 6];  // h_j^{n+1} = a_j h_j^n + c_j (S_e^{n+1} - S_e^n)
      for (std::size_t k = 0; k < 6; ++k) h[k] = factors_[j].a * h[k] + factors_[j].c * (x[k] - X[k]);
    }
    for (std::size_t k = 0; k < 6; ++k) X[k] = x[k];
    if (book) {
      double r = 0.0;
      psi += branch_form(t, &hist_[t * nj * 6], &r);
      rate += r;
    }
  }
  if (book) {
    step_dissipation_ = 0.5 * dt_ * (committed_rate_ + rate);
    total_dissipation_ += step_dissipation_;
    committed_rate_ = rate;
    committed_branch_ = psi;
  }
  begin_step(0.0);
}

double ViscoelasticHyperelastic::trial_potential(const VecX& u) const {
  if (elastic_only_) return elastic_.energy(u);
  double w = 0.0;
  for (Index t = 0; t < num_tets(); ++t) {
    const Mat3 F = elastic_.deformation_gradient(t, u);
    if (!elastic_.in_domain(F)) return std::numeric_limits<double>::infinity();
    const Mat3 E = green(F);
    double e6[6];
    to_voigt(E, e6);
    w += elastic_.rest(t).volume * ((1.0 + gain_) * elastic_.law().energy_density(E) +
                                    voigt_dot(&s_hist_[6 * static_cast<std::size_t>(t)], e6));
  }
  return w;
}

double ViscoelasticHyperelastic::energy(const VecX& u) const {
  const double we = elastic_.energy(u);
  if (elastic_only_) return we;
  const std::size_t nt = static_cast<std::size_t>(num_tets()), nj = prony_.size();
  std::vector<double> h(nj * 6);
  double x[6], psi = 0.0, rate = 0.0;
  for (std::size_t t = 0; t < nt; ++t) {
    const Mat3 F = elastic_.deformation_gradient(static_cast<Index>(t), u);
    to_voigt(elastic_.law().pk2_stress(green(F)), x);
    const double* X = &driver_[6 * t];
    for (std::size_t j = 0; j < nj; ++j) {
      const double* hc = &hist_[(t * nj + j) * 6];
      for (std::size_t k = 0; k < 6; ++k)
        h[j * 6 + k] = factors_[j].a * hc[k] + factors_[j].c * (x[k] - X[k]);
    }
    psi += branch_form(t, h.data(), &rate);
  }
  return we + psi;
}

void ViscoelasticHyperelastic::internal_force(const VecX& u, VecX& f) const {
  if (elastic_only_) {
    elastic_.internal_force(u, f);
    return;
  }
  assert(u.size() == num_dofs());
  f.setZero(num_dofs());
  const auto& tets = elastic_.tets();
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const Mat3 F = elastic_.deformation_gradient(static_cast<Index>(t), u);
    HyperelasticTL::Mat34 ft;
    if (elastic_.in_domain(F))
      ft = elastic_.tet_force_from_stress(static_cast<Index>(t), F,
                                          total_stress(t, elastic_.law().pk2_stress(green(F))));
    else
      ft.setConstant(kNaN);
    for (int p = 0; p < 4; ++p) f.segment<3>(3 * static_cast<Eigen::Index>(tets[t][p])) += ft.col(p);
  }
}

void ViscoelasticHyperelastic::tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const {
  if (elastic_only_) {
    elastic_.tangent_apply(u, v, Kv);
    return;
  }
  assert(u.size() == num_dofs() && v.size() == num_dofs());
  Kv.setZero(num_dofs());
  const auto& tets = elastic_.tets();
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const Index ti = static_cast<Index>(t);
    const Mat3 F = elastic_.deformation_gradient(ti, u);
    Mat3 dP;
    if (elastic_.in_domain(F)) {
      // dP = dF S_total + F (1 + g) D : sym(F^T dF)
      const Mat3 dF = elastic_.displacement_gradient(ti, v);
      Mat3 S_e;
      Mat6 D;
      elastic_.law().evaluate(green(F), nullptr, &S_e, &D);
      const Mat3 FtdF = F.transpose() * dF;
      dP =
          dF * total_stress(t, S_e) + (1.0 + gain_) * (F * apply_tangent(D, 0.5 * (FtdF + FtdF.transpose())));
    } else {
      dP.setConstant(kNaN);
    }
    const TetRest& r = elastic_.rest(ti);
    for (int p = 0; p < 4; ++p)
      Kv.segment<3>(3 * static_cast<Eigen::Index>(tets[t][p])) += r.volume * (dP * r.grad[p]);
  }
}

void ViscoelasticHyperelastic::tangent(const VecX& u, SpMat& K) const {
  if (elastic_only_) {
    elastic_.tangent(u, K);
    return;
  }
  const TangentPattern& pattern = elastic_.pattern();
  if (!pattern.matches(K))
    pattern.reset(K);
  else
    std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
  double* values = K.valuePtr();
  const auto& tets = elastic_.tets();
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const Index ti = static_cast<Index>(t);
    const Mat3 F = elastic_.deformation_gradient(ti, u);
    HyperelasticTL::Mat12 Kt;
    if (elastic_.in_domain(F)) {
      Mat3 S_e;
      Mat6 D;
      elastic_.law().evaluate(green(F), nullptr, &S_e, &D);
      Kt = elastic_.tet_stiffness_from(ti, F, total_stress(t, S_e), (1.0 + gain_) * D);
    } else {
      Kt.setConstant(kNaN);
    }
    pattern.scatter(ti, tets[t], Kt, values);
  }
}

// ---------------------------------------------------------------- checkpoints

double ViscoelasticHyperelastic::committed_elastic_energy() const {
  if (spring_stale_) {
    committed_elastic_ = elastic_.energy(committed_u_);
    spring_stale_ = false;
  }
  return committed_elastic_;
}

std::vector<double> ViscoelasticHyperelastic::committed_state() const {
  return pack_committed_state(hist_, driver_,
                              {committed_elastic_energy(), committed_branch_, committed_rate_,
                               step_dissipation_, total_dissipation_});
}

void ViscoelasticHyperelastic::restore_committed_state(const std::vector<double>& s) {
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
