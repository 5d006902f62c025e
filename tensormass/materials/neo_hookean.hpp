// Compressible neo-Hookean material, the deal.II reference's form (reference_fem/dealii/materials.hpp,
// NeoHookeanLaw), as a stateless value type:
//   W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,   I1 = tr C, C = I + 2E, J = sqrt(det C)
//   S = mu (I - C^{-1}) + lambda ln J C^{-1}
//   D = dS/dE = lambda C^{-1} (x) C^{-1} + 2 (mu - lambda ln J) C^{-1} (.) C^{-1}
// It linearises to the Lame constants (lambda, mu) of St Venant-Kirchhoff; unlike St VK its energy
// grows without bound as J -> 0 (the -mu ln J + lambda/2 (ln J)^2 terms), so it does not soften in
// compression. Theory and limits: docs/theory/hyperelastic-laws.md.
#pragma once

#include "tensormass/materials/tensor_algebra.hpp"

namespace tmlab::tm {

class NeoHookean {
 public:
  /// Throws tmlab::Error naming the parameter unless mu > 0 and the bulk modulus lambda + 2 mu/3 > 0.
  NeoHookean(double lambda, double mu);
  /// From Young's modulus E > 0 and -1 < nu < 0.5 (Lame constants as St VK's).
  static NeoHookean from_young_poisson(double young, double poisson);

  double lambda() const { return lambda_; }
  double mu() const { return mu_; }
  LameConstants small_strain() const { return {lambda_, mu_}; }

  double energy_density(const Mat3& E) const;
  Mat3 pk2_stress(const Mat3& E) const;
  Mat3 tangent(const Mat3& E, const Mat3& dE) const;
  Mat6 tangent_matrix(const Mat3& E) const;
  /// W, S and D at E in one pass (any pointer may be null).
  void evaluate(const Mat3& E, double* W, Mat3* S, Mat6* D) const;

 private:
  double lambda_ = 0.0, mu_ = 0.0;
};

}  // namespace tmlab::tm
