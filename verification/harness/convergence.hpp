// Observed orders of convergence: least-squares slope of log(error) against log(h).
#pragma once

#include <vector>

namespace tmlab::verify {

/// Slope of the least-squares line through (log x_i, log y_i) over the `last` points with the
/// smallest x (all points when last <= 0 or last > n). Needs >= 2 points with x, y > 0 and
/// distinct x; throws tmlab::Error otherwise.
double fitted_order(const std::vector<double>& x, const std::vector<double>& y, int last = 0);

/// Orders between consecutive points (sorted by decreasing x): log(y_i/y_{i+1}) / log(x_i/x_{i+1}).
std::vector<double> pairwise_orders(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace tmlab::verify
