// The Newton iteration history of a run, one entry per step: summary.json's "solver.newton" block
// and its part of the run's checkpoint (runner/run_checkpoint.hpp).
#pragma once

#include "core/config/case_config.hpp"
#include "core/results/checkpoint.hpp"
#include "tensormass/solvers/newton.hpp"

#include <nlohmann/json.hpp>

#include <vector>

namespace tmlab::tm::runner {

/// The iteration history of a run, one entry per step, for summary.json ("solver.newton"):
/// iterations, cut-backs, sub-increments, backtracks, the final |R| and its target, whether the
/// step stopped at round-off, and the residual history of the last (sub-)increment.
class NewtonLog {
 public:
  /// One step: `last` is the final (sub-)increment's solve.
  void add(const NewtonResult& last, int iterations, int cutbacks, int sub_increments, bool at_roundoff);
  /// The history as checkpoint entries "newton.*", and back (an inconsistent history throws
  /// tmlab::Error naming the file).
  void save(CheckpointData& d) const;
  void restore(const CheckpointData& d);
  /// The linear solves are the "solver.linear_solver" block's (runner/linear_solve_log.hpp).
  nlohmann::json json(const SolverSpec& s) const;

  /// The linear solver's counts after a step (ConstrainedLinearSolver::stats() of this process).
  void set_linear(const LinearSolveStats& process) { process_ = process; }
  /// The run's counts: those of the processes before a resume (from the checkpoint) plus this
  /// one's; symbolic analyses and negative pivots the largest of them (a resumed process analyses
  /// its pattern again: the factorisation is not checkpointed), so a resumed run reports what an
  /// uninterrupted one does.
  LinearSolveStats linear() const;

 private:
  std::vector<int> iterations_, cutbacks_, sub_increments_, backtracks_;
  std::vector<double> residual_, target_;
  std::vector<bool> roundoff_;
  std::vector<std::vector<double>> history_;
  LinearSolveStats before_, process_;  ///< counts restored from the checkpoint; this process's
};

}  // namespace tmlab::tm::runner
