// The graded map against its defining conditions: s(1) = W for the k grading_rate finds, uniform
// (s = L xi / t_a) over the patch, s(t_a) = L, continuous slope L / t_a at t_a, increasing.
#include "verification/numerics/graded_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::verify::numerics {
namespace {

TEST(GradedMap, ReachesTheBlockWidth) {
  for (const auto& [W_over_L, t_a] : {std::pair{30.0, 0.5}, std::pair{8.0, 0.25}, std::pair{3.0, 0.5}}) {
    const double L = 2e-3;
    const double k = grading_rate(W_over_L, t_a);
    EXPECT_GT(k, 0.0);
    EXPECT_NEAR(graded(1.0, L, t_a, k), W_over_L * L, 1e-12 * W_over_L * L) << "W/L = " << W_over_L;
  }
}

TEST(GradedMap, UniformOverThePatchThenC1) {
  const double L = 1.5, t_a = 0.4;
  const double k = grading_rate(20.0, t_a);
  EXPECT_DOUBLE_EQ(graded(0.0, L, t_a, k), 0.0);
  EXPECT_DOUBLE_EQ(graded(0.1, L, t_a, k), 0.375);
  EXPECT_DOUBLE_EQ(graded(t_a, L, t_a, k), L);
  // The slope just beyond t_a equals the patch's L / t_a (exp(k (xi - t_a)) -> 1).
  const double h = 1e-7;
  const double right = (graded(t_a + h, L, t_a, k) - graded(t_a, L, t_a, k)) / h;
  EXPECT_NEAR(right, L / t_a, 1e-5 * L / t_a);
  // The slope grows like exp(k (xi - t_a)) beyond.
  const double mid = 0.7;
  const double slope = (graded(mid + h, L, t_a, k) - graded(mid - h, L, t_a, k)) / (2 * h);
  EXPECT_NEAR(slope, (L / t_a) * std::exp(k * (mid - t_a)), 1e-6 * slope);
  double prev = -1.0;
  for (int i = 0; i <= 100; ++i) {
    const double s = graded(i / 100.0, L, t_a, k);
    EXPECT_GT(s, prev);
    prev = s;
  }
}

}  // namespace
}  // namespace tmlab::verify::numerics
