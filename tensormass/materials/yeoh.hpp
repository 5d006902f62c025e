// Yeoh material (strain-stiffening), decoupled, the deal.II reference's form
// (reference_fem/dealii/materials.hpp, YeohLaw), as a stateless value type:
//   W = c10 x + c20 x^2 + c30 x^3 + kappa/2 (ln J)^2,   x = I1b - 3,  I1b = J^{-2/3} tr C
// S and D from isochoric_invariants.hpp with Psi_1 = c10 + 2 c20 x + 3 c30 x^2, Psi_11 = 2 c20 + 6 c30 x.
// Small-strain shear modulus mu = 2 c10, bulk modulus kappa. Theory: docs/theory/hyperelastic-laws.md.
#pragma once

#include "tensormass/materials/tensor_algebra.hpp"

namespace tmlab::tm {

class Yeoh {
 public:
  /// Throws tmlab::Error naming the parameter unless c10 > 0, kappa > 0 and c20, c30 are finite
  /// (c20 < 0, common in fits, can make the law lose convexity at large strain).
  Yeoh(double c10, double c20, double c30, double kappa);

  double c10() const { return c10_; }      ///< Pa
  double c20() const { return c20_; }      ///< Pa
  double c30() const { return c30_; }      ///< Pa
  double kappa() const { return kappa_; }  ///< Pa, bulk modulus
  /// Lame constants of the small-strain limit: mu = 2 c10, lambda = kappa - 2 mu/3.
  LameConstants small_strain() const;

  double energy_density(const Mat3& E) const;
  Mat3 pk2_stress(const Mat3& E) const;
  Mat3 tangent(const Mat3& E, const Mat3& dE) const;
  Mat6 tangent_matrix(const Mat3& E) const;
  /// W, S and D at E in one pass (any pointer may be null).
  void evaluate(const Mat3& E, double* W, Mat3* S, Mat6* D) const;

 private:
  double c10_ = 0.0;
  double c20_ = 0.0;
  double c30_ = 0.0;
  double kappa_ = 0.0;
};

}  // namespace tmlab::tm
