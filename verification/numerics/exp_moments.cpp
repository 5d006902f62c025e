// Exponential moments and the hereditary integral of a polynomial driver: see exp_moments.hpp.
#include "verification/numerics/exp_moments.hpp"

#include <algorithm>
#include <cmath>

namespace tmlab::verify::numerics {

std::vector<double> exp_moments(double t, double tau, std::size_t kmax) {
  std::vector<double> I(kmax + 1, 0.0);
  const double x = t / tau;
  if (x >= 1.0) {
    I[0] = -tau * std::expm1(-x);
    double tk = 1.0;
    for (std::size_t k = 1; k <= kmax; ++k) {
      tk *= t;
      I[k] = tau * tk - double(k) * tau * I[k - 1];
    }
    return I;
  }
  double tk1 = t, kfact = 1.0;  // t^{k+1}, k!
  for (std::size_t k = 0; k <= kmax; ++k) {
    if (k > 0) {
      tk1 *= t;
      kfact *= double(k);
    }
    // sum_m (-x)^m / (k+m+1)!, terms computed by ratio.
    double term = 1.0;
    for (std::size_t j = 1; j <= k + 1; ++j) term /= double(j);  // 1/(k+1)!
    double sum = term;
    for (int mm = 1; mm < 200; ++mm) {
      term *= -x / double(k + 1 + mm);
      sum += term;
      if (std::abs(term) < 1e-18 * std::abs(sum)) break;
    }
    I[k] = tk1 * kfact * sum;
  }
  return I;
}

double hereditary(const Poly& Y, double t1, double tau, double t) {
  const Poly dY = poly_deriv(Y);
  const double te = std::min(t, t1);
  const auto I = exp_moments(te, tau, dY.size());
  double h = 0.0;
  for (std::size_t k = 0; k < dY.size(); ++k) h += dY[k] * I[k];
  if (t > t1) h *= std::exp(-(t - t1) / tau);
  return h;
}

}  // namespace tmlab::verify::numerics
