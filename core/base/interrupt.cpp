// SIGINT / SIGTERM as a request to stop at the next safe point: see interrupt.hpp.
#include "core/base/interrupt.hpp"

#include <csignal>

#include <signal.h>

namespace tmlab {

namespace {

// The only process-wide state in tmlab (see interrupt.hpp): written by the handler, read at safe points.
volatile std::sig_atomic_t g_pending_signal = 0;

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
  g_pending_signal = 0;
  struct sigaction sa {};
  sa.sa_handler = tmlab_on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &sa, &saved_->previous[0]);
  ::sigaction(SIGTERM, &sa, &saved_->previous[1]);
}

InterruptHandler::~InterruptHandler() {
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

void check_interrupt(const std::string& where) {
  const int sig = g_pending_signal;
  if (sig != 0) throw Interrupted(sig, signal_name(sig) + " received " + where);
}

}  // namespace tmlab
