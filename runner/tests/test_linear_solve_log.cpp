// The summary's "solver.linear_solver" block: the case's choice, the solves by solver, the symbolic
// analyses, the fallbacks by reason and iteration and their note; and the case's choice as the Newton
// linear solver. The counts themselves come from ConstrainedLinearSolver (test_newton); a run's
// block: test_case_runner_contact.
#include "runner/linear_solve_log.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm::runner {
namespace {

TEST(LinearSolveLog, CaseChoiceGivesTheNewtonLinearSolver) {
  EXPECT_EQ(newton_linear_solver(SolverSpec::Linear::Auto), NewtonLinearSolver::Cholmod);
  EXPECT_EQ(newton_linear_solver(SolverSpec::Linear::Cholmod), NewtonLinearSolver::Cholmod);
  EXPECT_EQ(newton_linear_solver(SolverSpec::Linear::Ldlt), NewtonLinearSolver::Direct);
  EXPECT_EQ(newton_linear_solver(SolverSpec{}.linear), NewtonLinearSolver::Cholmod);  // the default
}

TEST(LinearSolveLog, JsonCountsSolvesAnalysesAndFallbacksByReason) {
  LinearSolveStats st;
  st.solves = 12;
  st.cholmod_solves = 9;
  st.ldlt_solves = 3;
  st.cholmod_analyses = 1;
  st.ldlt_analyses = 1;
  st.fallbacks_indefinite = 2;
  st.fallbacks_round_off = 1;
  st.max_negative_pivots = 5;
  st.fallbacks_by_iteration = {2, 1, 0, 0};
  const nlohmann::json j = linear_solver_json(SolverSpec{}, st);
  EXPECT_EQ(j["kind"], "auto");
  EXPECT_EQ(j["solves"], 12);
  EXPECT_EQ(j["solves_by"], nlohmann::json({{"cholmod", 9}, {"ldlt", 3}, {"lu", 0}}));
  EXPECT_EQ(j["symbolic_analyses"], nlohmann::json({{"cholmod", 1}, {"ldlt", 1}, {"lu", 0}}));
  EXPECT_EQ(j["fallbacks_to_ldlt"], 3);
  EXPECT_EQ(j["fallbacks"], nlohmann::json({{"indefinite", 2}, {"round_off", 1}}));
  EXPECT_EQ(j["fallbacks_by_newton_iteration"], nlohmann::json({2, 1, 0, 0}));
  EXPECT_EQ(j["max_negative_pivots"], 5);
  const std::string note = j.at("note");
  for (const char* part :
       {"3 of 12 solves", "2 indefinite (up to 5 negative eigenvalues)", "1 positive definite to round-off",
        "2 at iteration 1, 1 at iteration 2", "0 at iteration 4 or later", "docs/theory/newton.md"})
    EXPECT_NE(note.find(part), std::string::npos) << part << " in: " << note;

  // No fallback: no note.
  SolverSpec ldlt;
  ldlt.linear = SolverSpec::Linear::Ldlt;
  LinearSolveStats clean;
  clean.solves = clean.ldlt_solves = 4;
  const nlohmann::json k = linear_solver_json(ldlt, clean);
  EXPECT_EQ(k["kind"], "ldlt");
  EXPECT_EQ(k["fallbacks_to_ldlt"], 0);
  EXPECT_FALSE(k.contains("note"));
}

}  // namespace
}  // namespace tmlab::tm::runner
