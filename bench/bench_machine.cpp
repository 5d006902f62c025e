// The machine's own limits, measured in the same run as the kernels so ratios can be quoted:
// memory bandwidth (STREAM-style triad a = b + s c, 24 bytes per element moved) on arrays far larger
// than cache, and double-precision FMA throughput (independent chains, vectorisable).
#include <benchmark/benchmark.h>

#include <vector>

namespace {

void BM_Triad(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double s = 3.0;
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(24 * n));
}
BENCHMARK(BM_Triad)->Arg(1 << 12)->Arg(1 << 25)->Unit(benchmark::kMillisecond);

void BM_FmaThroughput(benchmark::State& state) {
  // 32 independent accumulators x 1000 iterations, 2 flops per FMA.
  constexpr int kLanes = 32, kIters = 1000;
  alignas(64) double acc[kLanes];
  for (int l = 0; l < kLanes; ++l) acc[l] = 1.0 + 1e-3 * l;
  const double x = 0.999999, y = 1e-7;
  for (auto _ : state) {
    for (int k = 0; k < kIters; ++k)
      for (int l = 0; l < kLanes; ++l) acc[l] = acc[l] * x + y;
    benchmark::DoNotOptimize(acc);
  }
  state.counters["FLOP/s"] =
      benchmark::Counter(2.0 * kLanes * kIters, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_FmaThroughput);

}  // namespace

BENCHMARK_MAIN();
