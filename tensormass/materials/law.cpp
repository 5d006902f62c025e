#include "tensormass/materials/law.hpp"

#include "core/base/error.hpp"

#include <string>

namespace tmlab::tm {

namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace

Law Law::of(MaterialLaw kind, const LawParameters& p, const LameConstants& l) {
  switch (kind) {
    case MaterialLaw::StVK:
      if (!(l.mu > 0.0) || !(l.lambda + 2.0 * l.mu / 3.0 > 0.0))
        throw Error("St Venant-Kirchhoff material needs mu > 0 and lambda + 2 mu/3 > 0, got lambda = " +
                    std::to_string(l.lambda) + ", mu = " + std::to_string(l.mu));
      return StVenantKirchhoff{l.lambda, l.mu};
    case MaterialLaw::NeoHookean:
      return NeoHookean(l.lambda, l.mu);
    case MaterialLaw::MooneyRivlin:
      return MooneyRivlin(p.c10, p.c01, p.kappa);
    case MaterialLaw::Yeoh:
      return Yeoh(p.c10, p.c20, p.c30, p.kappa);
    case MaterialLaw::Ogden:
      return Ogden(p.mu, p.alpha, p.kappa);
    case MaterialLaw::VerondaWestmann:
      break;
  }
  return VerondaWestmann(p.c1, p.c2, p.kappa);
}

LameConstants Law::small_strain() const {
  return std::visit(Overloaded{[](const StVenantKirchhoff& m) {
                                 return LameConstants{m.lambda, m.mu};
                               },
                               [](const auto& m) { return m.small_strain(); }},
                    v_);
}

void Law::evaluate(const Mat3& E, double* W, Mat3* S, Mat6* D) const {
  std::visit(Overloaded{[&](const StVenantKirchhoff& m) {
                          if (W) *W = m.energy_density(E);
                          if (S) *S = m.pk2_stress(E);
                          if (D) *D = isotropic_tangent(m.lambda, m.mu);
                        },
                        [&](const auto& m) { m.evaluate(E, W, S, D); }},
             v_);
}

double Law::energy_density(const Mat3& E) const {
  double w = 0.0;
  evaluate(E, &w, nullptr, nullptr);
  return w;
}

Mat3 Law::pk2_stress(const Mat3& E) const {
  Mat3 s;
  evaluate(E, nullptr, &s, nullptr);
  return s;
}

Mat3 Law::tangent(const Mat3& E, const Mat3& dE) const {
  if (const auto* m = std::get_if<StVenantKirchhoff>(&v_)) return m->tangent(dE);
  return apply_tangent(tangent_matrix(E), dE);
}

Mat6 Law::tangent_matrix(const Mat3& E) const {
  Mat6 d;
  evaluate(E, nullptr, nullptr, &d);
  return d;
}

}  // namespace tmlab::tm
