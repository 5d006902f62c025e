#include "tensormass/materials/neo_hookean.hpp"

#include "tensormass/materials/isochoric_invariants.hpp"

#include <Eigen/LU>

#include <cmath>

namespace tmlab::tm {

NeoHookean::NeoHookean(double lambda, double mu) : lambda_(lambda), mu_(mu) {
  require_positive("neo-Hookean material", "mu", "shear modulus", mu);
  require_finite("neo-Hookean material", "lambda", lambda);
  require_positive("neo-Hookean material", "lambda + 2 mu/3", "bulk modulus", lambda + 2.0 * mu / 3.0);
}

NeoHookean NeoHookean::from_young_poisson(double young, double poisson) {
  const auto m = StVenantKirchhoff::from_young_poisson(young, poisson);  // checks E and nu
  return {m.lambda, m.mu};
}

void NeoHookean::evaluate(const Mat3& E, double* W, Mat3* S, Mat6* D) const {
  const Mat3 C = Mat3::Identity() + 2.0 * E;
  const double lnJ = 0.5 * std::log(C.determinant());
  if (W) *W = 0.5 * mu_ * (C.trace() - 3.0) - mu_ * lnJ + 0.5 * lambda_ * lnJ * lnJ;
  if (!S && !D) return;
  const Mat3 Ci = C.inverse();
  if (S) *S = mu_ * (Mat3::Identity() - Ci) + (lambda_ * lnJ) * Ci;
  if (D) *D = lambda_ * outer(Ci, Ci) + (2.0 * (mu_ - lambda_ * lnJ)) * box(Ci, Ci);
}

double NeoHookean::energy_density(const Mat3& E) const {
  double w = 0.0;
  evaluate(E, &w, nullptr, nullptr);
  return w;
}
Mat3 NeoHookean::pk2_stress(const Mat3& E) const {
  Mat3 s;
  evaluate(E, nullptr, &s, nullptr);
  return s;
}
Mat6 NeoHookean::tangent_matrix(const Mat3& E) const {
  Mat6 d;
  evaluate(E, nullptr, nullptr, &d);
  return d;
}
Mat3 NeoHookean::tangent(const Mat3& E, const Mat3& dE) const { return apply_tangent(tangent_matrix(E), dE); }

}  // namespace tmlab::tm
