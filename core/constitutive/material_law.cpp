#include "core/constitutive/material_law.hpp"

#include "core/base/format.hpp"

#include <cmath>

namespace tmlab {

SmallStrainModuli small_strain_moduli(MaterialLaw law, const LawParameters& p) {
  SmallStrainModuli m;
  switch (law) {
    case MaterialLaw::StVK:
    case MaterialLaw::NeoHookean:
      m.shear = p.young / (2.0 * (1.0 + p.poisson));
      m.bulk = p.young / (3.0 * (1.0 - 2.0 * p.poisson));
      return m;
    case MaterialLaw::MooneyRivlin:
      m.shear = 2.0 * (p.c10 + p.c01);
      break;
    case MaterialLaw::Yeoh:
      m.shear = 2.0 * p.c10;
      break;
    case MaterialLaw::Ogden:
      for (std::size_t k = 0; k < p.mu.size() && k < p.alpha.size(); ++k)
        m.shear += 0.5 * p.mu[k] * p.alpha[k];
      break;
    case MaterialLaw::VerondaWestmann:
      m.shear = p.c1 * p.c2;
      break;
  }
  m.bulk = p.kappa;
  return m;
}

LawParameterProblem law_parameter_problem(MaterialLaw law, const LawParameters& p) {
  auto finite = [](double x) { return std::isfinite(x); };
  if (law_takes_young_poisson(law)) {
    if (!(p.young > 0.0) || !finite(p.young))
      return {"E", "must be > 0 (got " + significant(p.young, 6) + ")"};
    if (!(p.poisson > -1.0 && p.poisson < 0.5))
      return {"nu", "must satisfy -1 < nu < 0.5 (got " + significant(p.poisson, 6) + ")"};
    return {};
  }
  if (!(p.kappa > 0.0) || !finite(p.kappa))
    return {"kappa", "must be > 0 (got " + significant(p.kappa, 6) + ")"};
  switch (law) {
    case MaterialLaw::MooneyRivlin:
      if (!finite(p.c10)) return {"c10", "must be finite"};
      if (!finite(p.c01)) return {"c01", "must be finite"};
      if (!(p.c10 + p.c01 > 0.0))
        return {"c01", "c10 + c01 must be > 0 (the small-strain shear modulus is 2 (c10 + c01); got c10 = " +
                           significant(p.c10, 6) + ", c01 = " + significant(p.c01, 6) + ")"};
      break;
    case MaterialLaw::Yeoh:
      if (!(p.c10 > 0.0) || !finite(p.c10)) return {"c10", "must be > 0 (got " + significant(p.c10, 6) + ")"};
      if (!finite(p.c20)) return {"c20", "must be finite"};
      if (!finite(p.c30)) return {"c30", "must be finite"};
      break;
    case MaterialLaw::Ogden: {
      if (p.mu.empty()) return {"mu", "must be a non-empty list (one mu_p per term)"};
      if (p.alpha.size() != p.mu.size())
        return {"alpha", "must have as many terms as mu (" + std::to_string(p.mu.size()) + ", got " +
                             std::to_string(p.alpha.size()) + ")"};
      double sum = 0.0;
      for (std::size_t k = 0; k < p.mu.size(); ++k) {
        if (!finite(p.mu[k])) return {"mu", "term " + std::to_string(k + 1) + " must be finite"};
        if (!finite(p.alpha[k]) || p.alpha[k] == 0.0)
          return {"alpha", "term " + std::to_string(k + 1) + " must be finite and non-zero (got " +
                               significant(p.alpha[k], 6) + ")"};
        sum += p.mu[k] * p.alpha[k];
      }
      if (!(sum > 0.0))
        return {"mu",
                "violates the Ogden stability condition sum_p mu_p alpha_p > 0 (positive shear modulus "
                "1/2 sum_p mu_p alpha_p; got sum = " +
                    significant(sum, 6) + ")"};
      break;
    }
    case MaterialLaw::VerondaWestmann:
      if (!(p.c1 > 0.0) || !finite(p.c1)) return {"c1", "must be > 0 (got " + significant(p.c1, 6) + ")"};
      if (!(p.c2 > 0.0) || !finite(p.c2)) return {"c2", "must be > 0 (got " + significant(p.c2, 6) + ")"};
      break;
    default:
      break;
  }
  return {};
}

}  // namespace tmlab
