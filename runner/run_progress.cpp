// The progress of a run's steps: see run_progress.hpp.
#include "runner/run_progress.hpp"

#include "core/base/interrupt.hpp"

#include <string>

namespace tmlab::tm::runner {

Progress::Progress(const CaseConfig& cfg, std::ostream* log) : n_steps_(cfg.solver.steps) {
  if (!log) return;
  ProgressOptions po;
  po.label = cfg.name;
  reporter_ = std::make_unique<ProgressReporter>(n_steps_, po);
}

void Progress::operator()(int step, double t) {
  if (reporter_) reporter_->update(step, t);
  check_interrupt("at t = " + std::to_string(t) + " s (step " + std::to_string(step) + " of " +
                  std::to_string(n_steps_) + ")");
}

void Progress::finish() {
  if (reporter_) reporter_->finish();
}

}  // namespace tmlab::tm::runner
