// The stepping of a run: the case's solver (static load stepping, explicit central differences,
// implicit dynamics; with or without contact) advanced from rest, every step recorded, the
// checkpoint written at step boundaries, progress and the stop request checked after each.
#pragma once

#include "core/config/case_config.hpp"
#include "runner/loop_state.hpp"
#include "runner/problem.hpp"
#include "runner/run_checkpoint.hpp"
#include "runner/run_progress.hpp"
#include "runner/step_recorder.hpp"
#include "tensormass/solvers/explicit_dynamics.hpp"

#include <nlohmann/json.hpp>

#include <ostream>

namespace tmlab::tm::runner {

/// Steps the case's solver from rest, recording t = 0 first (a resumed run restores it from the
/// checkpoint); returns the summary's solver block. A case with a `contact` section steps with its
/// rigid bodies (runner/contact_stepping.hpp).
nlohmann::json step(const Problem& p, StepRecorder& rec, std::ostream* log, RunCheckpoint& ck);

/// True when step `k` writes the fields (every output.every steps, and the last step).
bool field_step(const CaseConfig& cfg, int k);

/// The summary's solver block of an explicit run: the step, the stability estimate, the damping.
nlohmann::json explicit_summary(const CaseConfig& cfg, const StabilityEstimate& st);

}  // namespace tmlab::tm::runner
