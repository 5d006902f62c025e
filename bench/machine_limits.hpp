// The machine's own limits, measured in the same run as the kernels so that ratios can be quoted
// against them (docs/performance.md): double-precision FMA throughput (peak GFLOP/s) and the
// STREAM triad bandwidth a = b + s c (24 bytes moved per element, arrays far larger than the
// caches), each on 1 and 2 threads. Each thread is started once per measurement and repeats the
// loop; the best of the repeats is kept (the machine is shared: the best is the least disturbed).
#pragma once

#include <cstddef>

namespace tmlab::tm {

struct MachineLimits {
  double peak_gflops_1t = 0.0, peak_gflops_2t = 0.0;
  double triad_gbs_1t = 0.0, triad_gbs_2t = 0.0;
};

/// FMA loop: 32 independent chains of acc = acc * x + y (vectorised), 2 flops per FMA.
/// Triad: `triad_bytes` in total over the three arrays (split between the threads).
MachineLimits measure_machine_limits(double seconds_each = 0.3, std::size_t triad_bytes = std::size_t(768)
                                                                                          << 20);

}  // namespace tmlab::tm
