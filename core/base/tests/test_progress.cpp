// ProgressReporter: terminal mode throttles by time, log mode prints every 10%.
#include "core/base/progress.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

namespace {

using Clock = tmlab::ProgressReporter::Clock;
using std::chrono::milliseconds;

long count(const std::string& s, char c) { return static_cast<long>(std::count(s.begin(), s.end(), c)); }

TEST(Progress, LogModePrintsEveryTenPercent) {
  std::ostringstream out;
  const Clock::time_point t0{};
  tmlab::ProgressReporter p(1000, out, false, {}, t0);
  for (long k = 1; k <= 1000; ++k) p.update(k, 1e-3 * k, t0 + milliseconds(k));
  p.finish(t0 + milliseconds(1000));
  EXPECT_EQ(count(out.str(), '\n'), 10) << out.str();
  EXPECT_NE(out.str().find("step 1000/1000 (100%)"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("step 500/1000 (50%)"), std::string::npos);
}

TEST(Progress, LogModeFinishPrintsAbortedState) {
  std::ostringstream out;
  const Clock::time_point t0{};
  tmlab::ProgressReporter p(100, out, false, {}, t0);
  for (long k = 1; k <= 37; ++k) p.update(k, 0.0, t0 + milliseconds(10 * k));
  p.finish(t0 + milliseconds(400));
  EXPECT_EQ(count(out.str(), '\n'), 4);  // 10, 20, 30 %, then the final 37
  EXPECT_NE(out.str().find("step 37/100"), std::string::npos);
}

TEST(Progress, TtyModeThrottlesToInterval) {
  std::ostringstream out;
  const Clock::time_point t0{};
  tmlab::ProgressReporter p(10000, out, true, {}, t0);
  // 10000 updates spread over 2 s: at 0.0002 s, then one per 0.5 s (0.5002, 1.0002, 1.5002).
  for (long k = 1; k <= 10000; ++k) p.update(k, 0.0, t0 + std::chrono::microseconds(200 * k));
  p.finish(t0 + milliseconds(2000));
  EXPECT_EQ(count(out.str(), '\r'), 4 + 1) << out.str();
  EXPECT_EQ(out.str().back(), '\n');
}

TEST(Progress, StatusShowsRateAndEta) {
  std::ostringstream out;
  const Clock::time_point t0{};
  tmlab::ProgressReporter::Options opt;
  opt.label = "cube";
  tmlab::ProgressReporter p(1000, out, false, opt, t0);
  const std::string s = p.status(100, 0.5, t0 + std::chrono::seconds(10));
  EXPECT_NE(s.find("[cube] step 100/1000 (10%)"), std::string::npos) << s;
  EXPECT_NE(s.find("10 steps/s"), std::string::npos) << s;
  EXPECT_NE(s.find("ETA 1:30"), std::string::npos) << s;
  EXPECT_NE(p.status(0, 0.0, t0).find("ETA ?"), std::string::npos);
}

}  // namespace
