// The Euler elastica of a cantilever under a dead transverse tip load P (load parameter
// k = P L^2 / (E I)): the exact large-rotation solution of inextensible Euler-Bernoulli beam theory.
//
// With theta(s) the rotation of the axis at arc length s (clamp s = 0, theta(0) = 0), moment
// balance gives E I theta'' + P cos(theta) = 0 and theta'(L) = 0 (no tip moment), so
//   E I / 2 theta'^2 = P (sin theta0 - sin theta),   theta0 = theta(L), the tip rotation,
// and the length condition L = int ds fixes theta0:
//   sqrt(k) = alpha(theta0) = int_0^theta0 dtheta / sqrt(2 (sin theta0 - sin theta)).
// The tip position follows from dx = cos(theta) ds (along the undeformed axis) and dy = sin(theta) ds:
//   x_tip / L = sqrt(2 sin theta0) / alpha,   y_tip / L = (1 / alpha) int_0^theta0 sin(theta) dtheta /
//   sqrt(2 (sin theta0 - sin theta)).
// The integrable end singularity is removed by sin(theta0) - sin(theta) = v^2 (dtheta = 2 v dv /
// cos theta); the integrals are then smooth on v in [0, sqrt(sin theta0)] and are evaluated by
// composite 5-point Gauss-Legendre; theta0 by bisection (alpha is increasing in theta0).
#pragma once

namespace tmlab::verify {

struct ElasticaTip {
  double theta0 = 0.0;      ///< tip rotation, radians
  double transverse = 0.0;  ///< tip deflection along the load, / L
  double axial = 0.0;       ///< tip position along the undeformed axis, / L (1 - axial: the shortening)
};

/// The tip of the elastica for load parameter k = P L^2 / (E I), 0 < k <= 1000 (the tip rotation
/// tends to 90 degrees as k grows). Throws tmlab::Error outside that range.
ElasticaTip elastica_cantilever_tip(double load_parameter);

}  // namespace tmlab::verify
