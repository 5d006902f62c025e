// SIGINT / SIGTERM as a request to stop at the next safe point: see interrupt.hpp.
#include "core/base/interrupt.hpp"

#include <csignal>
#include <cstdlib>
#include <string>

#include <signal.h>

namespace tmlab {

namespace {

// The only process-wide state in tmlab (see interrupt.hpp): written by the handler, read at safe points.
volatile std::sig_atomic_t g_pending_signal = 0;

// The test stop point (note_progress_point): set once by the InterruptHandler from the environment;
// counted on the thread that writes checkpoints. Belongs to the same process-wide signal state.
struct TestStopPoint {
  long at = 0;  // raise at this call (0: never)
  int signal = SIGINT;
  long calls = 0;
};
TestStopPoint g_stop_point;

constexpr const char* kStopVariable = "TMLAB_TEST_STOP_AFTER_PROGRESS";

TestStopPoint parse_stop_point(const char* text) {
  TestStopPoint p;
  if (text == nullptr || *text == '\0') return p;
  const std::string s(text);
  const std::size_t colon = s.find(':');
  const std::string count = s.substr(0, colon);
  const std::string sig = colon == std::string::npos ? "SIGINT" : s.substr(colon + 1);
  std::size_t used = 0;
  long n = 0;
  try {
    n = std::stol(count, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != count.size() || count.empty() || n < 1)
    throw Error(std::string(kStopVariable) + "='" + s + "': expected N or N:SIGINT / N:SIGTERM with N >= 1");
  if (sig == "SIGINT")
    p.signal = SIGINT;
  else if (sig == "SIGTERM")
    p.signal = SIGTERM;
  else
    throw Error(std::string(kStopVariable) + "='" + s + "': the signal must be SIGINT or SIGTERM");
  p.at = n;
  return p;
}

extern "C" void tmlab_on_signal(int sig) {
  if (g_pending_signal != 0) {
    // Second signal: the first was not honoured yet; let the default action end the process.
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  g_pending_signal = sig;
}

}  // namespace

struct InterruptHandler::Saved {
  struct sigaction previous[2];
};

InterruptHandler::InterruptHandler() : saved_(std::make_unique<Saved>()) {
  g_stop_point = parse_stop_point(std::getenv(kStopVariable));  // throws before anything is installed
  g_pending_signal = 0;
  struct sigaction sa {};
  sa.sa_handler = tmlab_on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &sa, &saved_->previous[0]);
  ::sigaction(SIGTERM, &sa, &saved_->previous[1]);
}

InterruptHandler::~InterruptHandler() {
  g_stop_point = TestStopPoint{};
  ::sigaction(SIGINT, &saved_->previous[0], nullptr);
  ::sigaction(SIGTERM, &saved_->previous[1], nullptr);
}

int pending_interrupt() { return g_pending_signal; }

void set_pending_interrupt(int signal) { g_pending_signal = signal; }

std::string signal_name(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  return "signal " + std::to_string(signal);
}

void note_progress_point() {
  if (g_stop_point.at > 0 && ++g_stop_point.calls == g_stop_point.at) std::raise(g_stop_point.signal);
}

void check_interrupt(const std::string& where) {
  const int sig = g_pending_signal;
  if (sig != 0) throw Interrupted(sig, signal_name(sig) + " received " + where);
}

}  // namespace tmlab
