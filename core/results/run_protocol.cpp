// One run under the result protocol: see run_protocol.hpp.
#include "core/results/run_protocol.hpp"

#include "core/results/unit_checkpoint.hpp"

namespace tmlab {

ProtocolCheckpoint protocol_checkpoint(UnitCheckpoint& ck) {
  return {[&ck] { ck.remove(); }, [&ck](const Interrupted& e) { return ck.stopped(e); }};
}

void run_with_protocol(RunOutput& out, const ManifestInput& manifest,
                       const std::function<nlohmann::json()>& compute, const ProtocolCheckpoint& ck) {
  try {
    out.write_json("manifest.json", make_manifest(manifest));
    const nlohmann::json summary = compute();
    if (ck.remove) ck.remove();  // a complete result holds no checkpoint
    out.finalize(summary);
  } catch (const Interrupted& e) {
    const Interrupted stopped = ck.stopped ? ck.stopped(e) : e;
    out.abandon(stopped);
    throw stopped;
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
}

}  // namespace tmlab
