#include "verification/harness/convergence.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace tmlab::verify {

namespace {

/// Indices sorted by decreasing x (coarse to fine).
std::vector<std::size_t> coarse_to_fine(const std::vector<double>& x) {
  std::vector<std::size_t> idx(x.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return x[a] > x[b]; });
  return idx;
}

}  // namespace

double fitted_order(const std::vector<double>& x, const std::vector<double>& y, int last) {
  if (x.size() != y.size()) throw Error("fitted_order: x and y differ in length");
  const auto idx = coarse_to_fine(x);
  const std::size_t n = x.size();
  const std::size_t m =
      (last <= 0 || static_cast<std::size_t>(last) > n) ? n : static_cast<std::size_t>(last);
  if (m < 2) throw Error("fitted_order: needs at least two points (got " + std::to_string(m) + ")");
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = n - m; k < n; ++k) {
    const double xi = x[idx[k]], yi = y[idx[k]];
    if (!(xi > 0) || !(yi > 0) || !std::isfinite(xi) || !std::isfinite(yi))
      throw Error("fitted_order: needs positive finite values (got x = " + std::to_string(xi) +
                  ", y = " + std::to_string(yi) + ")");
    const double lx = std::log(xi), ly = std::log(yi);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  const double md = static_cast<double>(m);
  const double den = md * sxx - sx * sx;
  if (!(std::abs(den) > 1e-14 * md * sxx)) throw Error("fitted_order: the x values are not distinct");
  return (md * sxy - sx * sy) / den;
}

std::vector<double> pairwise_orders(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size()) throw Error("pairwise_orders: x and y differ in length");
  const auto idx = coarse_to_fine(x);
  std::vector<double> out;
  for (std::size_t k = 0; k + 1 < idx.size(); ++k) {
    const double x0 = x[idx[k]], x1 = x[idx[k + 1]], y0 = y[idx[k]], y1 = y[idx[k + 1]];
    out.push_back(std::log(y0 / y1) / std::log(x0 / x1));
  }
  return out;
}

}  // namespace tmlab::verify
