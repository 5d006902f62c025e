// Stopwatch and seconds_since(). No assertion depends on how fast the machine is: only on the
// clocks being monotone and on the units (seconds).
#include "core/base/stopwatch.hpp"

#include <gtest/gtest.h>

#include <chrono>

namespace tmlab {
namespace {

TEST(Stopwatch, SecondsSinceAPastInstantIsInSeconds) {
  // An instant two seconds ago (constructed, not waited for): at least 2 s, and not 2000 (ms) or
  // 2e9 (ns). The upper bound only guards the unit; the test itself takes microseconds.
  const auto t0 = std::chrono::steady_clock::now() - std::chrono::seconds(2);
  const double s = seconds_since(t0);
  EXPECT_GE(s, 2.0);
  EXPECT_LT(s, 1000.0);
}

TEST(Stopwatch, WallAndCpuAreNonNegativeAndNonDecreasing) {
  const Stopwatch sw;
  double wall = sw.wall();
  double cpu = sw.cpu();
  EXPECT_GE(wall, 0.0);
  EXPECT_GE(cpu, 0.0);
  for (int i = 0; i < 1000; ++i) {
    const double w = sw.wall();
    const double c = sw.cpu();
    ASSERT_GE(w, wall);
    ASSERT_GE(c, cpu);
    wall = w;
    cpu = c;
  }
}

TEST(Stopwatch, CpuTimeAdvancesWhileThisProcessComputes) {
  // CPU time only advances while the process runs, so this loop ends on any machine load; its
  // result feeds `sink` so the work cannot be optimised away.
  const Stopwatch sw;
  volatile double sink = 0.0;
  do {
    for (int i = 0; i < 100000; ++i) sink = sink + 1e-9 * i;
  } while (sw.cpu() == 0.0);
  EXPECT_GT(sw.cpu(), 0.0);
  EXPECT_LT(sw.cpu(), 1000.0);  // seconds, not clock ticks
  EXPECT_GT(sink, 0.0);
}

}  // namespace
}  // namespace tmlab
