// Stopping long commands cleanly on SIGINT / SIGTERM.
//
// An InterruptHandler (one, in main()) installs handlers that only record the signal; long loops
// call check_interrupt() at their safe points (after a step, between verification cases), which
// throws tmlab::Interrupted. The runner's RunOutput then writes INTERRUPTED with the reason (and a
// checkpoint where the command supports --resume) instead of leaving RUNNING behind. A second
// signal while the first is still pending ends the process at once (the default action), so a
// command that is stuck between safe points can still be stopped.
//
// The recorded signal is the one piece of process-wide state in tmlab: a signal handler can only
// communicate through a volatile sig_atomic_t with static storage (C++17 [support.signal]).
#pragma once

#include "core/base/error.hpp"

#include <memory>
#include <string>

namespace tmlab {

/// Thrown by check_interrupt(): the run was asked to stop by `signal` (SIGINT, SIGTERM).
class Interrupted : public Error {
 public:
  Interrupted(int signal, const std::string& what) : Error(what), signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

/// Installs the SIGINT / SIGTERM handlers for its lifetime and restores the previous ones after.
/// Reads the test stop point TMLAB_TEST_STOP_AFTER_PROGRESS (see note_progress_point); a malformed
/// value is a tmlab::Error naming the variable.
class InterruptHandler {
 public:
  InterruptHandler();
  ~InterruptHandler();
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;

 private:
  struct Saved;  // the handlers to restore
  std::unique_ptr<Saved> saved_;
};

/// The signal received since the handler was installed (0: none).
int pending_interrupt();
/// "SIGINT" / "SIGTERM" / "signal N".
std::string signal_name(int signal);
/// Throws tmlab::Interrupted ("<signal> received <where>") when a signal is pending.
void check_interrupt(const std::string& where);
/// For tests: record `signal` as if it had been delivered (0 clears it).
void set_pending_interrupt(int signal);

/// A deterministic stop point for tests of --resume. Long commands call this after each unit of
/// resumable progress (every checkpoint written, every finished run of a paper figure). When the
/// environment variable TMLAB_TEST_STOP_AFTER_PROGRESS holds "N" or "N:SIGTERM" (read by the
/// InterruptHandler), the N-th call raises SIGINT (or SIGTERM) in this process: the signal goes
/// through the installed handler exactly as one from `kill` would, but at a known point of the run,
/// so a test interrupts a run after its N-th checkpoint without depending on timing. Without the
/// variable (or without an InterruptHandler) it does nothing.
void note_progress_point();

}  // namespace tmlab
