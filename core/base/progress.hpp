// tmlab::ProgressReporter: "step k/N, time, rate, ETA" for long runs. On a terminal it rewrites one
// status line at most every ~0.5 s; otherwise (a log file, CI) it prints a full line at every 10%
// of the steps, so logs stay short. Time comes from std::chrono::steady_clock, measured or passed
// in (for tests); there is no global state.
#pragma once

#include <chrono>
#include <iosfwd>
#include <string>

namespace tmlab {

/// True when standard error is a terminal.
bool stderr_is_tty();

/// How a ProgressReporter prints.
struct ProgressOptions {
  std::string label = "run";    ///< shown in brackets at the start of each line
  double tty_interval_s = 0.5;  ///< minimum time between terminal updates
  int percent_step = 10;        ///< log mode: print at every this many percent
};

class ProgressReporter {
 public:
  using Clock = std::chrono::steady_clock;

  /// Options (a namespace-scope struct so it can be a default argument here).
  using Options = ProgressOptions;

  /// Reports progress of `total_steps` steps to `out` (which must outlive the reporter); `tty`
  /// selects the terminal mode. `start` is the wall-clock start used for rate and ETA.
  ProgressReporter(long total_steps, std::ostream& out, bool tty, Options options, Clock::time_point start);
  /// To std::cerr, terminal mode when stderr is a TTY, starting now.
  explicit ProgressReporter(long total_steps, Options options = {});

  /// Reports that `step` steps (of total_steps) are done and simulated time is `sim_time`.
  void update(long step, double sim_time);
  void update(long step, double sim_time, Clock::time_point now);
  /// Prints the final state (and ends the terminal line). Idempotent.
  void finish();
  void finish(Clock::time_point now);

  /// The status text for this state, e.g. "[run] step 120/1000 (12%) t=0.012 40.1 steps/s ETA 0:22".
  std::string status(long step, double sim_time, Clock::time_point now) const;

 private:
  void emit(long step, double sim_time, Clock::time_point now);

  long total_;
  std::ostream* out_;
  bool tty_;
  Options options_;
  Clock::time_point start_;
  Clock::time_point last_print_{};
  bool printed_ = false;
  int next_percent_ = 0;  ///< log mode: next percentage to print at
  long last_step_ = 0;
  double last_time_ = 0.0;
  std::size_t last_width_ = 0;  ///< terminal mode: length of the line to overwrite
  bool finished_ = false;
};

}  // namespace tmlab
