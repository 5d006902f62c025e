#include "tensormass/materials/yeoh.hpp"

#include "tensormass/materials/isochoric_invariants.hpp"

#include <cmath>

namespace tmlab::tm {

Yeoh::Yeoh(double c10, double c20, double c30, double kappa)
    : c10_(c10), c20_(c20), c30_(c30), kappa_(kappa) {
  require_positive("Yeoh material", "c10", "c10 (half the shear modulus)", c10);
  require_finite("Yeoh material", "c20", c20);
  require_finite("Yeoh material", "c30", c30);
  require_positive("Yeoh material", "kappa", "bulk modulus", kappa);
}

LameConstants Yeoh::small_strain() const {
  const double mu = 2.0 * c10_;
  return {kappa_ - 2.0 * mu / 3.0, mu};
}

void Yeoh::evaluate(const Mat3& E, double* W, Mat3* S, Mat6* D) const {
  const IsochoricInvariants k(E);
  IsochoricPotential p;
  const double x = k.i1b - 3.0;  // as the reference: det(C)^{-1/3} tr C - 3
  p.psi = c10_ * x + c20_ * x * x + c30_ * x * x * x;
  p.d1 = c10_ + 2.0 * c20_ * x + 3.0 * c30_ * x * x;
  p.d11 = 2.0 * c20_ + 6.0 * c30_ * x;
  evaluate_decoupled(k, p, kappa_, W, S, D);
}

double Yeoh::energy_density(const Mat3& E) const {
  double w = 0.0;
  evaluate(E, &w, nullptr, nullptr);
  return w;
}
Mat3 Yeoh::pk2_stress(const Mat3& E) const {
  Mat3 s;
  evaluate(E, nullptr, &s, nullptr);
  return s;
}
Mat6 Yeoh::tangent_matrix(const Mat3& E) const {
  Mat6 d;
  evaluate(E, nullptr, nullptr, &d);
  return d;
}
Mat3 Yeoh::tangent(const Mat3& E, const Mat3& dE) const { return apply_tangent(tangent_matrix(E), dE); }

}  // namespace tmlab::tm
