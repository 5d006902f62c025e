// Progress: the safe point after each recorded step throws tmlab::Interrupted when a stop was
// requested, saying where the run stopped; without a request it lets the run go on.
#include "core/base/interrupt.hpp"
#include "runner/run_progress.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <sstream>
#include <string>

namespace tmlab::tm::runner {
namespace {

class RunProgressTest : public ::testing::Test {
 protected:
  void TearDown() override { set_pending_interrupt(0); }
};

CaseConfig four_steps() {
  CaseConfig cfg;
  cfg.name = "progress";
  cfg.solver.steps = 4;
  return cfg;
}

TEST_F(RunProgressTest, NoStopRequestLetsTheRunGoOn) {
  const CaseConfig cfg = four_steps();
  std::ostringstream log;
  Progress progress(cfg, &log);
  for (int k = 1; k <= 4; ++k) EXPECT_NO_THROW(progress(k, 0.25 * k));
  progress.finish();
}

TEST_F(RunProgressTest, AStopRequestThrowsInterruptedNamingTheStep) {
  const CaseConfig cfg = four_steps();
  Progress progress(cfg, nullptr);  // no log: no progress line, the safe point all the same
  progress(1, 0.25);
  set_pending_interrupt(SIGTERM);
  try {
    progress(3, 0.75);
    FAIL() << "a pending SIGTERM did not stop the run";
  } catch (const Interrupted& e) {
    EXPECT_EQ(e.signal(), SIGTERM);
    EXPECT_NE(std::string(e.what()).find("(step 3 of 4)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("at t = 0.75"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tmlab::tm::runner
