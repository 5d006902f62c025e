// Direct convolution of the Prony kernel with X_e' (hereditary_integral.hpp).
#include "tensormass/viscoelastic/hereditary_integral.hpp"

#include "core/base/error.hpp"

#include <cmath>
#include <string>

namespace tmlab::tm {

void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  if (n < 1 || n > 8) throw Error("gauss_legendre: 1..8 points supported, got " + std::to_string(n));
  nodes.assign(static_cast<std::size_t>(n), 0.0);
  weights.assign(static_cast<std::size_t>(n), 0.0);
  // Newton on the Legendre polynomial P_n from the Chebyshev-like guess cos(pi (i + 3/4)/(n + 1/2)).
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;  // P_0, P_1; recurrence (k+1) P_{k+1} = (2k+1) x P_k - k P_{k-1}
      for (int k = 1; k < n; ++k) {
        const double p2 = ((2.0 * k + 1.0) * x * p1 - k * p0) / (k + 1.0);
        p0 = p1;
        p1 = p2;
      }
      const double pn = n == 1 ? x : p1, pm = n == 1 ? 1.0 : p0;
      dp = n * (x * pn - pm) / (x * x - 1.0);  // P_n'(x)
      const double dx = pn / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    nodes[static_cast<std::size_t>(i)] = x;
    weights[static_cast<std::size_t>(i)] =
        2.0 / ((1.0 - x * x) * dp * dp);  // w_i = 2 / ((1 - x^2) P_n'(x)^2)
  }
}

VecX convolve_rate(const std::function<void(double, VecX&)>& rate, Index width, double tau, double t0,
                   double t, int panels, int points) {
  std::vector<double> xg, wg;
  gauss_legendre(points, xg, wg);
  VecX h = VecX::Zero(width), r(width);
  if (!(t > t0) || panels < 1) return h;
  const double dt = (t - t0) / panels;
  for (int p = 0; p < panels; ++p) {
    const double c = t0 + (p + 0.5) * dt;
    for (std::size_t q = 0; q < xg.size(); ++q) {
      const double s = c + 0.5 * dt * xg[q];
      rate(s, r);
      h += (0.5 * dt * wg[q] * std::exp(-(t - s) / tau)) * r;  // exp(-(t-s)/tau) X_e'(s) ds
    }
  }
  return h;
}

StoredHistory::StoredHistory(Index width) : width_(width) {}

void StoredHistory::add(double t, const VecX& x, const VecX& dxdt) {
  if (!t_.empty() && !(t > t_.back()))
    throw Error("StoredHistory::add: time " + std::to_string(t) + " does not follow " +
                std::to_string(t_.back()));
  if (x.size() != width_ || dxdt.size() != width_)
    throw Error("StoredHistory::add: sample width differs from " + std::to_string(width_));
  t_.push_back(t);
  x_.push_back(x);
  dx_.push_back(dxdt);
}

VecX StoredHistory::interpolate(double t) const {
  if (t_.empty()) throw Error("StoredHistory::interpolate: empty history");
  if (t <= t_.front()) return x_.front();
  if (t >= t_.back()) return x_.back();
  std::size_t i = 0;
  while (t_[i + 1] < t) ++i;
  const double h = t_[i + 1] - t_[i], s = (t - t_[i]) / h;
  // Cubic Hermite basis on [t_i, t_{i+1}]
  const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s), h01 = s * s * (3 - 2 * s),
               h11 = s * s * (s - 1);
  return h00 * x_[i] + (h10 * h) * dx_[i] + h01 * x_[i + 1] + (h11 * h) * dx_[i + 1];
}

VecX StoredHistory::convolve(std::size_t k, double tau, int points) const {
  if (k >= t_.size()) throw Error("StoredHistory::convolve: sample index out of range");
  std::vector<double> xg, wg;
  gauss_legendre(points, xg, wg);
  const double t = t_[k];
  // jump at t_0
  VecX h = std::exp(-(t - t_[0]) / tau) * x_[0];
  for (std::size_t i = 0; i < k; ++i) {
    const double dt = t_[i + 1] - t_[i];
    // Derivative of the Hermite interpolant, s in [0, 1]:
    //   X_H'(s) = [dh00 x_i + dh01 x_{i+1}]/dt + dh10 X'_i + dh11 X'_{i+1}
    for (std::size_t q = 0; q < xg.size(); ++q) {
      const double s = 0.5 * (1.0 + xg[q]);
      const double d00 = 6 * s * s - 6 * s, d10 = 3 * s * s - 4 * s + 1, d01 = -6 * s * s + 6 * s,
                   d11 = 3 * s * s - 2 * s;
      const double weight = 0.5 * dt * wg[q] * std::exp(-(t - (t_[i] + s * dt)) / tau);
      h += (weight * d00 / dt) * x_[i] + (weight * d01 / dt) * x_[i + 1] + (weight * d10) * dx_[i] +
           (weight * d11) * dx_[i + 1];
    }
  }
  return h;
}

VecX StoredHistory::total(std::size_t k, const PronySeries& prony, int points) const {
  VecX X = x_.at(k);
  for (std::size_t j = 0; j < prony.size(); ++j) X += prony.alpha(j) * convolve(k, prony.tau(j), points);
  return X;
}

}  // namespace tmlab::tm
