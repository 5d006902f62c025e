// Admissible parameters of every law, from the law catalogue alone (core/constitutive/
// law_catalogue.hpp): what a fit starts from (law_parameters) with a data modulus E = 3 kPa
// (G0 = 1 kPa), two terms for an N-term law, defaults where the catalogue has them, kappa = 10 kPa.
// For the catalogue's consistency tests (its users link tmlab::constitutive themselves).
#pragma once

#include "core/constitutive/law_catalogue.hpp"

#include <cmath>
#include <cstddef>
#include <vector>

namespace tmlab::testing {

inline double sample_value(const LawParameterInfo& info, std::size_t term, std::size_t terms) {
  constexpr double kE = 3000.0, kG0 = 1000.0;
  const auto exponent = [](std::size_t k) { return k % 2 == 0 ? 2.0 + 2.0 * double(k) : -2.0 * double(k); };
  if (info.has_default) return info.default_value;
  switch (info.fit.start) {
    case FitStart::Decade:
      return info.fit.scale * (info.fit.of_young ? kE : kG0);
    case FitStart::Spread:
      return info.fit.scale * kG0;
    case FitStart::Absolute:
      return info.fit.scale;
    case FitStart::TermExponent:
      return exponent(term);
    case FitStart::TermModulus:
      return 2.0 * kG0 / (double(terms) * exponent(term));
  }
  return 0.0;
}

inline LawParameters sample_parameters(MaterialLaw law, std::size_t terms = 2) {
  LawParameters p;
  for (const LawParameterInfo& info : law_descriptor(law).parameters) {
    if (info.list) {
      std::vector<double>& v = p.*info.values;
      for (std::size_t k = 0; k < terms; ++k) v.push_back(sample_value(info, k, terms));
    } else {
      p.*info.scalar = sample_value(info, 0, 1);
    }
  }
  p.kappa = 1e4;
  return p;
}

}  // namespace tmlab::testing
