// PronySeries: the normalised relaxation function of a quasi-linear viscoelastic material,
//
//   r(t) = E(t) / E_inf = 1 + sum_j alpha_j exp(-t / tau_j)
//   (seed eq. 10, corrected in docs/theory/seed-errata.md, eqs. 9-10)
//
// alpha_j >= 0 are the LONG-TERM normalised weights (alpha_j = E_j / E_inf) and tau_j > 0 the
// relaxation times in seconds. The instantaneous modulus is E_0 = E(0) = E_inf (1 + sum alpha).
//
// The other convention in the literature (Nava et al. 2008, seed eq. 24) normalises by the
// INSTANTANEOUS modulus: E(t) = E_0 (1 - sum_k g_k (1 - exp(-t/tau_k))), 0 <= g_k, sum g < 1.
// The two are the same function with (errata row "10 vs 24")
//
//   alpha_j = g_j / (1 - sum_k g_k),   E_inf = E_0 (1 - sum_k g_k),
//   g_j = alpha_j / (1 + sum_k alpha_k),   E_0 = E_inf (1 + sum_k alpha_k).
//
// Value type, validated on construction (always on, tmlab::Error names the term and the value).
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tmlab::tm {

class PronySeries {
 public:
  /// Long-term normalised weights alpha_j (eq. 10) and times tau_j. Throws tmlab::Error (naming the
  /// term) when the series is empty, the sizes differ, a weight is negative or non-finite, or a
  /// time is <= 0 or non-finite. Zero weights are allowed (an elastic material).
  static PronySeries from_long_term(std::vector<double> alpha, std::vector<double> tau);
  /// Instantaneous normalised weights g_j (eq. 24, Nava) and times tau_j; converted with
  /// alpha_j = g_j / (1 - sum g). Throws as from_long_term, and when sum g >= 1.
  static PronySeries from_instantaneous(const std::vector<double>& g, std::vector<double> tau);
  /// {"convention": "long_term" | "instantaneous", "terms": [{"weight": w, "tau": t}, ...]};
  /// unknown keys are rejected. `where` names the file, `path` the key path of `j` in it.
  static PronySeries from_json(const nlohmann::json& j, const std::string& where,
                               const std::string& path = "");

  std::size_t size() const { return alpha_.size(); }
  const std::vector<double>& alpha() const { return alpha_; }  ///< long-term normalised weights
  const std::vector<double>& tau() const { return tau_; }      ///< relaxation times, s
  double alpha(std::size_t j) const { return alpha_[j]; }
  double tau(std::size_t j) const { return tau_[j]; }
  /// sum_j alpha_j.
  double alpha_sum() const;
  /// True when every weight is exactly zero (the material is elastic).
  bool is_elastic() const;

  /// g_j = alpha_j / (1 + sum alpha) (eq. 24 convention).
  std::vector<double> instantaneous_weights() const;
  /// r(t) = E(t)/E_inf = 1 + sum_j alpha_j exp(-t/tau_j), t >= 0.
  double relaxation(double t) const;
  /// E_inf = E_0 / (1 + sum alpha) = E_0 (1 - sum g) from the instantaneous modulus E_0.
  double long_term_modulus(double instantaneous_modulus) const;
  /// E_0 = E_inf (1 + sum alpha) from the long-term modulus.
  double instantaneous_modulus(double long_term_modulus) const;

  /// {"convention": "long_term", "terms": [...]} (reads back with from_json).
  nlohmann::json to_json() const;

 private:
  PronySeries(std::vector<double> alpha, std::vector<double> tau);
  std::vector<double> alpha_;
  std::vector<double> tau_;
};

}  // namespace tmlab::tm
