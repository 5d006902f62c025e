// The Prony-series vocabulary, recursion factors and weight conversion; see prony.hpp.
#include "core/constitutive/prony.hpp"

#include "core/base/enum_names.hpp"

namespace tmlab {

namespace {

// Each choice's names in declaration order: the one table both to_string and *_from_string read
// (core/base/enum_names.hpp).
const char* const kConventions[] = {"long_term", "instantaneous"};
const char* const kHistories[] = {"nodal_force", "pk2"};
const char* const kIntegrations[] = {"midpoint", "exact_linear", "backward_euler"};
const char* const kRelaxations[] = {"full", "deviatoric"};
const char* const kSchemes[] = {"xu2011", "xu2011_exact_linear", "backward_euler", "objective"};

double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

}  // namespace

std::string to_string(PronyConvention c) { return enum_name(kConventions, c); }
std::string to_string(PronyHistory h) { return enum_name(kHistories, h); }
std::string to_string(PronyIntegration i) { return enum_name(kIntegrations, i); }
std::string to_string(PronyRelaxation r) { return enum_name(kRelaxations, r); }
std::string to_string(PronyScheme s) { return enum_name(kSchemes, s); }

std::optional<PronyConvention> prony_convention_from_string(const std::string& name) {
  return enum_from_name<PronyConvention>(kConventions, name);
}
std::optional<PronyHistory> prony_history_from_string(const std::string& name) {
  return enum_from_name<PronyHistory>(kHistories, name);
}
std::optional<PronyIntegration> prony_integration_from_string(const std::string& name) {
  return enum_from_name<PronyIntegration>(kIntegrations, name);
}
std::optional<PronyRelaxation> prony_relaxation_from_string(const std::string& name) {
  return enum_from_name<PronyRelaxation>(kRelaxations, name);
}
std::optional<PronyScheme> prony_scheme_from_string(const std::string& name) {
  // The scheme's former names, still read so that older case files keep working.
  if (name == "seed") return PronyScheme::Xu2011;
  if (name == "seed_exact_linear") return PronyScheme::Xu2011ExactLinear;
  return enum_from_name<PronyScheme>(kSchemes, name);
}

std::vector<std::string> prony_convention_names() { return enum_names(kConventions); }
std::vector<std::string> prony_history_names() { return enum_names(kHistories); }
std::vector<std::string> prony_integration_names() { return enum_names(kIntegrations); }
std::vector<std::string> prony_relaxation_names() { return enum_names(kRelaxations); }
std::vector<std::string> prony_scheme_names() { return enum_names(kSchemes); }

PronySchemeParts scheme_parts(PronyScheme s) {
  switch (s) {
    case PronyScheme::Xu2011:
      return {PronyHistory::NodalForce, PronyIntegration::Midpoint};
    case PronyScheme::Xu2011ExactLinear:
      return {PronyHistory::NodalForce, PronyIntegration::ExactLinear};
    case PronyScheme::BackwardEuler:
      return {PronyHistory::NodalForce, PronyIntegration::BackwardEuler};
    case PronyScheme::Objective:
      break;
  }
  return {PronyHistory::Pk2, PronyIntegration::ExactLinear};
}

std::vector<double> long_term_weights(const std::vector<double>& g) {
  // alpha_j = g_j / (1 - sum_k g_k)   (errata, eq. 10 vs 24)
  const double s = sum(g);
  std::vector<double> alpha(g.size());
  for (std::size_t j = 0; j < g.size(); ++j) alpha[j] = g[j] / (1.0 - s);
  return alpha;
}

std::vector<double> instantaneous_weights(const std::vector<double>& alpha) {
  // g_j = alpha_j / (1 + sum alpha)
  const double s = 1.0 + sum(alpha);
  std::vector<double> g(alpha.size());
  for (std::size_t j = 0; j < g.size(); ++j) g[j] = alpha[j] / s;
  return g;
}

std::vector<double> long_term_weights(PronyConvention convention, const std::vector<double>& weights) {
  return convention == PronyConvention::Instantaneous ? long_term_weights(weights) : weights;
}

}  // namespace tmlab
