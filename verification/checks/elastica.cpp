#include "verification/checks/elastica.hpp"

#include "core/base/error.hpp"

#include <array>
#include <cmath>
#include <string>

namespace tmlab::verify {

namespace {
/// int_0^theta0 f(theta) dtheta / sqrt(2 (sin theta0 - sin theta)) with sin theta = sin theta0 - v^2:
/// int_0^sqrt(sin theta0) sqrt(2) f(theta(v)) / cos(theta(v)) dv.
template <class F>
double elastica_integral(double theta0, F f, int panels) {
  static constexpr std::array<double, 5> x{-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                           0.9061798459386640};
  static constexpr std::array<double, 5> w{0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                           0.4786286704993665, 0.2369268850561891};
  const double s0 = std::sin(theta0), V = std::sqrt(s0), h = V / panels;
  double sum = 0.0;
  for (int i = 0; i < panels; ++i)
    for (int q = 0; q < 5; ++q) {
      const double v = h * (i + 0.5 * (x[q] + 1.0));
      const double theta = std::asin(s0 - v * v);
      sum += 0.5 * h * w[q] * std::sqrt(2.0) * f(theta) / std::cos(theta);
    }
  return sum;
}
}  // namespace

ElasticaTip elastica_cantilever_tip(double k) {
  if (!(k > 0.0 && k <= 1000.0))
    throw Error("elastica: load parameter P L^2 / (E I) must be in (0, 1000] (got " + std::to_string(k) +
                ")");
  const double target = std::sqrt(k), pi = std::acos(-1.0);
  auto alpha = [](double theta0) {
    return elastica_integral(
        theta0, [](double) { return 1.0; }, 400);
  };
  double lo = 0.0, hi = 0.5 * pi * (1.0 - 1e-12);
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (alpha(mid) < target ? lo : hi) = mid;
  }
  ElasticaTip tip;
  tip.theta0 = 0.5 * (lo + hi);
  const int panels = 4000;
  const double a = elastica_integral(
      tip.theta0, [](double) { return 1.0; }, panels);
  tip.axial = std::sqrt(2.0 * std::sin(tip.theta0)) / a;
  tip.transverse = elastica_integral(
                       tip.theta0, [](double t) { return std::sin(t); }, panels) /
                   a;
  return tip;
}

}  // namespace tmlab::verify
