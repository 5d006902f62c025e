// Offset-free errors of a computed surface profile against the Hertz half-space profile
// u_z(r) = -c (2 a^2 - r^2) inside the contact r <= a (verification/checks/analytic_hertz_checks.cpp).
#pragma once

#include <vector>

namespace tmlab::verify::numerics {

/// Errors relative to delta(a) = c a^2: `rms`, the RMS over the samples of (u_h - u_exact) minus its
/// mean; `curvature`, |B - c| / c for the least-squares fit u_z = A + B r^2.
struct ProfileErrors {
  double rms = 0.0, curvature = 0.0;
};

/// The errors of the samples (r[i], uz[i]) (same length, at least two distinct radii).
ProfileErrors profile_errors(const std::vector<double>& r, const std::vector<double>& uz, double a, double c);

}  // namespace tmlab::verify::numerics
