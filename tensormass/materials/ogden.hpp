// Ogden material with N terms, decoupled, as a stateless value type:
//   W = sum_p mu_p / alpha_p (lb_1^alpha_p + lb_2^alpha_p + lb_3^alpha_p - 3) + kappa/2 (ln J)^2
// with the isochoric principal stretches lb_i = J^{-1/3} lambda_i, lambda_i^2 = c_i the eigenvalues
// of C = I + 2E. Small-strain shear modulus mu = 1/2 sum_p mu_p alpha_p, bulk modulus kappa.
//
// As a symmetric function W = Phi(c_1, c_2, c_3) of the eigenvalues (eigenvectors n_i, N_i = n_i (x) n_i):
//   S  = 2 sum_i Phi_i N_i
//   dS = 4 [ sum_ij Phi_ij (N_j : dE) N_i + sum_{i<j} Theta_ij (n_i . dE n_j) (n_i (x) n_j + n_j (x) n_i) ],
//   Theta_ij = (Phi_i - Phi_j) / (c_i - c_j)
// with, for A_p = J^{-alpha_p/3}, s_p = sum_k c_k^{beta_p}, beta_p = alpha_p/2,
//   Phi_i = sum_p mu_p A_p [ c_i^{beta-1}/2 - s_p/(6 c_i) ] + kappa ln J / (2 c_i)
//   Theta_ij = sum_p mu_p A_p [ DD_{beta-1}(c_i, c_j)/2 + s_p/(6 c_i c_j) ] - kappa ln J / (2 c_i c_j)
// where DD_k(a, b) = (a^k - b^k)/(a - b) is evaluated in a form that is accurate to round-off for
// all a, b > 0, including a = b (limit k a^{k-1}): so equal (or nearly equal) eigenvalues need no
// special case and no perturbation, and the eigenvectors of a repeated eigenvalue may be any
// orthonormal basis of its eigenspace (the formula is continuous there).
// Theory and limits: docs/theory/hyperelastic-laws.md.
#pragma once

#include "tensormass/materials/tensor_algebra.hpp"

#include <vector>

namespace tmlab::tm {

class Ogden {
 public:
  /// Throws tmlab::Error naming the parameter unless: 1 <= N terms, mu and alpha of equal length,
  /// every mu_p and alpha_p finite, every alpha_p != 0, the stability condition
  /// sum_p mu_p alpha_p > 0 (positive shear modulus) and kappa > 0.
  Ogden(std::vector<double> mu, std::vector<double> alpha, double kappa);

  const std::vector<double>& mu() const { return mu_; }        ///< mu_p, Pa
  const std::vector<double>& alpha() const { return alpha_; }  ///< alpha_p, dimensionless
  double kappa() const { return kappa_; }                      ///< bulk modulus, Pa
  std::size_t num_terms() const { return mu_.size(); }
  /// mu = 1/2 sum_p mu_p alpha_p, lambda = kappa - 2 mu/3.
  LameConstants small_strain() const;

  double energy_density(const Mat3& E) const;
  Mat3 pk2_stress(const Mat3& E) const;
  Mat3 tangent(const Mat3& E, const Mat3& dE) const;
  Mat6 tangent_matrix(const Mat3& E) const;
  /// W, S and D at E in one pass (any pointer may be null); one eigen-decomposition of C.
  void evaluate(const Mat3& E, double* W, Mat3* S, Mat6* D) const;

  /// DD_k(a, b) = (a^k - b^k)/(a - b) for a, b > 0, accurate to round-off, k a^{k-1} at a = b.
  static double power_divided_difference(double k, double a, double b);

 private:
  std::vector<double> mu_, alpha_;
  double kappa_ = 0.0;
};

}  // namespace tmlab::tm
