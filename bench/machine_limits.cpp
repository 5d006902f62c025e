#include "bench/machine_limits.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <thread>
#include <vector>

namespace tmlab::tm {

namespace {

using Clock = std::chrono::steady_clock;

/// Runs body(thread) on `threads` threads at once, repeatedly until `seconds` have passed; returns
/// the shortest wall time of one round (all threads started together each round).
double best_round(int threads, double seconds, const std::function<void(int)>& body) {
  double best = 1e300;
  const auto end = Clock::now() + std::chrono::duration<double>(seconds);
  int rounds = 0;
  do {
    const auto t0 = Clock::now();
    std::vector<std::thread> pool;
    for (int k = 1; k < threads; ++k) pool.emplace_back(body, k);
    body(0);
    for (auto& th : pool) th.join();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
    ++rounds;
  } while (Clock::now() < end || rounds < 3);
  return best;
}

volatile double g_sink = 0.0;  // keeps the FMA results alive

double fma_gflops(int threads, double seconds) {
  constexpr int kLanes = 32;
  constexpr long kIters = 2000000;
  auto body = [](int) {
    alignas(64) double acc[kLanes];
    for (int l = 0; l < kLanes; ++l) acc[l] = 1.0 + 1e-3 * l;
    const double x = 0.999999, y = 1e-7;
    for (long k = 0; k < kIters; ++k)
      for (int l = 0; l < kLanes; ++l) acc[l] = acc[l] * x + y;
    double s = 0.0;
    for (int l = 0; l < kLanes; ++l) s += acc[l];
    g_sink = s;
  };
  const double t = best_round(threads, seconds, body);
  return 2.0 * kLanes * kIters * threads / t * 1e-9;
}

double triad_gbs(int threads, double seconds, std::size_t bytes) {
  const std::size_t n = bytes / 24 / static_cast<std::size_t>(threads);
  std::vector<std::vector<double>> a(static_cast<std::size_t>(threads)), b(a.size()), c(a.size());
  // First touch by the thread that uses the arrays.
  best_round(threads, 0.0, [&](int k) {
    const std::size_t i = static_cast<std::size_t>(k);
    a[i].assign(n, 0.0);
    b[i].assign(n, 1.0);
    c[i].assign(n, 2.0);
  });
  auto body = [&](int k) {
    const std::size_t i = static_cast<std::size_t>(k);
    double* pa = a[i].data();
    const double* pb = b[i].data();
    const double* pc = c[i].data();
    const double s = 3.0;
    for (std::size_t j = 0; j < n; ++j) pa[j] = pb[j] + s * pc[j];
  };
  const double t = best_round(threads, seconds, body);
  double chk = 0.0;
  for (const auto& v : a) chk += v[n / 2];
  g_sink = chk;
  return 24.0 * static_cast<double>(n) * threads / t * 1e-9;
}

}  // namespace

MachineLimits measure_machine_limits(double seconds_each, std::size_t triad_bytes) {
  MachineLimits m;
  m.peak_gflops_1t = fma_gflops(1, seconds_each);
  m.peak_gflops_2t = fma_gflops(2, seconds_each);
  m.triad_gbs_1t = triad_gbs(1, seconds_each, triad_bytes);
  m.triad_gbs_2t = triad_gbs(2, seconds_each, triad_bytes);
  return m;
}

}  // namespace tmlab::tm
