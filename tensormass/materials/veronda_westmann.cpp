#include "tensormass/materials/veronda_westmann.hpp"

#include "tensormass/materials/isochoric_invariants.hpp"

#include <cmath>

namespace tmlab::tm {

VerondaWestmann::VerondaWestmann(double c1, double c2, double kappa) : c1_(c1), c2_(c2), kappa_(kappa) {
  require_positive("Veronda-Westmann material", "c1", "c1", c1);
  require_positive("Veronda-Westmann material", "c2", "c2", c2);
  require_positive("Veronda-Westmann material", "kappa", "bulk modulus", kappa);
}

LameConstants VerondaWestmann::small_strain() const {
  const double mu = c1_ * c2_;
  return {kappa_ - 2.0 * mu / 3.0, mu};
}

void VerondaWestmann::evaluate(const Mat3& E, double* W, Mat3* S, Mat6* D) const {
  const IsochoricInvariants k(E);
  IsochoricPotential p;
  const double x = k.i1b - 3.0, e = std::exp(c2_ * x);
  p.psi = c1_ * std::expm1(c2_ * x) - 0.5 * c1_ * c2_ * (k.i2b - 3.0);
  p.d1 = c1_ * c2_ * e;
  p.d11 = c1_ * c2_ * c2_ * e;
  p.d2 = -0.5 * c1_ * c2_;
  evaluate_decoupled(k, p, kappa_, W, S, D);
}

double VerondaWestmann::energy_density(const Mat3& E) const {
  double w = 0.0;
  evaluate(E, &w, nullptr, nullptr);
  return w;
}
Mat3 VerondaWestmann::pk2_stress(const Mat3& E) const {
  Mat3 s;
  evaluate(E, nullptr, &s, nullptr);
  return s;
}
Mat6 VerondaWestmann::tangent_matrix(const Mat3& E) const {
  Mat6 d;
  evaluate(E, nullptr, nullptr, &d);
  return d;
}
Mat3 VerondaWestmann::tangent(const Mat3& E, const Mat3& dE) const {
  return apply_tangent(tangent_matrix(E), dE);
}

}  // namespace tmlab::tm
