// SIGINT / SIGTERM become a pending request that check_interrupt() turns into tmlab::Interrupted
// at a safe point; the handler is removed again when its InterruptHandler goes.
#include "core/base/interrupt.hpp"

#include <gtest/gtest.h>

#include <csignal>

TEST(Interrupt, SignalBecomesPendingAndCheckThrows) {
  const tmlab::InterruptHandler handler;
  EXPECT_EQ(tmlab::pending_interrupt(), 0);
  EXPECT_NO_THROW(tmlab::check_interrupt("at step 1"));
  std::raise(SIGTERM);  // handled: the process goes on
  EXPECT_EQ(tmlab::pending_interrupt(), SIGTERM);
  try {
    tmlab::check_interrupt("at step 2 of 10");
    FAIL() << "expected tmlab::Interrupted";
  } catch (const tmlab::Interrupted& e) {
    EXPECT_EQ(e.signal(), SIGTERM);
    EXPECT_EQ(std::string(e.what()), "SIGTERM received at step 2 of 10");
  }
  tmlab::set_pending_interrupt(0);
}

TEST(Interrupt, SecondSignalEndsTheProcess) {
  // The first signal is only recorded; a second one before any safe point takes the default action.
  EXPECT_EXIT(
      {
        const tmlab::InterruptHandler handler;
        std::raise(SIGINT);
        std::raise(SIGINT);
        std::_Exit(0);  // not reached
      },
      ::testing::KilledBySignal(SIGINT), "");
}

TEST(Interrupt, Names) {
  EXPECT_EQ(tmlab::signal_name(SIGINT), "SIGINT");
  EXPECT_EQ(tmlab::signal_name(SIGTERM), "SIGTERM");
  EXPECT_EQ(tmlab::signal_name(SIGUSR1), "signal " + std::to_string(SIGUSR1));
}
