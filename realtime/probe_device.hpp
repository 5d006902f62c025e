// The probe-input API of the real-time loop: what a haptic device driver implements to put a real
// device in the loop in place of the scripted trajectory or the web page (docs/realtime.md, "A
// haptic device").
//
// The haptic thread is the device's servo loop. Once per haptic tick, at loop time t (s, 0 at the
// start of the run, advancing by 1/haptic_hz), it calls
//   position(t)           the probe centre now (m, in the mesh frame), then, after the coupling,
//   render(t, force)      the force the tissue exerts on the probe (N, mesh frame): the force the
//                         device should push the hand with (the rendered coupling,
//                         LoopOptions::rendered).
// Both are called from the haptic thread only, every tick, in that order, and must neither block
// (no mutex, no blocking I/O, no sleep) nor allocate: a late return is a missed haptic deadline.
// position(0.0) is also called once on the thread that starts the loop, before the threads run,
// for the probe's start.
//
// The driver owns the mapping between the device and the mesh frame (workspace scale and offset,
// axes), keeps the probe where the model can take it (probe_box() of live_protocol.hpp: the mesh's
// bounding box grown by two probe radii is what the web page is clamped to), and scales and caps
// the force to what the device can render. The loop never calls a device after
// run_realtime_loop returns.
#pragma once

#include "core/mesh/mesh.hpp"

namespace tmlab::rt {

using tmlab::Vec3;

class ProbeDevice {
 public:
  virtual ~ProbeDevice() = default;
  /// The probe centre at loop time t (s), m, mesh frame. Haptic thread; no blocking, no allocation.
  virtual Vec3 position(double t) = 0;
  /// The force of the tissue on the probe at loop time t, N, mesh frame. Haptic thread; no blocking,
  /// no allocation.
  virtual void render(double t, const Vec3& force) = 0;
};

}  // namespace tmlab::rt
