#include "tensormass/materials/law.hpp"

namespace tmlab::tm {

namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

}  // namespace

std::string Law::name() const {
  return std::visit(Overloaded{[](const StVenantKirchhoff&) { return std::string("stvk"); },
                               [](const NeoHookean&) { return std::string("neo_hookean"); },
                               [](const MooneyRivlin&) { return std::string("mooney_rivlin"); },
                               [](const Yeoh&) { return std::string("yeoh"); },
                               [](const Ogden&) { return std::string("ogden"); },
                               [](const VerondaWestmann&) { return std::string("veronda_westmann"); }},
                    v_);
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
