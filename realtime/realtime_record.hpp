// `tmlab realtime CASE --record`: one offscreen run of the threaded loop with the case's scripted
// probe, then the measurements (docs/realtime.md):
//   - timing per thread (haptic, control, visual): target_hz, rate_hz, p50_us, p99_us, p999_us,
//     missed (and the busy-time percentiles);
//   - per coupling scheme: haptic_force_error_rel and coupling_energy_J of the deterministic
//     coupling study (control at the case's study_control_hz against the ground truth at the
//     haptic rate: reproducible), and the same two measures of the live run (live_*: the forces
//     the haptic thread computed against the ground truth replayed on the probe path it read);
//   - PNG frames (frame_renderer.hpp) of every png_every-th visual frame and forces.csv.
#pragma once

#include "realtime/loop_timing.hpp"
#include "realtime/realtime_case.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <string>

namespace tmlab::rt {

struct RecordOptions {
  double duration = 0.0;  ///< s; 0: the case's
  bool frames = true;     ///< write PNG frames
  std::function<void(const std::string&)> log;
};

/// Runs and measures; writes frames/, forces.csv and timing.json into `dir`; returns the timing
/// document (also the summary's content).
nlohmann::json record_realtime(const RealtimeCase& c, const RecordOptions& opt,
                               const std::filesystem::path& dir);

/// The timing block of one thread as JSON.
nlohmann::json to_json(const ThreadTiming& t);

}  // namespace tmlab::rt
