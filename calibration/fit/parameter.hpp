// Fit parameters in physical units with bounds, fixed or free, and the transform that maps each
// free parameter to an unbounded internal coordinate so that every trial the optimiser makes
// respects the bounds (docs/identification.md):
//   (0, inf)        x = exp(t)                         "log"
//   (lo, inf)       x = lo + exp(t)                    "log" (shifted)
//   (-inf, hi)      x = hi - exp(t)                    "log" (reflected)
//   (lo, hi)        x = lo + (hi - lo) / (1 + exp(-t)) "logit"
//   (-inf, inf)     x = t                              "identity"
// Standard errors come back to physical units by the delta method, dx = (dx/dt) dt.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace tmlab::fit {

enum class Transform { Identity, Log, Logit };

struct Parameter {
  std::string name;    ///< e.g. "young", "poisson", "c10", "mu1", "tau2"
  std::string unit;    ///< "Pa", "1", "s"
  double value = 0.0;  ///< the starting value (or the value when fixed), physical units
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool fixed = false;
  /// The range the global stage samples starting points from (physical units, inside the bounds).
  double start_low = 0.0, start_high = 0.0;

  Transform transform() const;
  /// Physical -> internal. The value must lie strictly inside the bounds.
  double to_internal(double x) const;
  /// Internal -> physical (always strictly inside the bounds, up to round-off at the limits).
  double to_physical(double t) const;
  /// dx/dt at internal t.
  double derivative(double t) const;
};

std::string to_string(Transform t);

/// Throws tmlab::Error naming the parameter unless every name is unique, lower < upper, and
/// value, start_low and start_high lie strictly inside (lower, upper) with start_low <= start_high.
void validate(const std::vector<Parameter>& params);

/// Index of the parameter `name` (tmlab::Error listing the names when it is absent).
std::size_t index_of(const std::vector<Parameter>& params, const std::string& name);

/// Fixes parameter `name` at `value` (tmlab::Error if unknown or outside its bounds).
void fix(std::vector<Parameter>& params, const std::string& name, double value);

}  // namespace tmlab::fit
