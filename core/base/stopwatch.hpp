// Elapsed time for logs and study tables: wall time from std::chrono::steady_clock and process CPU
// time from std::clock. Header-only; no global state.
#pragma once

#include <chrono>
#include <ctime>

namespace tmlab {

/// Wall seconds (steady_clock) since t0.
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Wall and process CPU seconds since construction.
class Stopwatch {
 public:
  double wall() const { return seconds_since(wall0_); }
  double cpu() const { return static_cast<double>(std::clock() - cpu0_) / CLOCKS_PER_SEC; }

 private:
  std::clock_t cpu0_ = std::clock();
  std::chrono::steady_clock::time_point wall0_ = std::chrono::steady_clock::now();
};

}  // namespace tmlab
