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

TEST(NewtonLog, LinearSolveCountsCarryAcrossAResume) {
  // The process before the stop: 10 solves, 2 fallbacks, one analysis. Its checkpoint restored in a
  // new process that then does 5 solves (1 fallback, its own analysis of the same pattern): the run
  // reports 15 solves, 3 fallbacks and one analysis, as an uninterrupted run does.
  LinearSolveStats first;
  first.solves = first.cholmod_solves = 10;
  first.cholmod_analyses = 1;
  first.ldlt_analyses = 1;
  first.fallbacks_indefinite = 2;
  first.max_negative_pivots = 7;
  first.fallbacks_by_iteration = {2, 0, 0, 0};
  NewtonLog before = two_steps();
  before.set_linear(first);
  CheckpointData d;
  before.save(d);
  NewtonLog back;
  back.restore(d);
  EXPECT_EQ(back.linear().solves, 10);
  LinearSolveStats second;
  second.solves = 5;
  second.cholmod_solves = 4;
  second.ldlt_solves = 1;
  second.cholmod_analyses = 1;
  second.ldlt_analyses = 1;
  second.fallbacks_indefinite = 1;
  second.max_negative_pivots = 3;
  second.fallbacks_by_iteration = {0, 0, 1, 0};
  back.set_linear(second);
  const LinearSolveStats t = back.linear();
  EXPECT_EQ(t.solves, 15);
  EXPECT_EQ(t.cholmod_solves, 14);
  EXPECT_EQ(t.ldlt_solves, 1);
  EXPECT_EQ(t.cholmod_analyses, 1);
  EXPECT_EQ(t.fallbacks_indefinite, 3);
  EXPECT_EQ(t.max_negative_pivots, 7);
  EXPECT_EQ(t.fallbacks_by_iteration, (std::vector<long>{2, 0, 1, 0}));
  // A checkpoint without the counts (written before they existed) restores with none.
  CheckpointData old;
  two_steps().save(old);
  CheckpointData stripped;
  for (const char* k : {"newton.iterations", "newton.cutbacks", "newton.sub_increments", "newton.backtracks",
                        "newton.roundoff", "newton.history_lengths"})
    stripped.put(k, old.ints(k));
  for (const char* k : {"newton.residual", "newton.target", "newton.history"})
    stripped.put(k, old.doubles(k));
  NewtonLog from_old;
  from_old.restore(stripped);
  EXPECT_EQ(from_old.linear().solves, 0);
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
