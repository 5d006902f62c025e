// Closed-form elastic and Lee-Radok viscoelastic indentation (indentation.hpp has the equations).
#include "calibration/closed_forms/indentation.hpp"

#include "core/base/error.hpp"

#include <gsl/gsl_sf_dawson.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace tmlab::closed_forms {

namespace {

constexpr double kPi = 3.14159265358979323846;

void check_elastic(double young, double poisson) {
  if (!(young > 0.0) || !std::isfinite(young)) throw Error("indentation: Young's modulus must be positive");
  if (!(poisson > -1.0 && poisson <= 0.5)) throw Error("indentation: Poisson's ratio must be in (-1, 0.5]");
}

void check_length(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw Error(std::string("indentation: the ") + what + " must be positive");
}

// G(x) = exp(-x) int_0^x exp(u) sqrt(u) du = sqrt(x) - D(sqrt(x)), D Dawson's integral
// D(y) = exp(-y^2) int_0^y exp(s^2) ds. Integrating by parts, int_0^x e^u u^{1/2} du =
// e^x x^{1/2} - int_0^x e^u u^{-1/2}/2 du, and the last integral is e^x D(sqrt x) (u = s^2).
double g_sqrt(double x) {
  if (x <= 0.0) return 0.0;
  const double y = std::sqrt(x);
  return y - gsl_sf_dawson(y);
}

void check_history(const DepthHistory& h) {
  if (h.t.size() != h.d.size() || h.t.empty()) {
    throw Error("indentation: the depth history needs as many depths as times, and at least one");
  }
  for (std::size_t k = 0; k < h.t.size(); ++k) {
    if (!std::isfinite(h.t[k]) || !std::isfinite(h.d[k])) {
      throw Error("indentation: sample " + std::to_string(k) + " of the depth history is not finite");
    }
    if (k > 0 && !(h.t[k] > h.t[k - 1])) {
      throw Error("indentation: the times of the depth history must increase strictly (sample " +
                  std::to_string(k) + ")");
    }
  }
}

}  // namespace

double hertz_force(double young, double poisson, double radius, double depth) {
  check_elastic(young, poisson);
  check_length(radius, "sphere radius");
  if (depth <= 0.0) return 0.0;
  return 4.0 / 3.0 * young / (1.0 - poisson * poisson) * std::sqrt(radius) * depth * std::sqrt(depth);
}

double hertz_contact_radius(double radius, double depth) {
  check_length(radius, "sphere radius");
  return depth <= 0.0 ? 0.0 : std::sqrt(radius * depth);
}

double sneddon_force(double young, double poisson, double punch_radius, double depth) {
  check_elastic(young, poisson);
  check_length(punch_radius, "punch radius");
  if (depth <= 0.0) return 0.0;
  return 2.0 * punch_radius * young * depth / (1.0 - poisson * poisson);
}

double finite_layer_factor(double poisson, double radius, double depth, double thickness,
                           LayerSupport support) {
  if (!(poisson > -1.0 && poisson <= 0.5)) throw Error("indentation: Poisson's ratio must be in (-1, 0.5]");
  check_length(radius, "sphere radius");
  check_length(thickness, "layer thickness");
  if (depth <= 0.0) return 1.0;
  const double chi = std::sqrt(radius * depth) / thickness;
  if (chi > 1.0) {
    throw Error("indentation: the finite-layer correction is fitted for sqrt(R d)/h <= 1; got " +
                std::to_string(chi));
  }
  const double nu = poisson;
  // Dimitriadis et al. (2002), eq. 12: the layer's alpha_0 and beta_0 for each support.
  const double alpha = support == LayerSupport::Bonded
                           ? -(1.2876 - 1.4678 * nu + 1.3442 * nu * nu) / (1.0 - nu)
                           : -0.347 * (3.0 - 2.0 * nu) / (1.0 - nu);
  const double beta = support == LayerSupport::Bonded ? (0.6387 - 1.0277 * nu + 1.5164 * nu * nu) / (1.0 - nu)
                                                      : 0.056 * (5.0 - 2.0 * nu) / (1.0 - nu);
  const double pi2 = kPi * kPi;
  const double c1 = -2.0 * alpha / kPi;
  const double c2 = 4.0 * alpha * alpha / pi2;
  const double c3 = -8.0 / (pi2 * kPi) * (alpha * alpha * alpha + 4.0 * pi2 * beta / 15.0);
  const double c4 = 16.0 * alpha / (pi2 * pi2) * (alpha * alpha * alpha + 3.0 * pi2 * beta / 5.0);
  return 1.0 + chi * (c1 + chi * (c2 + chi * (c3 + chi * c4)));
}

double RelaxationModulus::at(double t) const {
  double e = e_inf;
  for (std::size_t i = 0; i < moduli.size(); ++i) e += moduli[i] * std::exp(-t / taus[i]);
  return e;
}

