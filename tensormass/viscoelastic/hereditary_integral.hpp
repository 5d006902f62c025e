// The exact hereditary integral of the quasi-linear viscoelastic model by direct convolution, an
// independent check of the internal-variable ODE form (ode_references.hpp) and of ViscoelasticStVK's
// recursions (midpoint, exact_linear, backward_euler):
//
//   h_j(t) = int_{t0}^t exp(-(t-s)/tau_j) X_e'(s) ds,       X(t) = X_e(t) + sum_j alpha_j h_j(t)
//   (+ a jump X_e(t0) at t0 contributes exp(-(t-t0)/tau_j) X_e(t0) to h_j: the r(t) X_e(0+) of
//   docs/theory/seed-errata.md, eq. 11)
//
// X_e is a vector of any width (a scalar, one tet's stress, all tets' stresses). Two sources:
//   * an analytic rate X_e'(s) (a callback), integrated by composite Gauss-Legendre on `panels`
//     equal panels of [t0, t];
//   * a stored history of samples (t_k, X_e(t_k), X_e'(t_k)), interpolated by cubic Hermite
//     polynomials (X_e' is then the derivative of the interpolant, a quadratic per interval) and
//     integrated interval by interval by Gauss-Legendre; h at one sample time costs O(k), at all of
//     them O(n^2) (no recursion is used: that is the point of the check).
// Interpolation error O(dt^4) in X_e, O(dt^3) in X_e' (dt the sample spacing); the quadrature error
// with g Gauss points per interval is O((dt/tau)^(2g)) relative.
#pragma once

#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/viscoelastic/prony_series.hpp"

#include <functional>
#include <vector>

namespace tmlab::tm {

/// Gauss-Legendre nodes and weights on [-1, 1], n = 1..8 points (degree 2n-1 exact).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

/// h(t) = int_{t0}^t exp(-(t-s)/tau) X_e'(s) ds for an analytic rate; rate(s, out) writes X_e'(s)
/// (width values). Composite Gauss-Legendre with `panels` panels and `points` points per panel.
VecX convolve_rate(const std::function<void(double, VecX&)>& rate, Index width, double tau, double t0,
                   double t, int panels, int points = 5);

class StoredHistory {
 public:
  explicit StoredHistory(Index width);
  /// Appends a sample; times must increase strictly (throws tmlab::Error otherwise); x and dxdt have width().
  void add(double t, const VecX& x, const VecX& dxdt);
  Index width() const { return width_; }
  std::size_t size() const { return t_.size(); }
  double time(std::size_t k) const { return t_[k]; }
  const VecX& value(std::size_t k) const { return x_[k]; }
  /// X_e at t in [t_0, t_last] by cubic Hermite interpolation.
  VecX interpolate(double t) const;
  /// h(t_k) = exp(-(t_k - t_0)/tau) X_e(t_0) + int_{t_0}^{t_k} exp(-(t_k-s)/tau) X_H'(s) ds
  /// (the first term is the jump at t_0; zero when the history starts unloaded). `points` Gauss points
  /// per sample interval.
  VecX convolve(std::size_t k, double tau, int points = 5) const;
  /// X(t_k) = X_e(t_k) + sum_j alpha_j h_j(t_k).
  VecX total(std::size_t k, const PronySeries& prony, int points = 5) const;

 private:
  Index width_;
  std::vector<double> t_;
  std::vector<VecX> x_, dx_;
};

}  // namespace tmlab::tm
