// Closed-form indentation of a linear elastic or linear viscoelastic half-space by a rigid axisymmetric
// indenter: the analytic references of the contact verification cases and the fast surrogate forward
// models of the fit (docs/contact.md, docs/identification.md).
//
// Elastic (Young's modulus E, Poisson's ratio nu, depth d >= 0, frictionless contact):
//   sphere of radius R (Hertz, valid for d << R):   F = 4/3 E/(1-nu^2) sqrt(R) d^{3/2},  a = sqrt(R d)
//   flat cylindrical punch of radius a (Sneddon):    F = 2 a E d / (1-nu^2)
// Finite layer of thickness h under a sphere (Dimitriadis et al. 2002, Biophys. J. 82:2798, eq. 11-12):
//   F = F_Hertz (1 + c1 chi + c2 chi^2 + c3 chi^3 + c4 chi^4),  chi = sqrt(R d) / h
// Viscoelastic (Lee and Radok 1960), relaxation modulus E(t) = E_inf + sum_i E_i exp(-t/tau_i) at a
// constant nu, valid while the contact radius does not decrease (d(t) non-decreasing):
//   sphere: F(t) = 4 sqrt(R) / (3 (1-nu^2)) int_0^t E(t-s) d/ds[d(s)^{3/2}] ds
//   punch:  F(t) = 2 a / (1-nu^2)           int_0^t E(t-s) d/ds[d(s)] ds
#pragma once

#include <vector>

namespace tmlab::closed_forms {

/// Hertz force of a rigid sphere (radius R, m) pressed d (m) into an elastic half-space, N.
/// d <= 0 gives 0 (no contact). Throws tmlab::Error for E <= 0, nu outside (-1, 0.5], R <= 0.
double hertz_force(double young, double poisson, double radius, double depth);
/// Hertz contact radius a = sqrt(R d), m (0 for d <= 0).
double hertz_contact_radius(double radius, double depth);
/// Sneddon force of a rigid flat cylindrical punch (radius a, m) pressed d (m), N (0 for d <= 0).
double sneddon_force(double young, double poisson, double punch_radius, double depth);

/// How the layer of a finite-thickness correction is held on its support.
enum class LayerSupport { Bonded, Frictionless };
/// The factor F / F_Hertz of Dimitriadis et al. (2002) for a sphere on a layer of thickness h,
/// chi = sqrt(R d) / h. Their series is fitted for chi <= 1; beyond that it throws tmlab::Error.
double finite_layer_factor(double poisson, double radius, double depth, double thickness,
                           LayerSupport support);

/// A relaxation modulus E(t) = E_inf + sum_i E_i exp(-t / tau_i) (Pa, s).
struct RelaxationModulus {
  double e_inf = 0.0;
  std::vector<double> moduli;  ///< E_i
  std::vector<double> taus;    ///< tau_i > 0
  double at(double t) const;   ///< E(t), t >= 0
  double instantaneous() const { return at(0.0); }
  /// Throws tmlab::Error unless E_inf > 0, E_i >= 0, tau_i > 0 and the sizes agree.
  void validate() const;
};

/// A displacement history d(t), linear between samples (times strictly increasing, d(t0) = 0 at
/// or before contact). Lee-Radok needs d non-decreasing; a decreasing segment throws tmlab::Error
/// naming the sample (unloading needs Ting's solution, which is not implemented).
struct DepthHistory {
  std::vector<double> t, d;
};

/// Lee-Radok force of a sphere at every sample time of `history`, N. Exact for a depth linear
/// between samples: within a segment d^{3/2} is integrated against each exponential in closed form
/// through Dawson's integral (see indentation.cpp), so no time-step error enters.
std::vector<double> lee_radok_sphere(const RelaxationModulus& modulus, double poisson, double radius,
                                     const DepthHistory& history);
/// The flat-punch analogue (force linear in d: the convolution is exact for piecewise-linear d).
std::vector<double> lee_radok_punch(const RelaxationModulus& modulus, double poisson, double punch_radius,
                                    const DepthHistory& history);

/// A ramp to depth d_max over t_ramp, then a hold, sampled at the given times (the standard
/// relaxation indentation test).
DepthHistory ramp_hold(double d_max, double t_ramp, const std::vector<double>& times);

}  // namespace tmlab::closed_forms
