#include "realtime/realtime_loop.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "realtime/triple_buffer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

namespace tmlab::rt {

namespace {

using Clock = std::chrono::steady_clock;

double us(Clock::duration d) { return std::chrono::duration<double, std::micro>(d).count(); }
Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}
Vec3 to_vec(const ProbeSample& p) { return {p.x[0], p.x[1], p.x[2]}; }

/// The result with its logs and frames reserved for the whole run (the loops never allocate).
LoopResult reserved_result(const LoopOptions& opt, std::size_t n_haptic, std::size_t n_control,
                           std::size_t n_visual, std::size_t n_dofs) {
  LoopResult r;
  if (opt.keep_log) {
    for (auto* v : {&r.x, &r.extrapolation, &r.local_model}) v->reserve(n_haptic);
    r.t.reserve(n_haptic);
    r.control_probe.reserve(n_control);
    r.control_force.reserve(n_control);
  }
  const std::size_t n_frames =
      opt.keep_frames ? n_visual / static_cast<std::size_t>(std::max(1, opt.frame_every)) + 2 : 0;
  r.frames.assign(n_frames, std::vector<float>(n_dofs));
  r.frame_t.reserve(n_frames);
  r.frame_force.reserve(n_frames);
  r.frame_probe.reserve(n_frames);
  return r;
}

}  // namespace

