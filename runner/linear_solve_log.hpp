// What the Newton steps' linear solves of a run did: summary.json's "solver.linear_solver" block.
#pragma once

#include "core/config/case_config.hpp"
#include "tensormass/solvers/newton.hpp"

#include <nlohmann/json.hpp>

namespace tmlab::tm::runner {

/// The NewtonOptions::linear_solver of a case's solver.linear: auto and cholmod are CHOLMOD with
/// the LDL^T fallback, ldlt Eigen's LDL^T.
NewtonLinearSolver newton_linear_solver(SolverSpec::Linear linear);

/// summary.json's "solver.linear_solver": the case's choice (`kind`), the solves by solver, the
/// symbolic analyses (one per sparsity pattern), the fallbacks to LDL^T by reason (indefinite:
/// negative pivots in LDL^T; round_off: none) and by Newton iteration, and, when there were
/// fallbacks, a `note` saying what they mean. `stats`: the run's counts (NewtonLog::linear(), which
/// carries them across a resume).
nlohmann::json linear_solver_json(const SolverSpec& s, const LinearSolveStats& stats);

}  // namespace tmlab::tm::runner
