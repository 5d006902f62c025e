// The stepping of a case with a `contact` section (docs/contact.md): the same loops as
// runner/stepping.hpp with the case's rigid bodies. Each sets up its contact object (surface and
// grid built once, the rig checked against the mesh), records t = 0 (unless resuming) and steps;
// the contact state changes only inside the solver's accepted steps.
#pragma once

#include "runner/loop_state.hpp"
#include "runner/problem.hpp"
#include "runner/run_checkpoint.hpp"
#include "runner/run_progress.hpp"
#include "runner/step_recorder.hpp"

#include <nlohmann/json.hpp>

namespace tmlab::tm::runner {

/// Steps a case with a `contact` section: static (augmented Lagrangian or penalty around the static
/// Newton), explicit (kinematic contact) or implicit (the augmented-Lagrangian loop around the
/// implicit Newton solve). Returns the summary's solver block with its "contact" block.
nlohmann::json step_contact(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                            RunCheckpoint& ck);

}  // namespace tmlab::tm::runner
