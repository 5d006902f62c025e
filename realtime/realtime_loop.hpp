// The three asynchronous threads of the paper's Section IV-C on the control model:
//
//   haptic  (haptic_hz, periodic): reads the probe position (a device's position(t), the scripted
//           trajectory at its tick time, or the latest position an interactive source stored),
//           publishes it through a sequence lock, takes the newest control snapshot from a triple
//           buffer if there is one, and computes BOTH couplings (extrapolation and local model),
//           rendering the chosen one (to the device's render(t, F) when there is a device).
//           It never waits for the control thread.
//   control (1/dt model steps per second, paced so that model time never runs ahead of wall
//           time): reads the probe, takes one explicit step, publishes a ContactSnapshot (triple
//           buffer) and the node positions (second triple buffer). When a step takes longer than
//           dt the model falls behind wall time (reported as missed steps and as the lag).
//   visual  (visual_hz, periodic): takes the newest node positions; when recording, copies every
//           `frame_every`-th one into frames reserved before the run.
//
// Hand-over: one SeqLock<ProbeSample> (haptic -> control), TripleBuffer<ContactSnapshot>
// (control -> haptic), TripleBuffer<vector<float>> (control -> visual); no mutex anywhere, no
// allocation inside the loops (logs and timing samples are reserved for the whole run first).
// Each thread records its start lateness (jitter) and busy time per iteration (loop_timing.hpp).
#pragma once

#include "realtime/control_model.hpp"
#include "realtime/haptic_coupling.hpp"
#include "realtime/loop_timing.hpp"
#include "realtime/probe_device.hpp"
#include "realtime/probe_trajectory.hpp"
#include "realtime/seqlock.hpp"

#include <atomic>
#include <functional>
#include <vector>

namespace tmlab::rt {

/// The probe position of one haptic tick (trivially copyable: it crosses a SeqLock).
struct ProbeSample {
  double t = 0.0;
  double x[3] = {0.0, 0.0, 0.0};
};

struct LoopOptions {
  double duration = 1.0;  ///< s of wall time
  double haptic_hz = 1000.0;
  double visual_hz = 40.0;
  CouplingScheme rendered = CouplingScheme::LocalModel;
  /// Probe input, the first one set of: a device (probe_device.hpp: the haptic thread reads its
  /// position and hands it the rendered force every tick), an interactive source (the haptic thread
  /// reads the latest value stored in the sequence lock, e.g. by the --serve page), a scripted
  /// trajectory (its position at the tick time).
  ProbeDevice* device = nullptr;
  const SeqLock<ProbeSample>* interactive = nullptr;
  const ProbeTrajectory* trajectory = nullptr;
  bool keep_frames = false;  ///< keep visual frames (node positions) for offline rendering
  int frame_every = 1;       ///< keep every k-th visual frame
  /// Called by the visual thread with each new frame (positions, rendered force, probe); must not
  /// allocate or block (the --serve server copies into its own triple buffer). May be empty.
  std::function<void(const std::vector<float>&, const Vec3& force, const Vec3& probe)> on_frame;
  /// Called by the loop's own (waiting) thread with 1 once all three threads have done their first
  /// iteration, and with 2 just before the stop is requested (the allocation test counts between
  /// the two). May be empty.
  std::function<void(int)> on_phase;
  /// Stops the loop early when set (may be null).
  const std::atomic<bool>* stop = nullptr;
  /// A pending SIGINT / SIGTERM (core/base/interrupt.hpp) stops the loop too, within one period of
  /// each thread (the waiting thread polls every 5 ms); LoopResult::signal says which.
  bool stop_on_interrupt = true;
  /// Keep the per-tick and per-step logs of LoopResult (false for long interactive runs, whose
  /// logs would need storage for the whole duration reserved up front).
  bool keep_log = true;
  /// Timing samples are reserved for the first `timing_window` seconds (0: the whole duration);
  /// later iterations are counted (rate, missed) but not in the percentiles (`unrecorded`).
  double timing_window = 0.0;
};

struct LoopResult {
  ThreadTiming haptic, control, visual;
  // per haptic tick
  std::vector<double> t;
  std::vector<Vec3> x, extrapolation, local_model;
  // per control step: the probe centre it used and the force on the probe at (u_n, probe)
  std::vector<Vec3> control_probe, control_force;
  double model_time = 0.0;  ///< model time reached, s
  double wall_time = 0.0;   ///< s from the start to the stop of the three threads
  int signal = 0;           ///< the SIGINT / SIGTERM that stopped the loop early (0: none)
  // kept visual frames
  std::vector<std::vector<float>> frames;
  std::vector<double> frame_t;
  std::vector<Vec3> frame_force, frame_probe;
};

/// Runs the loop on `control` (reset here with the probe at its start) for opt.duration seconds.
LoopResult run_realtime_loop(ControlModel& control, const LoopOptions& opt);

}  // namespace tmlab::rt
