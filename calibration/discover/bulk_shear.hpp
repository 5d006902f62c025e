// Separate bulk and shear relaxation (the `separate_bulk_shear_relaxation` effect of discover;
// docs/discover.md section 3): the rig's relaxation function when the shear and the bulk modulus
// relax differently, by the correspondence principle of linear viscoelasticity.
//
// The baseline (the paper's tensor-mass Prony model) relaxes the whole stress with one normalised
// function g(t) = 1 + sum_j alpha_j exp(-t/tau_j): G(t) = G0 g(t), K(t) = K0 g(t), the Poisson ratio
// nu0 constant, and every rig's force relaxes with g. The effect lets the bulk modulus relax further,
// to the drained Poisson ratio nu_inf < nu0 with its own time tau_b:
//   G(t) = G0 g(t),   K(t) = K0 g(t) - (K0 - K_inf) (1 - exp(-t/tau_b)),
//   K_inf = 2 G0 (1 + nu_inf) / (3 (1 - 2 nu_inf)),
// G0, K0 from the law's small-strain (E, nu0). The rig's modulus is an operator in G and K
// (Carson transforms; Lee and Radok for indentation while the contact grows):
//   confined          M  = K + 4/3 G
//   unconfined/tension E = 9 K G / (3 K + G):  (3K + G) * x = 3K * y,   E * y = 3 G * x
//   sphere, punch     E* = 4 G (3K + G) / (3K + 4G): (3K + 4G) * x = (3K + G) * y,   E* * y = 4 G * x
// (`*` the hereditary integral), normalised by the rig's modulus at (G0, K0), so that with
// nu_inf = nu0 the operator is exactly g * y: the baseline's, step by step. The input y is the
// long-term elastic force X_e(d) of the rig, as in the baseline; each Prony operator is stepped with
// the exact-linear update (input linear between samples), the Volterra equations for x solved at
// each sample in closed form (they are linear in x_n).
//
// In unconfined compression the lateral strain follows x: its relaxation is the apparent Poisson
// ratio rising or falling in a hold, which a plain Prony term cannot produce. On force data of one
// rig the operator is one more exponential of the rig modulus (e.g. unconfined, g = 1: a term at
// tau' = tau_b (3 K0 + G0) / (3 K_inf + G0)): the two effects are confounded there (docs).
#pragma once

#include <vector>

namespace tmlab::discover {

/// A Prony relaxation function P(t) = p_inf + sum_j p_j exp(-t/tau_j) as an operator on a
/// piecewise-linear input, with its history variables.
struct PronyOperator {
  double p_inf = 0.0;
  std::vector<double> p, tau;
};

enum class BulkShearRig { confined, uniaxial_stress, indentation };

/// The rig relaxation operator with separate bulk and shear relaxation, stepped sample by sample.
/// step() computes the output for a trial input without changing the state; commit() keeps it.
class BulkShearRelaxation {
 public:
  /// alpha, tau: the common Prony terms (weights relative to the long-term modulus); nu0 the law's
  /// Poisson ratio, nu_inf the drained one, tau_b the bulk relaxation time.
  BulkShearRelaxation(BulkShearRig rig, const std::vector<double>& alpha, const std::vector<double>& tau,
                      double nu0, double nu_inf, double tau_b);
  /// Output (normalised rig force) at a new sample with input y after a step dt (dt = 0 at the
  /// first sample: the input jumps from zero).
  double step(double dt, double y);
  /// Keeps the state of the last step().
  void commit();
  /// The auxiliary field x of the last step (uniaxial stress: proportional to the axial stress
  /// carried by the volumetric-deviatoric split; used by the tests).
  double last_x() const { return x_trial_; }

 private:
  struct Hist {
    std::vector<double> h;  ///< one history variable per term
  };
  double apply(const PronyOperator& op, const Hist& hist, Hist& out, double decay_dt, double in,
               double in_prev) const;
  BulkShearRig rig_;
  PronyOperator a_, b_, c_;  ///< rig: a * x = b * y, out = c * x / ref (confined: out = b * y / ref)
  double ref_ = 1.0;
  Hist ha_, hb_, hc_, ha_t_, hb_t_, hc_t_;
  double x_ = 0.0, y_ = 0.0, x_trial_ = 0.0, y_trial_ = 0.0;
  bool started_ = false, started_trial_ = false;
};

}  // namespace tmlab::discover
