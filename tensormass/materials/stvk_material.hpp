// St Venant-Kirchhoff material: W(E) = lambda/2 (tr E)^2 + mu tr(E^2), as a stateless value type
// with the value / gradient / hessian triad (energy_density, pk2_stress, tangent).
//
// Lame constants from Young's modulus and Poisson's ratio (seed eqs. 4-5, with the correction of
// docs/theory/seed-errata.md, eq. 5): lambda = E nu / ((1+nu)(1-2nu)), mu = E / (2(1+nu)).
// The printed mu = E nu / (2(1+nu)) is wrong; tests/test_printed_errors.cpp keeps the check.
#pragma once

#include <Eigen/Core>

namespace tmlab::tm {

using Mat3 = Eigen::Matrix3d;

struct StVenantKirchhoff {
  double lambda = 0.0;  ///< first Lame constant, Pa
  double mu = 0.0;      ///< shear modulus, Pa

  /// Lame constants from Young's modulus E (Pa) and Poisson's ratio nu. Throws tmlab::Error naming
  /// the parameter unless E > 0 and -1 < nu < 0.5.
  static StVenantKirchhoff from_young_poisson(double young, double poisson);

  /// W(E) = lambda/2 (tr E)^2 + mu E:E, J/m^3 (E symmetric Green-Lagrange strain).
  double energy_density(const Mat3& E) const {
    const double tr = E.trace();
    return 0.5 * lambda * tr * tr + mu * E.cwiseProduct(E).sum();
  }
  /// S = dW/dE = lambda tr(E) I + 2 mu E (second Piola-Kirchhoff stress).
  Mat3 pk2_stress(const Mat3& E) const { return lambda * E.trace() * Mat3::Identity() + 2.0 * mu * E; }
  /// dS = (d^2 W / dE^2) : dE = lambda tr(dE) I + 2 mu dE (constant: St VK is linear in E).
  Mat3 tangent(const Mat3& dE) const { return pk2_stress(dE); }

  double young() const { return mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu); }
  double poisson() const { return lambda / (2.0 * (lambda + mu)); }
};

/// Symmetric 3x3 tensors stored as 6 values in Voigt order (xx, yy, zz, xy, xz, yz): the layout
/// of the viscoelastic stress histories.
inline void to_voigt(const Mat3& A, double* v) {
  v[0] = A(0, 0);
  v[1] = A(1, 1);
  v[2] = A(2, 2);
  v[3] = A(0, 1);
  v[4] = A(0, 2);
  v[5] = A(1, 2);
}
inline Mat3 from_voigt(const double* v) {
  Mat3 A;
  A << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
  return A;
}

}  // namespace tmlab::tm
