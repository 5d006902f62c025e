#include "tensormass/materials/mooney_rivlin.hpp"

#include "tensormass/materials/isochoric_invariants.hpp"

#include <cmath>

namespace tmlab::tm {

MooneyRivlin::MooneyRivlin(double c10, double c01, double kappa) : c10_(c10), c01_(c01), kappa_(kappa) {
  require_finite("Mooney-Rivlin material", "c10", c10);
  require_finite("Mooney-Rivlin material", "c01", c01);
  require_positive("Mooney-Rivlin material", "c10 + c01", "the shear modulus 2 (c10 + c01)", c10 + c01);
  require_positive("Mooney-Rivlin material", "kappa", "bulk modulus", kappa);
}

LameConstants MooneyRivlin::small_strain() const {
  const double mu = 2.0 * (c10_ + c01_);
  return {kappa_ - 2.0 * mu / 3.0, mu};
}

void MooneyRivlin::evaluate(const Mat3& E, double* W, Mat3* S, Mat6* D) const {
  const IsochoricInvariants k(E);
  IsochoricPotential p;
  p.psi = c10_ * (k.i1b - 3.0) + c01_ * (k.i2b - 3.0);
  p.d1 = c10_;
  p.d2 = c01_;
  evaluate_decoupled(k, p, kappa_, W, S, D);
}

double MooneyRivlin::energy_density(const Mat3& E) const {
  double w = 0.0;
  evaluate(E, &w, nullptr, nullptr);
  return w;
}
Mat3 MooneyRivlin::pk2_stress(const Mat3& E) const {
  Mat3 s;
  evaluate(E, nullptr, &s, nullptr);
  return s;
}
Mat6 MooneyRivlin::tangent_matrix(const Mat3& E) const {
  Mat6 d;
  evaluate(E, nullptr, nullptr, &d);
  return d;
}
Mat3 MooneyRivlin::tangent(const Mat3& E, const Mat3& dE) const {
  return apply_tangent(tangent_matrix(E), dE);
}

}  // namespace tmlab::tm
