// The benchmark's confusion matrix is diagonal within the stated tolerance (docs/discover.md,
// section 6). Quick (label unit): noise only, a contact offset, a neo-Hookean law, a force drift and
// an actuator resonance on unconfined compression, a finite layer under a sphere indenter
// (the indentation forward model end to end) and an extra Prony term in confined compression (the
// confined forward model end to end); every one must come out right: the library sets exactly their
// effect, the noise-only set nothing and no structure, the resonance unexplained and periodic at 0.7 Hz. Full
// (label slow, TMLAB_DISCOVER_FULL_BENCHMARK=1 or the slow ctest): every applicable library effect and
// separate bulk and shear relaxation on unconfined compression, three noise-only sets, three outside effects,
// seven sphere-indentation, four tension and three confined-compression sets; tolerance below.
#include "calibration/discover/benchmark.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

namespace tmlab::discover {
namespace {

TEST(Benchmark, QuickConfusionMatrixIsDiagonal) {
  Options o;
  const BenchmarkResult b = run_benchmark(benchmark_sets(true), o);
  ASSERT_EQ(b.entries.size(), 7u);
  EXPECT_EQ(b.entries.back().rig, "confined_compression");
  for (const auto& e : b.entries) {
    std::string f;
    for (const auto& x : e.found) f += x + " ";
    EXPECT_TRUE(e.correct) << e.name << ": found [" << f << "], unexplained " << e.unexplained << " "
                           << e.signature;
  }
  EXPECT_EQ(b.noise_false_positives, 0);
  EXPECT_EQ(b.outside_flagged, 1);
  EXPECT_EQ(b.outside_forced, 0);
  EXPECT_DOUBLE_EQ(b.diagonal_fraction, 1.0);
  EXPECT_GT(b.median_error_reduction, 0.5);
  for (const auto& e : b.entries)
    if (e.truth == "actuator_resonance") {
      // 0.7 Hz to the resolution of the periodogram (1 / test duration = 0.013 Hz and up).
      const bool near = e.signature.find("periodic at 0.69") != std::string::npos ||
                        e.signature.find("periodic at 0.7") != std::string::npos;
      EXPECT_TRUE(near) << e.signature;
    }
}

TEST(Benchmark, FullConfusionMatrixIsDiagonalWithinTolerance) {
  if (!std::getenv("TMLAB_DISCOVER_FULL_BENCHMARK")) GTEST_SKIP() << "set TMLAB_DISCOVER_FULL_BENCHMARK=1";
  Options o;
  const BenchmarkResult b = run_benchmark(benchmark_sets(false), o);
  // Stated tolerance (docs/discover.md): at least 80 % of the library sets right (a law credited
  // within the hyperelastic family), no false positive on the noise-only sets, every outside set
  // flagged as unexplained structure and none with an effect forced onto it.
  EXPECT_GE(b.diagonal_fraction, 0.8);
  EXPECT_EQ(b.library_sets, 25);
  EXPECT_EQ(b.noise_sets, 6);
  for (const auto& e : b.entries) {
    if (e.rig == "confined_compression") {
      EXPECT_TRUE(e.correct) << e.name;
    }
  }
  EXPECT_EQ(b.noise_false_positives, 0);
  EXPECT_EQ(b.outside_sets, 3);
  EXPECT_EQ(b.outside_flagged, b.outside_sets);
  // None with a shared effect forced onto it (a difference between tests is refused by the
  // test-consistency control; the resonance matches no candidate).
  EXPECT_EQ(b.outside_forced, 0);
}

}  // namespace
}  // namespace tmlab::discover
