// The progress of a run's steps: the progress line (when there is a log) and, after every
// recorded step, the safe point at which SIGINT/SIGTERM stop the run.
#pragma once

#include "core/base/progress.hpp"
#include "core/config/case_config.hpp"

#include <memory>
#include <ostream>

namespace tmlab::tm::runner {

/// After every recorded step: progress, and a safe point at which SIGINT/SIGTERM stop the run.
class Progress {
 public:
  /// A progress line of cfg.solver.steps steps labelled with the case name when `log` is given.
  Progress(const CaseConfig& cfg, std::ostream* log);
  /// Reports step `step` at time `t`; throws tmlab::Interrupted ("... at t = <t> s (step k of n)")
  /// when a stop was requested.
  void operator()(int step, double t);
  void finish();

 private:
  int n_steps_;
  std::unique_ptr<ProgressReporter> reporter_;
};

}  // namespace tmlab::tm::runner
