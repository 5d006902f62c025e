// Timing of one real-time thread: per iteration the lateness of its start against its schedule
// (the jitter) and its busy time, in storage reserved before the loop (record() never allocates;
// samples beyond the capacity are counted, not stored), summarised after the run.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace tmlab::rt {

struct ThreadTiming {
  std::string name;
  double target_hz = 0.0;
  double rate_hz = 0.0;  ///< iterations / elapsed wall time
  long iterations = 0;
  double elapsed_s = 0.0;
  double p50_us = 0.0, p99_us = 0.0, p999_us = 0.0;  ///< lateness of the iteration start (jitter)
  double busy_p50_us = 0.0, busy_p99_us = 0.0;       ///< work per iteration
  long missed = 0;                                   ///< iterations that ended after their deadline
  long unrecorded = 0;                               ///< samples beyond the reserved capacity
};

class LoopTiming {
 public:
  explicit LoopTiming(std::size_t capacity = 0) { reserve(capacity); }
  void reserve(std::size_t capacity) {
    lateness_.reserve(capacity);
    busy_.reserve(capacity);
  }
  /// One iteration (hot path: no allocation).
  void record(double lateness_us, double busy_us, bool missed) {
    ++iterations_;
    if (missed) ++missed_;
    if (lateness_.size() < lateness_.capacity()) {
      lateness_.push_back(static_cast<float>(lateness_us));
      busy_.push_back(static_cast<float>(busy_us));
    } else {
      ++unrecorded_;
    }
  }
  /// Percentiles (nearest rank) of the recorded samples; rate over `elapsed_s`.
  ThreadTiming summary(const std::string& name, double target_hz, double elapsed_s) const;

 private:
  std::vector<float> lateness_, busy_;
  long iterations_ = 0, missed_ = 0, unrecorded_ = 0;
};

/// Nearest-rank percentile q in [0, 1] of `v` (sorted copy); 0 for an empty set.
double percentile(std::vector<float> v, double q);

}  // namespace tmlab::rt
