// St Venant-Kirchhoff material: W(E) = lambda/2 (tr E)^2 + mu tr(E^2), as a stateless value type
// with the value / gradient / hessian triad (energy_density, pk2_stress, tangent).
//
// Lame constants from Young's modulus and Poisson's ratio (seed eqs. 4-5, with the correction of
// docs seed-errata.md, eq. 5): lambda = E nu / ((1+nu)(1-2nu)), mu = E / (2(1+nu)).
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
  Mat3 pk2_stress(const Mat3& E) const {
    return lambda * E.trace() * Mat3::Identity() + 2.0 * mu * E;
  }
  /// dS = (d^2 W / dE^2) : dE = lambda tr(dE) I + 2 mu dE (constant: St VK is linear in E).
  Mat3 tangent(const Mat3& dE) const { return pk2_stress(dE); }

  double young() const { return mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu); }
  double poisson() const { return lambda / (2.0 * (lambda + mu)); }
};

}  // namespace tmlab::tm
