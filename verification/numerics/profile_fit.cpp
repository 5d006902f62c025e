// Offset-free errors of a surface profile: see profile_fit.hpp.
#include "verification/numerics/profile_fit.hpp"

#include <Eigen/Dense>

#include <cmath>

namespace tmlab::verify::numerics {

ProfileErrors profile_errors(const std::vector<double>& r, const std::vector<double>& uz, double a,
                             double c) {
  const std::size_t n = r.size();
  double mean = 0.0;
  for (std::size_t i = 0; i < n; ++i) mean += uz[i] + c * (2 * a * a - r[i] * r[i]);
  mean /= double(n);
  double ss = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = uz[i] + c * (2 * a * a - r[i] * r[i]) - mean;
    ss += d * d;
  }
  Eigen::MatrixXd A(n, 2);
  Eigen::VectorXd b(n);
  for (std::size_t i = 0; i < n; ++i) {
    A(i, 0) = 1.0;
    A(i, 1) = r[i] * r[i];
    b[i] = uz[i];
  }
  const Eigen::Vector2d coef = A.colPivHouseholderQr().solve(b);
  ProfileErrors e;
  e.rms = std::sqrt(ss / double(n)) / (c * a * a);
  e.curvature = std::abs(coef[1] - c) / c;
  return e;
}

}  // namespace tmlab::verify::numerics
