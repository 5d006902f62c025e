// Error norms of the verification checks.
#pragma once

#include <Eigen/Core>

namespace tmlab::verify::numerics {

/// ||a - b||_inf / max(||b||_inf, floor): the relative max-norm difference.
double rel_max_diff(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double floor = 1e-300);

}  // namespace tmlab::verify::numerics
