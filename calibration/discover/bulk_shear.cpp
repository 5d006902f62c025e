#include "calibration/discover/bulk_shear.hpp"

#include "core/base/error.hpp"

#include <cmath>
#include <cstddef>

namespace tmlab::discover {

namespace {

/// s1 * A + s2 * B, term by term (both on the same relaxation times).
PronyOperator combine(double s1, const PronyOperator& a, double s2, const PronyOperator& b) {
  PronyOperator o;
  o.p_inf = s1 * a.p_inf + s2 * b.p_inf;
  o.tau = a.tau;
  for (std::size_t j = 0; j < a.p.size(); ++j) o.p.push_back(s1 * a.p[j] + s2 * b.p[j]);
  return o;
}

}  // namespace

BulkShearRelaxation::BulkShearRelaxation(BulkShearRig rig, const std::vector<double>& alpha,
                                         const std::vector<double>& tau, double nu0, double nu_inf,
                                         double tau_b)
    : rig_(rig) {
  if (alpha.size() != tau.size()) throw Error("bulk-shear relaxation: alpha and tau differ in length");
  if (!(nu0 > -1.0 && nu0 < 0.5) || !(nu_inf > -1.0 && nu_inf < 0.5))
    throw Error("bulk-shear relaxation: Poisson ratios must lie in (-1, 0.5)");
  if (!(tau_b > 0.0)) throw Error("bulk-shear relaxation: the bulk relaxation time must be positive");
  // Moduli per unit Young's modulus (the rig's output is normalised, so E drops out).
  const double g0 = 1.0 / (2.0 * (1.0 + nu0)), k0 = 1.0 / (3.0 * (1.0 - 2.0 * nu0));
  const double kinf = 2.0 * g0 * (1.0 + nu_inf) / (3.0 * (1.0 - 2.0 * nu_inf));
  PronyOperator g, k;
  g.p_inf = g0;
  k.p_inf = kinf;
  for (std::size_t j = 0; j < alpha.size(); ++j) {
    g.p.push_back(g0 * alpha[j]);
    k.p.push_back(k0 * alpha[j]);
    g.tau.push_back(tau[j]);
    k.tau.push_back(tau[j]);
  }
  g.p.push_back(0.0);
  k.p.push_back(k0 - kinf);
  g.tau.push_back(tau_b);
  k.tau.push_back(tau_b);
  switch (rig) {
    case BulkShearRig::confined:
      b_ = combine(1.0, k, 4.0 / 3.0, g);
      ref_ = k0 + 4.0 / 3.0 * g0;
      break;
    case BulkShearRig::uniaxial_stress:
      a_ = combine(3.0, k, 1.0, g);
      b_ = combine(3.0, k, 0.0, g);
      c_ = combine(0.0, k, 3.0, g);
      ref_ = 9.0 * k0 * g0 / (3.0 * k0 + g0);
      break;
    case BulkShearRig::indentation:
      a_ = combine(3.0, k, 4.0, g);
      b_ = combine(3.0, k, 1.0, g);
      c_ = combine(0.0, k, 4.0, g);
      ref_ = 4.0 * g0 * (3.0 * k0 + g0) / (3.0 * k0 + 4.0 * g0);
      break;
  }
  const std::size_t n = g.tau.size();
  ha_.h.assign(n, 0.0);
  hb_.h.assign(n, 0.0);
  hc_.h.assign(n, 0.0);
  ha_t_ = ha_;
  hb_t_ = hb_;
  hc_t_ = hc_;
}

double BulkShearRelaxation::apply(const PronyOperator& op, const Hist& hist, Hist& out, double dt, double in,
                                  double in_prev) const {
  // Exact-linear step of each term (input linear over the step): h <- e h + (1 - e) tau/dt (in - in_prev).
  double v = op.p_inf * in;
  for (std::size_t j = 0; j < op.p.size(); ++j) {
    double decay = 0.0, beta = 1.0;
    if (started_) {
      const double r = dt / op.tau[j];
      decay = std::exp(-r);
      beta = r > 1e-8 ? (1.0 - decay) / r : 1.0 - 0.5 * r;
    }
    out.h[j] = decay * hist.h[j] + beta * (in - (started_ ? in_prev : 0.0));
    v += op.p[j] * out.h[j];
  }
  return v;
}

double BulkShearRelaxation::step(double dt, double y) {
  y_trial_ = y;
  started_trial_ = true;
  const double by = apply(b_, hb_, hb_t_, dt, y, y_);
  if (rig_ == BulkShearRig::confined) return by / ref_;
  // a * x = b * y at this sample, linear in x_n: a_inf x + sum a_j (e h + beta (x - x_prev)) = b * y.
  double num = by, den = a_.p_inf;
  for (std::size_t j = 0; j < a_.p.size(); ++j) {
    double decay = 0.0, beta = 1.0;
    if (started_) {
      const double r = dt / a_.tau[j];
      decay = std::exp(-r);
      beta = r > 1e-8 ? (1.0 - decay) / r : 1.0 - 0.5 * r;
    }
    num -= a_.p[j] * (decay * ha_.h[j] - beta * (started_ ? x_ : 0.0));
    den += a_.p[j] * beta;
  }
  x_trial_ = num / den;
  apply(a_, ha_, ha_t_, dt, x_trial_, x_);
  return apply(c_, hc_, hc_t_, dt, x_trial_, x_) / ref_;
}

void BulkShearRelaxation::commit() {
  ha_ = ha_t_;
  hb_ = hb_t_;
  hc_ = hc_t_;
  x_ = x_trial_;
  y_ = y_trial_;
  started_ = started_trial_;
}

}  // namespace tmlab::discover
