// Mooney-Rivlin material, decoupled (isochoric/volumetric) form, as a stateless value type:
//   W = c10 (I1b - 3) + c01 (I2b - 3) + kappa/2 (ln J)^2
// with the isochoric invariants I1b = J^{-2/3} I1, I2b = J^{-4/3} I2 of C = I + 2E; S and D from
// isochoric_invariants.hpp (Psi_1 = c10, Psi_2 = c01, no second derivatives). Small-strain shear
// modulus mu = 2 (c10 + c01), bulk modulus kappa. c01 = 0 is the decoupled neo-Hookean law.
// Theory and limits: docs/theory/hyperelastic-laws.md.
#pragma once

#include "tensormass/materials/tensor_algebra.hpp"

namespace tmlab::tm {

class MooneyRivlin {
 public:
  /// Throws tmlab::Error naming the parameter unless c10 + c01 > 0 (positive shear modulus),
  /// kappa > 0 and both coefficients are finite (one of them may be negative).
  MooneyRivlin(double c10, double c01, double kappa);

  double c10() const { return c10_; }      ///< Pa, coefficient of I1b - 3
  double c01() const { return c01_; }      ///< Pa, coefficient of I2b - 3
  double kappa() const { return kappa_; }  ///< Pa, bulk modulus
  /// Lame constants of the small-strain limit: mu = 2 (c10 + c01), lambda = kappa - 2 mu/3.
  LameConstants small_strain() const;

  double energy_density(const Mat3& E) const;
  Mat3 pk2_stress(const Mat3& E) const;
  Mat3 tangent(const Mat3& E, const Mat3& dE) const;
  Mat6 tangent_matrix(const Mat3& E) const;
  /// W, S and D at E in one pass (any pointer may be null).
  void evaluate(const Mat3& E, double* W, Mat3* S, Mat6* D) const;

 private:
  double c10_ = 0.0;
  double c01_ = 0.0;
  double kappa_ = 0.0;
};

}  // namespace tmlab::tm
