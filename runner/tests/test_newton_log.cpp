// NewtonLog: the summary's "solver.newton" block (per-step arrays, the largest iteration count, the
// steps stopped at round-off) and its exact checkpoint round trip.
#include "core/base/error.hpp"
#include "runner/newton_log.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm::runner {
namespace {

NewtonResult solve(int backtracks, double residual, double target, std::vector<double> history) {
  NewtonResult r;
  r.backtracks = backtracks;
  r.residual_final = residual;
  r.target = target;
  r.history = std::move(history);
  return r;
}

NewtonLog two_steps() {
  NewtonLog log;
  log.add(solve(1, 1e-9, 1e-8, {1.0, 1e-3, 1e-9}), 3, 0, 1, false);
  log.add(solve(0, 2e-7, 1e-8, {2.0, 2e-7}), 7, 2, 4, true);
  return log;
}

TEST(NewtonLog, JsonHoldsEveryStepAndTheTotals) {
  SolverSpec s;
  s.rtol = 1e-6;
  s.max_iterations = 25;
  const nlohmann::json j = two_steps().json(s);
  EXPECT_EQ(j["max_iterations_in_a_step"], 7);
  EXPECT_EQ(j["steps_at_roundoff"], 1);
  EXPECT_EQ(j["max_iterations"], 25);
  EXPECT_EQ(j["rtol"], 1e-6);
  EXPECT_EQ(j["linear"], "auto");  // the case's choice; what the solves did: test_linear_solve_log
  const nlohmann::json& p = j["per_step"];
  EXPECT_EQ(p["iterations"], nlohmann::json({3, 7}));
  EXPECT_EQ(p["cutbacks"], nlohmann::json({0, 2}));
  EXPECT_EQ(p["sub_increments"], nlohmann::json({1, 4}));
  EXPECT_EQ(p["backtracks_last_solve"], nlohmann::json({1, 0}));
  EXPECT_EQ(p["residual_final"], nlohmann::json({1e-9, 2e-7}));
  EXPECT_EQ(p["at_roundoff"], nlohmann::json({false, true}));
  EXPECT_EQ(p["residual_history_last_solve"][1], nlohmann::json({2.0, 2e-7}));
}

TEST(NewtonLog, CheckpointRoundTripIsExact) {
  CheckpointData d;
  two_steps().save(d);
  NewtonLog back;
  back.add(solve(9, 9.0, 9.0, {9.0}), 9, 9, 9, true);  // replaced, not appended to
  back.restore(d);
  const SolverSpec s;
  EXPECT_EQ(back.json(s), two_steps().json(s));
}

TEST(NewtonLog, InconsistentHistoryIsRefused) {
  CheckpointData d;
  two_steps().save(d);
  d.put("newton.history_lengths", std::vector<std::int64_t>{3, 5});  // 8 values, 5 stored
  d.set_source("ck.h5");
  NewtonLog back;
  try {
    back.restore(d);
    FAIL() << "an inconsistent history was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ck.h5: inconsistent Newton history"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tmlab::tm::runner
