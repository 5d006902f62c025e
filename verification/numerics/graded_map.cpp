// The graded map of the indentation blocks: see graded_map.hpp.
#include "verification/numerics/graded_map.hpp"

#include <cmath>

namespace tmlab::verify::numerics {

double grading_rate(double W_over_L, double t_a) {
  auto g = [&](double k) { return 1.0 + (std::expm1(k * (1.0 - t_a)) / k) / t_a - W_over_L; };
  double lo = 1e-9, hi = 1.0;
  while (g(hi) < 0.0) hi *= 2.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double graded(double xi, double L, double t_a, double k) {
  return xi <= t_a ? L * xi / t_a : L + (L / t_a) * std::expm1(k * (xi - t_a)) / k;
}

}  // namespace tmlab::verify::numerics