void RelaxationModulus::validate() const {
  if (!(e_inf > 0.0) || !std::isfinite(e_inf)) throw Error("relaxation modulus: E_inf must be positive");
  if (moduli.size() != taus.size()) throw Error("relaxation modulus: one tau per Prony modulus");
  for (std::size_t i = 0; i < moduli.size(); ++i) {
    if (!(moduli[i] >= 0.0) || !std::isfinite(moduli[i])) {
      throw Error("relaxation modulus: E_" + std::to_string(i + 1) + " must be >= 0");
    }
    if (!(taus[i] > 0.0) || !std::isfinite(taus[i])) {
      throw Error("relaxation modulus: tau_" + std::to_string(i + 1) + " must be positive");
    }
  }
}

std::vector<double> lee_radok_sphere(const RelaxationModulus& modulus, double poisson, double radius,
                                     const DepthHistory& history) {
  modulus.validate();
  check_elastic(modulus.e_inf, poisson);
  check_length(radius, "sphere radius");
  check_history(history);
  const double k = 4.0 * std::sqrt(radius) / (3.0 * (1.0 - poisson * poisson));
  const std::size_t n_terms = modulus.moduli.size();
  // q_i(t) = int_0^t exp(-(t-s)/tau_i) d/ds[d^{3/2}] ds, advanced segment by segment exactly.
  std::vector<double> q(n_terms, 0.0), force(history.t.size());
  const auto h = [](double d) { return d > 0.0 ? d * std::sqrt(d) : 0.0; };
  for (std::size_t s = 0; s < history.t.size(); ++s) {
    if (s > 0) {
      const double dt = history.t[s] - history.t[s - 1];
      const double da = history.d[s - 1], db = history.d[s];
      if (db < da && da > 0.0) {
        throw Error(
            "indentation: Lee-Radok needs a non-decreasing depth while in contact; it decreases at sample " +
            std::to_string(s) + " (unloading needs Ting's solution)");
      }
      const double v = (db - da) / dt;
      for (std::size_t i = 0; i < n_terms; ++i) {
        const double tau = modulus.taus[i];
        double increment = 0.0;
        if (v > 0.0 && db > 0.0) {
          // With w = d/v, d/ds d^{3/2} = 1.5 v^{3/2} sqrt(w) and the segment's integral is
          // 1.5 (v tau)^{3/2} [G(x_b) - exp(-(x_b - x_a)) G(x_a)], x = w / tau.
          const double xa = std::max(da, 0.0) / (v * tau), xb = db / (v * tau);
          increment = 1.5 * std::pow(v * tau, 1.5) * (g_sqrt(xb) - std::exp(-(xb - xa)) * g_sqrt(xa));
        }
        q[i] = std::exp(-dt / tau) * q[i] + increment;
      }
    }
    double f = modulus.e_inf * h(history.d[s]);
    for (std::size_t i = 0; i < n_terms; ++i) f += modulus.moduli[i] * q[i];
    force[s] = k * f;
  }
  return force;
}

std::vector<double> lee_radok_punch(const RelaxationModulus& modulus, double poisson, double punch_radius,
                                    const DepthHistory& history) {
  modulus.validate();
  check_elastic(modulus.e_inf, poisson);
  check_length(punch_radius, "punch radius");
  check_history(history);
  const double k = 2.0 * punch_radius / (1.0 - poisson * poisson);
  const std::size_t n_terms = modulus.moduli.size();
  std::vector<double> q(n_terms, 0.0), force(history.t.size());
  for (std::size_t s = 0; s < history.t.size(); ++s) {
    if (s > 0) {
      const double dt = history.t[s] - history.t[s - 1];
      const double da = std::max(history.d[s - 1], 0.0), db = std::max(history.d[s], 0.0);
      if (db < da) {
        throw Error("indentation: the punch solution needs a non-decreasing depth; it decreases at sample " +
                    std::to_string(s));
      }
      // The contact part of the segment starts where d crosses zero; d is linear there, so the
      // integral of exp(-(t_b - s)/tau) v ds over it is exact.
      const double v = (history.d[s] - history.d[s - 1]) / dt;
      const double contact_time = v > 0.0 ? (db - da) / v : 0.0;
      for (std::size_t i = 0; i < n_terms; ++i) {
        const double tau = modulus.taus[i];
        q[i] = std::exp(-dt / tau) * q[i] + v * tau * -std::expm1(-contact_time / tau);
      }
    }
    double f = modulus.e_inf * std::max(history.d[s], 0.0);
    for (std::size_t i = 0; i < n_terms; ++i) f += modulus.moduli[i] * q[i];
    force[s] = k * f;
  }
  return force;
}

DepthHistory ramp_hold(double d_max, double t_ramp, const std::vector<double>& times) {
  if (!(t_ramp > 0.0)) throw Error("indentation: the ramp time must be positive");
  DepthHistory h;
  h.t = times;
  if (std::find(h.t.begin(), h.t.end(), t_ramp) == h.t.end()) {
    h.t.push_back(t_ramp);
    std::sort(h.t.begin(), h.t.end());
  }
  h.d.reserve(h.t.size());
  for (const double t : h.t) h.d.push_back(d_max * std::clamp(t / t_ramp, 0.0, 1.0));
  return h;
}

}  // namespace tmlab::closed_forms
