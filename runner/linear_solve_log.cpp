// What the Newton steps' linear solves of a run did: see linear_solve_log.hpp.
#include "runner/linear_solve_log.hpp"

#include <string>

namespace tmlab::tm::runner {

NewtonLinearSolver newton_linear_solver(SolverSpec::Linear linear) {
  return linear == SolverSpec::Linear::Ldlt ? NewtonLinearSolver::Direct : NewtonLinearSolver::Cholmod;
}

nlohmann::json linear_solver_json(const SolverSpec& s, const LinearSolveStats& st) {
  nlohmann::json j = {
      {"kind", to_string(s.linear)},
      {"solves", st.solves},
      {"solves_by", {{"cholmod", st.cholmod_solves}, {"ldlt", st.ldlt_solves}, {"lu", st.lu_solves}}},
      {"symbolic_analyses",
       {{"cholmod", st.cholmod_analyses}, {"ldlt", st.ldlt_analyses}, {"lu", st.lu_analyses}}},
      {"fallbacks_to_ldlt", st.fallbacks()},
      {"fallbacks", {{"indefinite", st.fallbacks_indefinite}, {"round_off", st.fallbacks_round_off}}},
      {"fallbacks_by_newton_iteration", st.fallbacks_by_iteration},
      {"max_negative_pivots", st.max_negative_pivots}};
  if (st.fallbacks() > 0) {
    const auto& by = st.fallbacks_by_iteration;
    std::string its;
    for (std::size_t k = 0; k < by.size(); ++k)
      its += (k ? ", " : "") + std::to_string(by[k]) + " at iteration " + std::to_string(k + 1) +
             (k + 1 == by.size() ? " or later" : "");
    j["note"] = std::to_string(st.fallbacks()) + " of " + std::to_string(st.solves) +
                " solves met a tangent that is not positive definite, where CHOLMOD's LL^T does not exist, "
                "and were solved by LDL^T: " +
                std::to_string(st.fallbacks_indefinite) + " indefinite (up to " +
                std::to_string(st.max_negative_pivots) + " negative eigenvalues), " +
                std::to_string(st.fallbacks_round_off) + " positive definite to round-off; " + its +
                " of a Newton solve. Contact with a curved body far from equilibrium is the usual cause "
                "(docs/theory/newton.md, \"Linear solves\")";
  }
  return j;
}

}  // namespace tmlab::tm::runner
