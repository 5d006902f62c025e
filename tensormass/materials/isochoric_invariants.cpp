#include "tensormass/materials/isochoric_invariants.hpp"

#include "core/base/error.hpp"

#include <Eigen/LU>

#include <cmath>
#include <sstream>

namespace tmlab::tm {

IsochoricInvariants::IsochoricInvariants(const Mat3& E) {
  C = Mat3::Identity() + 2.0 * E;
  det_c = C.determinant();
  Ci = C.inverse();
  ln_j = 0.5 * std::log(det_c);
  i1 = C.trace();
  i2 = 0.5 * (i1 * i1 - C.cwiseProduct(C).sum());  // tr(C^2) = C : C for symmetric C
  jm23 = std::pow(det_c, -1.0 / 3.0);
  i1b = jm23 * i1;
  i2b = jm23 * jm23 * i2;
}

Mat3 IsochoricInvariants::dI1b() const { return jm23 * (Mat3::Identity() - (i1 / 3.0) * Ci); }

Mat3 IsochoricInvariants::dI2b() const {
  return (jm23 * jm23) * (i1 * Mat3::Identity() - C - (2.0 / 3.0) * i2 * Ci);
}

Mat6 IsochoricInvariants::d2I1b() const {
  const Mat3 I = Mat3::Identity();
  return jm23 * (-1.0 / 3.0 * sym_outer(I, Ci) + (i1 / 9.0) * outer(Ci, Ci) + (i1 / 3.0) * box(Ci, Ci));
}

Mat6 IsochoricInvariants::d2I2b() const {
  const Mat3 I = Mat3::Identity();
  const Mat3 A = i1 * I - C;  // dI2/dC
  return (jm23 * jm23) * (outer(I, I) - box(I, I) - (2.0 / 3.0) * sym_outer(A, Ci) +
                          (4.0 / 9.0) * i2 * outer(Ci, Ci) + (2.0 / 3.0) * i2 * box(Ci, Ci));
}

void evaluate_decoupled(const IsochoricInvariants& k, const IsochoricPotential& p, double kappa, double* W,
                        Mat3* S, Mat6* D) {
  if (W) *W = p.psi + 0.5 * kappa * k.ln_j * k.ln_j;
  if (!S && !D) return;
  const Mat3 G1 = k.dI1b();
  const bool has2 = p.d2 != 0.0 || p.d12 != 0.0 || p.d22 != 0.0;  // Yeoh: skip the I2b terms
  const Mat3 G2 = has2 ? k.dI2b() : Mat3::Zero();
  if (S) *S = 2.0 * (p.d1 * G1 + p.d2 * G2) + (kappa * k.ln_j) * k.Ci;
  if (D) {
    Mat6 d = 4.0 * (p.d11 * outer(G1, G1) + p.d1 * k.d2I1b());
    if (has2) d += 4.0 * (p.d12 * sym_outer(G1, G2) + p.d22 * outer(G2, G2) + p.d2 * k.d2I2b());
    d += kappa * outer(k.Ci, k.Ci) - (2.0 * kappa * k.ln_j) * box(k.Ci, k.Ci);
    *D = d;
  }
}

void require_positive(const char* law, const char* name, const char* what, double value) {
  if (value > 0.0 && std::isfinite(value)) return;
  std::ostringstream os;
  os << law << ": " << what << " must be finite and > 0, got " << name << " = " << value;
  throw Error(os.str());
}

void require_finite(const char* law, const char* name, double value) {
  if (std::isfinite(value)) return;
  std::ostringstream os;
  os << law << ": parameter " << name << " must be finite, got " << value;
  throw Error(os.str());
}

}  // namespace tmlab::tm
