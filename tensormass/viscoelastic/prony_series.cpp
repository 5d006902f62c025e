// Prony series (seed eqs. 9-10 and 24, corrected in docs/theory/seed-errata.md); see prony_series.hpp.
#include "tensormass/viscoelastic/prony_series.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/config/config_reader.hpp"
#include "core/constitutive/prony.hpp"

#include <cmath>

namespace tmlab::tm {

namespace {

/// Checks tau and the weights; `weight_name` is "alpha" or "g" for messages.
void validate(const std::vector<double>& w, const std::vector<double>& tau, const char* weight_name) {
  if (w.empty()) throw Error("Prony series: at least one term is required (got an empty series)");
  if (w.size() != tau.size()) {
    throw Error("Prony series: " + std::to_string(w.size()) + " weights but " + std::to_string(tau.size()) +
                " relaxation times");
  }
  for (std::size_t j = 0; j < w.size(); ++j) {
    const std::string term = "Prony series term " + std::to_string(j) + ": ";
    if (!std::isfinite(w[j]))
      throw Error(term + weight_name + " = " + significant(w[j], 17) + " is not finite");
    if (w[j] < 0.0) throw Error(term + weight_name + " = " + significant(w[j], 17) + " must be >= 0");
    if (!std::isfinite(tau[j])) throw Error(term + "tau = " + significant(tau[j], 17) + " is not finite");
    if (tau[j] <= 0.0) throw Error(term + "tau = " + significant(tau[j], 17) + " must be > 0 (seconds)");
  }
}

}  // namespace

PronySeries::PronySeries(std::vector<double> alpha, std::vector<double> tau)
    : alpha_(std::move(alpha)), tau_(std::move(tau)) {}

PronySeries PronySeries::from_long_term(std::vector<double> alpha, std::vector<double> tau) {
  validate(alpha, tau, "alpha");
  return PronySeries(std::move(alpha), std::move(tau));
}

PronySeries PronySeries::from_instantaneous(const std::vector<double>& g, std::vector<double> tau) {
  validate(g, tau, "g");
  double sum = 0.0;
  for (double v : g) sum += v;
  if (!(sum < 1.0)) {
    throw Error("Prony series: instantaneous weights sum to " + significant(sum, 17) +
                ", must be < 1 (the long-term modulus E_0 (1 - sum g) must stay positive)");
  }
  return from_long_term(long_term_weights(g), std::move(tau));  // alpha_j = g_j / (1 - sum g)
}

PronySeries PronySeries::from_json(const nlohmann::json& j, const std::string& where,
                                   const std::string& path) {
  ConfigReader r(j, where, path);
  const std::string name = r.require<std::string>("convention");
  const std::optional<PronyConvention> convention = prony_convention_from_string(name);
  if (!convention)
    throw r.error("convention",
                  "must be " + choice_list(prony_convention_names(), "\"") + " (got \"" + name + "\")");
  const nlohmann::json& terms = r.raw("terms");
  if (!terms.is_array() || terms.empty())
    throw r.error("terms", "must be a non-empty array of {\"weight\": w, \"tau\": t}");
  std::vector<double> w, tau;
  for (std::size_t k = 0; k < terms.size(); ++k) {
    ConfigReader t(terms[k], where, r.key_path("terms") + "[" + std::to_string(k) + "]");
    const double wk = t.require<double>("weight");
    if (!std::isfinite(wk) || wk < 0.0)
      throw t.error("weight", "must be >= 0 (got " + significant(wk, 17) + ")");
    w.push_back(wk);
    tau.push_back(t.positive("tau"));
    t.finish();
  }
  r.finish();
  try {
    return *convention == PronyConvention::LongTerm ? from_long_term(std::move(w), std::move(tau))
                                                    : from_instantaneous(w, std::move(tau));
  } catch (const Error& e) {
    throw Error(where + ": key '" + r.key_path("terms") + "': " + e.what());
  }
}

double PronySeries::alpha_sum() const {
  double s = 0.0;
  for (double a : alpha_) s += a;
  return s;
}

bool PronySeries::is_elastic() const {
  for (double a : alpha_)
    if (a != 0.0) return false;
  return true;
}

std::vector<double> PronySeries::instantaneous_weights() const {
  return tmlab::instantaneous_weights(alpha_);
}

double PronySeries::relaxation(double t) const {
  double r = 1.0;  // r(t) = 1 + sum_j alpha_j exp(-t/tau_j)   (eq. 10)
  for (std::size_t j = 0; j < alpha_.size(); ++j) r += alpha_[j] * std::exp(-t / tau_[j]);
  return r;
}

double PronySeries::long_term_modulus(double instantaneous_modulus) const {
  return instantaneous_modulus / (1.0 + alpha_sum());
}

double PronySeries::instantaneous_modulus(double long_term_modulus) const {
  return long_term_modulus * (1.0 + alpha_sum());
}

nlohmann::json PronySeries::to_json() const {
  nlohmann::json terms = nlohmann::json::array();
  for (std::size_t j = 0; j < alpha_.size(); ++j) terms.push_back({{"weight", alpha_[j]}, {"tau", tau_[j]}});
  return {{"convention", "long_term"}, {"terms", terms}};
}

}  // namespace tmlab::tm
