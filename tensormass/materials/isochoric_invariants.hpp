// Kinematics shared by the invariant-based hyperelastic laws (Mooney-Rivlin, Yeoh, Veronda-Westmann):
// the right Cauchy-Green tensor C = I + 2E, its isochoric invariants and their first and second
// derivatives with respect to C, and the decoupled law
//
//   W(C) = Psi(I1b, I2b) + kappa/2 (ln J)^2,   I1b = J^{-2/3} I1,  I2b = J^{-4/3} I2,  J = sqrt(det C)
//
// with I1 = tr C, I2 = ((tr C)^2 - tr(C^2))/2. Derivatives (Ci = C^{-1}, (x) and (.) as in
// tensor_algebra.hpp):
//   G1 = dI1b/dC = J^{-2/3} (I - I1/3 Ci)
//   G2 = dI2b/dC = J^{-4/3} (I1 I - C - 2/3 I2 Ci)
//   dG1/dC = J^{-2/3} [ -1/3 (I (x) Ci + Ci (x) I) + I1/9 Ci (x) Ci + I1/3 Ci (.) Ci ]
//   dG2/dC = J^{-4/3} [ I (x) I - I (.) I - 2/3 ((I1 I - C) (x) Ci + Ci (x) (I1 I - C))
//                       + 4/9 I2 Ci (x) Ci + 2/3 I2 Ci (.) Ci ]
// and, since S = 2 dW/dC and D = dS/dE = 4 d^2W/dC^2,
//   S = 2 (Psi_1 G1 + Psi_2 G2) + kappa ln J Ci
//   D = 4 [ Psi_11 G1 (x) G1 + Psi_12 (G1 (x) G2 + G2 (x) G1) + Psi_22 G2 (x) G2
//           + Psi_1 dG1/dC + Psi_2 dG2/dC ] + kappa Ci (x) Ci - 2 kappa ln J Ci (.) Ci.
// The volumetric term and the J^{-2/3} scaling are those of the deal.II reference's Yeoh law
// (reference_fem/dealii/materials.hpp), so that the two agree to round-off.
#pragma once

#include "tensormass/materials/tensor_algebra.hpp"

namespace tmlab::tm {

/// C, its inverse, J and the isochoric invariants of a Green-Lagrange strain E. Valid for det C > 0
/// (callers check J > 0 on F; the laws return NaN otherwise).
struct IsochoricInvariants {
  Mat3 C, Ci;
  double det_c = 1.0, ln_j = 0.0, i1 = 3.0, i2 = 3.0;
  double jm23 = 1.0;  ///< J^{-2/3} = det(C)^{-1/3}
  double i1b = 3.0, i2b = 3.0;

  explicit IsochoricInvariants(const Mat3& E);
  Mat3 dI1b() const;   ///< G1
  Mat3 dI2b() const;   ///< G2
  Mat6 d2I1b() const;  ///< dG1/dC
  Mat6 d2I2b() const;  ///< dG2/dC
};

/// Psi(I1b, I2b) and its first and second partial derivatives at one point.
struct IsochoricPotential {
  double psi = 0.0, d1 = 0.0, d2 = 0.0, d11 = 0.0, d12 = 0.0, d22 = 0.0;
};

/// W, S and D (any may be null) of the decoupled law Psi + kappa/2 (ln J)^2 at the invariants k.
void evaluate_decoupled(const IsochoricInvariants& k, const IsochoricPotential& p, double kappa, double* W,
                        Mat3* S, Mat6* D);

/// Throws tmlab::Error "<law>: <what> must be finite and > 0, got <name> = <value>" unless value > 0.
void require_positive(const char* law, const char* name, const char* what, double value);
/// Throws tmlab::Error naming the parameter unless value is finite.
void require_finite(const char* law, const char* name, double value);

}  // namespace tmlab::tm
