#include "realtime/loop_timing.hpp"

#include <algorithm>
#include <cmath>

namespace tmlab::rt {

double percentile(std::vector<float> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double rank = std::ceil(q * static_cast<double>(v.size()));
  const std::size_t i = static_cast<std::size_t>(std::clamp(rank, 1.0, static_cast<double>(v.size()))) - 1;
  return static_cast<double>(v[i]);
}

ThreadTiming LoopTiming::summary(const std::string& name, double target_hz, double elapsed_s) const {
  ThreadTiming t;
  t.name = name;
  t.target_hz = target_hz;
  t.iterations = iterations_;
  t.elapsed_s = elapsed_s;
  t.rate_hz = elapsed_s > 0.0 ? static_cast<double>(iterations_) / elapsed_s : 0.0;
  t.p50_us = percentile(lateness_, 0.5);
  t.p99_us = percentile(lateness_, 0.99);
  t.p999_us = percentile(lateness_, 0.999);
  t.busy_p50_us = percentile(busy_, 0.5);
  t.busy_p99_us = percentile(busy_, 0.99);
  t.missed = missed_;
  t.unrecorded = unrecorded_;
  return t;
}

}  // namespace tmlab::rt
