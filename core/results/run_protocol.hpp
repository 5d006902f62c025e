// One run under the result protocol (issue 27): the manifest, the computation, the checkpoint
// removed (a complete result holds none), summary.json last; on a stop request (tmlab::Interrupted)
// INTERRUPTED with where the checkpoint is, on any other error FAILED, and the exception passed on.
// The commands that compute into a RunOutput run through it (tmlab run's run_case, fit, discover,
// discover --benchmark, paper, hereditary, workprecision, depth-limit, bench, realtime --record), so
// the order of these steps is written once. Two keep their own order, each saying why: verify (its
// checkpoint lives beside the report and goes only after the report is final) and compare (its
// manifest names the two runs' folders, known only after they ran).
#pragma once

#include "core/base/interrupt.hpp"
#include "core/results/run_output.hpp"

#include <nlohmann/json.hpp>

#include <functional>

namespace tmlab {

class UnitCheckpoint;

/// What the protocol does with a command's checkpoint: remove it when the result is complete, and
/// at a stop turn the Interrupted into one that says where it is (both optional).
struct ProtocolCheckpoint {
  std::function<void()> remove;
  std::function<Interrupted(const Interrupted&)> stopped;
};
/// The hooks of a UnitCheckpoint (unit_checkpoint.hpp).
ProtocolCheckpoint protocol_checkpoint(UnitCheckpoint& ck);

/// Writes manifest.json from `manifest`, runs `compute` (which writes the result files into `out`
/// and returns the summary), removes the checkpoint and finalises `out` with the summary. When
/// anything throws: tmlab::Interrupted -> `ck.stopped` (when given), out.abandon (INTERRUPTED), the
/// stopped exception rethrown; any other std::exception -> out.abandon (FAILED), rethrown.
void run_with_protocol(RunOutput& out, const ManifestInput& manifest,
                       const std::function<nlohmann::json()>& compute, const ProtocolCheckpoint& ck = {});

}  // namespace tmlab
