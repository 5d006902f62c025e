// Veronda-Westmann material (exponential stiffening, soft tissue), decoupled, as a stateless value
// type (the form of FEBio and of Veronda & Westmann 1970 with a volumetric term):
//   W = c1 (exp(c2 (I1b - 3)) - 1) - c1 c2 / 2 (I2b - 3) + kappa/2 (ln J)^2
// S and D from isochoric_invariants.hpp with Psi_1 = c1 c2 e^{c2 x}, Psi_11 = c1 c2^2 e^{c2 x}
// (x = I1b - 3), Psi_2 = -c1 c2 / 2. Small-strain shear modulus mu = 2 (Psi_1 + Psi_2) = c1 c2,
// bulk modulus kappa. Theory and limits: docs/theory/hyperelastic-laws.md.
#pragma once

#include "tensormass/materials/tensor_algebra.hpp"

namespace tmlab::tm {

class VerondaWestmann {
 public:
  /// Throws tmlab::Error naming the parameter unless c1 > 0, c2 > 0 and kappa > 0.
  VerondaWestmann(double c1, double c2, double kappa);

  double c1() const { return c1_; }        ///< Pa
  double c2() const { return c2_; }        ///< dimensionless, exponential stiffening rate
  double kappa() const { return kappa_; }  ///< Pa, bulk modulus
  /// Lame constants of the small-strain limit: mu = c1 c2, lambda = kappa - 2 mu/3.
  LameConstants small_strain() const;

  double energy_density(const Mat3& E) const;
  Mat3 pk2_stress(const Mat3& E) const;
  Mat3 tangent(const Mat3& E, const Mat3& dE) const;
  Mat6 tangent_matrix(const Mat3& E) const;
  /// W, S and D at E in one pass (any pointer may be null).
  void evaluate(const Mat3& E, double* W, Mat3* S, Mat6* D) const;

 private:
  double c1_ = 0.0;
  double c2_ = 0.0;
  double kappa_ = 0.0;
};

}  // namespace tmlab::tm
