// SIGINT / SIGTERM become a pending request that check_interrupt() turns into tmlab::Interrupted
// at a safe point; the handler is removed again when its InterruptHandler goes.
#include "core/base/interrupt.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>

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

TEST(Interrupt, TestStopPointRaisesAtTheNthProgressPoint) {
  ::setenv("TMLAB_TEST_STOP_AFTER_PROGRESS", "3:SIGTERM", 1);
  {
    const tmlab::InterruptHandler handler;
    tmlab::note_progress_point();
    tmlab::note_progress_point();
    EXPECT_EQ(tmlab::pending_interrupt(), 0);
    tmlab::note_progress_point();  // the third: raised through the handler
    EXPECT_EQ(tmlab::pending_interrupt(), SIGTERM);
    tmlab::note_progress_point();  // only once: a second raise would end the process
    EXPECT_EQ(tmlab::pending_interrupt(), SIGTERM);
    tmlab::set_pending_interrupt(0);
  }
  ::unsetenv("TMLAB_TEST_STOP_AFTER_PROGRESS");
  const tmlab::InterruptHandler handler;  // without the variable: never
  for (int i = 0; i < 5; ++i) tmlab::note_progress_point();
  EXPECT_EQ(tmlab::pending_interrupt(), 0);
}

TEST(Interrupt, MalformedTestStopPointIsRefusedNamingTheVariable) {
  for (const char* bad : {"0", "x", "2:SIGKILL", "-1", "3:"}) {
    ::setenv("TMLAB_TEST_STOP_AFTER_PROGRESS", bad, 1);
    try {
      const tmlab::InterruptHandler handler;
      ADD_FAILURE() << bad << " accepted";
    } catch (const tmlab::Error& e) {
      EXPECT_NE(std::string(e.what()).find("TMLAB_TEST_STOP_AFTER_PROGRESS"), std::string::npos) << e.what();
    }
  }
  ::unsetenv("TMLAB_TEST_STOP_AFTER_PROGRESS");
}
