// The Prony-series vocabulary shared by every model (docs/theory/viscoelasticity.md): the names of
// the choices a case file makes, the recursion that advances a Prony branch over a step, and the
// conversion between the two weight conventions. The tensor-mass model (tensormass/viscoelastic)
// and the deal.II reference (reference_fem/dealii/materials.hpp) both use this one copy, so they
// cannot drift apart; the case file (core/config) parses its strings into these enums once.
//
// Relaxation function, long-term convention (seed eq. 10, errata eqs. 9-10):
//   r(t) = E(t) / E_inf = 1 + sum_j alpha_j exp(-t / tau_j),  alpha_j >= 0, tau_j > 0.
// Instantaneous convention (Nava et al. 2008, seed eq. 24): E(t) = E_0 (1 - sum_k g_k (1 - exp(-t/tau_k))),
// sum g < 1. The same function with (errata row "10 vs 24")
//   alpha_j = g_j / (1 - sum_k g_k),   g_j = alpha_j / (1 + sum_k alpha_k).
//
// Branch recursion over a step dt (eq. 20 family): h_j^{n+1} = a_j h_j^n + c_j (X_e^{n+1} - X_e^n) with
//   midpoint:       a = exp(-dt/tau), c = exp(-dt/(2 tau))   (the seed's eq. 20)
//   exact_linear:   a = exp(-dt/tau), c = (tau/dt)(1 - a)    (exact for X_e linear in t)
//   backward_euler: a = c = 1/(1 + dt/tau)                   (first order)
#pragma once

#include <cassert>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace tmlab {

/// How the case file's Prony weights are normalised: long_term (alpha_j, eq. 10) or
/// instantaneous (g_j, eq. 24).
enum class PronyConvention { LongTerm, Instantaneous };
/// What the history acts on: nodal_force (the seed's 12 nodal forces per tet, eq. 20; not
/// objective) or pk2 (the second Piola-Kirchhoff stress, objective).
enum class PronyHistory { NodalForce, Pk2 };
/// The recursion of a branch over a step: midpoint | exact_linear | backward_euler.
enum class PronyIntegration { Midpoint, ExactLinear, BackwardEuler };
/// What relaxes (pk2 only): the full stress, or only its deviatoric part (the bulk stress never relaxes).
enum class PronyRelaxation { Full, Deviatoric };
/// The case file's shorthands for a history + integration pair.
/// xu2011 is the recursion of Xu et al. 2011 (the paper the project implements).
enum class PronyScheme { Xu2011, Xu2011ExactLinear, BackwardEuler, Objective };

std::string to_string(PronyConvention c);
std::string to_string(PronyHistory h);
std::string to_string(PronyIntegration i);
std::string to_string(PronyRelaxation r);
std::string to_string(PronyScheme s);

/// The choice a name denotes, or nothing (exact, case-sensitive names as written by to_string;
/// prony_scheme_from_string also reads the former names seed and seed_exact_linear).
std::optional<PronyConvention> prony_convention_from_string(const std::string& name);
std::optional<PronyHistory> prony_history_from_string(const std::string& name);
std::optional<PronyIntegration> prony_integration_from_string(const std::string& name);
std::optional<PronyRelaxation> prony_relaxation_from_string(const std::string& name);
std::optional<PronyScheme> prony_scheme_from_string(const std::string& name);

/// Every name of a choice, in declaration order (for messages that list the accepted values).
std::vector<std::string> prony_convention_names();
std::vector<std::string> prony_history_names();
std::vector<std::string> prony_integration_names();
std::vector<std::string> prony_relaxation_names();
std::vector<std::string> prony_scheme_names();

/// The history and integration a shorthand stands for: xu2011 = nodal_force + midpoint,
/// xu2011_exact_linear = nodal_force + exact_linear, backward_euler = nodal_force + backward_euler,
/// objective = pk2 + exact_linear.
struct PronySchemeParts {
  PronyHistory history;
  PronyIntegration integration;
};
PronySchemeParts scheme_parts(PronyScheme s);

/// Recursion factors of one Prony term for a step dt >= 0 (dt = 0 gives a = c = 1).
struct RecursionFactors {
  double a = 1.0;  ///< decay of the old history
  double c = 1.0;  ///< weight of the increment of the driver X_e
};
/// Inline: it runs once per term and step inside the models' step loops (and inlined there, the
/// compiled step code is the one the models had before this function was shared).
inline RecursionFactors recursion_factors(PronyIntegration scheme, double dt, double tau) {
  assert(dt >= 0.0 && tau > 0.0);
  const double x = dt / tau;
  RecursionFactors f;
  switch (scheme) {
    case PronyIntegration::Midpoint:  // seed eq. 20: a = e^{-dt/tau}, c = e^{-dt/(2 tau)}
      f.a = std::exp(-x);
      f.c = std::exp(-0.5 * x);
      break;
    case PronyIntegration::ExactLinear:  // errata eq. 20: c = (tau/dt)(1 - e^{-dt/tau}) -> 1 as dt -> 0
      // expm1 keeps c accurate for small dt/tau, where 1 - e^{-x} would cancel.
      f.a = std::exp(-x);
      f.c = (x == 0.0) ? 1.0 : -std::expm1(-x) / x;
      break;
    case PronyIntegration::BackwardEuler:  // (h^{n+1} - h^n)/dt = -h^{n+1}/tau + (X^{n+1} - X^n)/dt
      f.a = 1.0 / (1.0 + x);
      f.c = f.a;
      break;
  }
  return f;
}

/// alpha_j = g_j / (1 - sum_k g_k): the long-term weights of instantaneous weights g (the caller
/// checks sum g < 1 and g_j >= 0).
std::vector<double> long_term_weights(const std::vector<double>& g);
/// g_j = alpha_j / (1 + sum_k alpha_k): the instantaneous weights of long-term weights alpha.
std::vector<double> instantaneous_weights(const std::vector<double>& alpha);
/// The long-term weights of `weights` given in `convention` (unchanged for long_term).
std::vector<double> long_term_weights(PronyConvention convention, const std::vector<double>& weights);

}  // namespace tmlab
