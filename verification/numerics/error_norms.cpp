// Error norms of the verification checks: see error_norms.hpp.
#include "verification/numerics/error_norms.hpp"

#include <algorithm>

namespace tmlab::verify::numerics {

double rel_max_diff(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double floor) {
  return (a - b).lpNorm<Eigen::Infinity>() / std::max(b.lpNorm<Eigen::Infinity>(), floor);
}

}  // namespace tmlab::verify::numerics