LoopResult run_realtime_loop(ControlModel& control, const LoopOptions& opt) {
  if (!opt.device && !opt.trajectory && !opt.interactive) throw Error("realtime loop: no probe input");
  if (!(opt.duration > 0.0) || !(opt.haptic_hz > 0.0) || !(opt.visual_hz > 0.0))
    throw Error("realtime loop: duration and rates must be > 0");
  const double th = 1.0 / opt.haptic_hz, tv = 1.0 / opt.visual_hz, dt = control.dt();
  const auto probe_at = [&](double t) {
    if (opt.device) return opt.device->position(t);
    return opt.interactive ? to_vec(opt.interactive->load()) : opt.trajectory->position(t);
  };
  const Vec3 x0 = probe_at(0.0);
  control.reset(x0);

  // Everything the loops touch, sized before they start.
  const std::size_t n_haptic = static_cast<std::size_t>(std::ceil(opt.duration * opt.haptic_hz)) + 16;
  const std::size_t n_control = static_cast<std::size_t>(std::ceil(opt.duration / dt)) + 16;
  const std::size_t n_visual = static_cast<std::size_t>(std::ceil(opt.duration * opt.visual_hz)) + 16;
  const std::size_t n_dofs = 3 * static_cast<std::size_t>(control.mesh().num_points());
  LoopResult r = reserved_result(opt, n_haptic, n_control, n_visual, n_dofs);
  const double window = opt.timing_window > 0.0 ? std::min(opt.timing_window, opt.duration) : opt.duration;
  const auto timing_samples = [&](std::size_t n, double hz) {
    return std::min(n, static_cast<std::size_t>(std::ceil(window * hz)) + 16);
  };
  LoopTiming haptic_timing(timing_samples(n_haptic, opt.haptic_hz)),
      control_timing(timing_samples(n_control, 1.0 / dt)),
      visual_timing(timing_samples(n_visual, opt.visual_hz));

  SeqLock<ProbeSample> probe(ProbeSample{0.0, {x0.x(), x0.y(), x0.z()}});
  SeqLock<ProbeSample> rendered_force;  // haptic -> visual (the force shown), t unused
  TripleBuffer<ContactSnapshot> snapshots;
  std::vector<float> proto(n_dofs);
  control.positions(proto.data());
  TripleBuffer<std::vector<float>> surface(proto);
  std::atomic<bool> stop{false};
  std::atomic<int> warm{0};
  const auto start = Clock::now() + std::chrono::milliseconds(20);  // all threads up before t = 0
  const auto end = start + seconds(opt.duration);
  std::size_t frames_kept = 0;
  const auto stopping = [&] {
    return stop.load(std::memory_order_relaxed) || (opt.stop && opt.stop->load());
  };
  // The waiting thread turns a pending SIGINT / SIGTERM into the stop (the handler only records it).
  const auto signalled = [&] {
    if (opt.stop_on_interrupt && r.signal == 0) r.signal = pending_interrupt();
    return r.signal != 0;
  };

  std::thread haptic([&] {
    ExtrapolationCoupling extrapolation;
    LocalModelCoupling local;
    for (long k = 0;; ++k) {
      const auto deadline = start + seconds(static_cast<double>(k) * th);
      if (deadline >= end || stopping()) break;
      std::this_thread::sleep_until(deadline);
      const auto wake = Clock::now();
      const double t = static_cast<double>(k) * th;
      const Vec3 x = probe_at(t);
      probe.store(ProbeSample{t, {x.x(), x.y(), x.z()}});
      if (snapshots.update()) {
        extrapolation.on_snapshot(snapshots.read_buffer());
        local.on_snapshot(snapshots.read_buffer());
      }
      const Vec3 fe = extrapolation.force(t, x), fl = local.force(t, x);
      const Vec3 f = opt.rendered == CouplingScheme::Extrapolation ? fe : fl;
      if (opt.device) opt.device->render(t, f);
      rendered_force.store(ProbeSample{t, {f.x(), f.y(), f.z()}});
      if (r.t.size() < r.t.capacity()) {
        r.t.push_back(t);
        r.x.push_back(x);
        r.extrapolation.push_back(fe);
        r.local_model.push_back(fl);
      }
      const auto done = Clock::now();
      if (k > 0) haptic_timing.record(us(wake - deadline), us(done - wake), done > deadline + seconds(th));
      if (k == 0) warm.fetch_add(1);
    }
  });

  std::thread ctl([&] {
    for (long n = 0;; ++n) {
      const auto scheduled = start + seconds(static_cast<double>(n) * dt);
      if (scheduled >= end || stopping()) break;
      std::this_thread::sleep_until(scheduled);  // model time never ahead of wall time
      const auto wake = Clock::now();
      const Vec3 c = to_vec(probe.load());
      const Vec3 f = control.step(c);
      control.fill_snapshot(c, snapshots.write_buffer());
      snapshots.publish();
      control.positions(surface.write_buffer().data());
      surface.publish();
      if (r.control_probe.size() < r.control_probe.capacity()) {
        r.control_probe.push_back(c);
        r.control_force.push_back(f);
      }
      const auto done = Clock::now();
      if (n > 0) control_timing.record(us(wake - scheduled), us(done - wake), done > scheduled + seconds(dt));
      if (n == 0) warm.fetch_add(1);
    }
  });

  std::thread visual([&] {
    for (long k = 0;; ++k) {
      const auto deadline = start + seconds(static_cast<double>(k) * tv);
      if (deadline >= end || stopping()) break;
      std::this_thread::sleep_until(deadline);
      const auto wake = Clock::now();
      surface.update();
      const std::vector<float>& pos = surface.read_buffer();
      const ProbeSample pf = rendered_force.load(), pp = probe.load();
      if (opt.on_frame) opt.on_frame(pos, to_vec(pf), to_vec(pp));
      if (opt.keep_frames && k % std::max(1, opt.frame_every) == 0 && frames_kept < r.frames.size()) {
        std::copy(pos.begin(), pos.end(), r.frames[frames_kept].begin());
        r.frame_t.push_back(static_cast<double>(k) * tv);
        r.frame_force.push_back(to_vec(pf));
        r.frame_probe.push_back(to_vec(pp));
        ++frames_kept;
      }
      const auto done = Clock::now();
      if (k > 0) visual_timing.record(us(wake - deadline), us(done - wake), done > deadline + seconds(tv));
      if (k == 0) warm.fetch_add(1);
    }
  });

  // Main thread: report the phases for the allocation test, then wait for the end.
  while (warm.load() < 3 && Clock::now() < end && !stopping() && !signalled())
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  if (opt.on_phase) opt.on_phase(1);
  while (Clock::now() < end && !stopping() && !signalled())
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  if (opt.on_phase) opt.on_phase(2);
  stop = true;
  haptic.join();
  ctl.join();
  visual.join();
  const double elapsed = std::max(0.0, std::chrono::duration<double>(Clock::now() - start).count());
  r.frames.resize(frames_kept);
  r.haptic = haptic_timing.summary("haptic", opt.haptic_hz, elapsed);
  r.control = control_timing.summary("control", 1.0 / dt, elapsed);
  r.visual = visual_timing.summary("visual", opt.visual_hz, elapsed);
  r.model_time = control.time();
  r.wall_time = elapsed;
  return r;
}

}  // namespace tmlab::rt
