// The relative max-norm difference on vectors whose answer is read off by hand.
#include "verification/numerics/error_norms.hpp"

#include <gtest/gtest.h>

namespace tmlab::verify::numerics {
namespace {

Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd x(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double e : v) x[i++] = e;
  return x;
}

TEST(ErrorNorms, RelativeMaxDifference) {
  EXPECT_DOUBLE_EQ(rel_max_diff(vec({1.0, 2.0, 3.0}), vec({1.0, 2.0, 4.0})), 0.25);
  EXPECT_DOUBLE_EQ(rel_max_diff(vec({-5.0, 0.0}), vec({-2.0, 1.0})), 1.5);
  EXPECT_EQ(rel_max_diff(vec({1.0, -1.0}), vec({1.0, -1.0})), 0.0);
}

TEST(ErrorNorms, FloorBoundsTheDenominator) {
  EXPECT_DOUBLE_EQ(rel_max_diff(vec({1e-3, 0.0}), vec({0.0, 0.0}), 1e-2), 0.1);
  EXPECT_DOUBLE_EQ(rel_max_diff(vec({3.0}), vec({1.0}), 10.0), 0.2);
  EXPECT_DOUBLE_EQ(rel_max_diff(vec({3.0}), vec({1.0}), 0.5), 2.0);
}

}  // namespace
}  // namespace tmlab::verify::numerics
