// ProgressReporter: see progress.hpp.
#include "core/base/progress.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <utility>

#include <unistd.h>

namespace tmlab {

namespace {

/// "1:02:03" or "2:03"; "?" when unknown.
std::string format_duration(double seconds) {
  if (!(seconds >= 0.0) || seconds > 1e8) return "?";
  const long s = static_cast<long>(seconds + 0.5);
  char buf[32];
  if (s >= 3600) {
    std::snprintf(buf, sizeof(buf), "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  } else {
    std::snprintf(buf, sizeof(buf), "%ld:%02ld", s / 60, s % 60);
  }
  return buf;
}

}  // namespace

bool stderr_is_tty() { return ::isatty(STDERR_FILENO) == 1; }

ProgressReporter::ProgressReporter(long total_steps, std::ostream& out, bool tty, Options options,
                                   Clock::time_point start)
    : total_(std::max(total_steps, 0L)), out_(&out), tty_(tty), options_(std::move(options)), start_(start) {
  options_.percent_step = std::clamp(options_.percent_step, 1, 100);
  next_percent_ = options_.percent_step;
}

ProgressReporter::ProgressReporter(long total_steps, Options options)
    : ProgressReporter(total_steps, std::cerr, stderr_is_tty(), std::move(options), Clock::now()) {}

std::string ProgressReporter::status(long step, double sim_time, Clock::time_point now) const {
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = (elapsed > 0.0 && step > 0) ? static_cast<double>(step) / elapsed : 0.0;
  const int percent =
      total_ > 0 ? static_cast<int>(100.0 * static_cast<double>(step) / static_cast<double>(total_)) : 100;
  char buf[256];
  std::snprintf(buf, sizeof(buf), "[%s] step %ld/%ld (%d%%) t=%.6g ", options_.label.c_str(), step, total_,
                percent, sim_time);
  std::string s = buf;
  if (rate > 0.0) {
    std::snprintf(buf, sizeof(buf), "%.3g steps/s ETA %s", rate,
                  format_duration(static_cast<double>(total_ - step) / rate).c_str());
    s += buf;
  } else {
    s += "ETA ?";
  }
  s += " elapsed " + format_duration(elapsed);
  return s;
}

void ProgressReporter::emit(long step, double sim_time, Clock::time_point now) {
  const std::string line = status(step, sim_time, now);
  if (tty_) {
    // Rewrite the status line in place, blanking what is left of a longer previous one.
    *out_ << '\r' << line;
    if (line.size() < last_width_) *out_ << std::string(last_width_ - line.size(), ' ');
    last_width_ = line.size();
  } else {
    *out_ << line << '\n';
  }
  out_->flush();
  last_print_ = now;
  printed_ = true;
}

void ProgressReporter::update(long step, double sim_time) { update(step, sim_time, Clock::now()); }

void ProgressReporter::update(long step, double sim_time, Clock::time_point now) {
  if (finished_) return;
  last_step_ = step;
  last_time_ = sim_time;
  if (tty_) {
    const double since = std::chrono::duration<double>(now - last_print_).count();
    if (!printed_ || since >= options_.tty_interval_s) emit(step, sim_time, now);
    return;
  }
  if (total_ <= 0) return;
  const double percent = 100.0 * static_cast<double>(step) / static_cast<double>(total_);
  if (percent >= next_percent_ && next_percent_ <= 100) {
    // Skip thresholds already passed (large steps) so each line is printed once.
    while (next_percent_ <= percent) next_percent_ += options_.percent_step;
    emit(step, sim_time, now);
  }
}

void ProgressReporter::finish() { finish(Clock::now()); }

void ProgressReporter::finish(Clock::time_point now) {
  if (finished_) return;
  finished_ = true;
  if (tty_) {
    emit(last_step_, last_time_, now);
    *out_ << '\n';
    out_->flush();
  } else if (next_percent_ <= 100 || !printed_) {
    emit(last_step_, last_time_, now);  // the last state was not printed yet
  }
}

}  // namespace tmlab
