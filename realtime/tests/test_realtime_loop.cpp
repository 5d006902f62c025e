// The threaded loop (issue 17, tests 1 and 3): a scripted poke run through the three threads gives
// the same contact force history as the offline model replayed on the probe positions the control
// thread read (bit for bit: the hand-over corrupts nothing), each thread reports its timing, and no
// thread allocates once all three are running (a counting operator new) nor takes a lock (counting
// replacements of the pthread mutex and rwlock entry points, which std::mutex, std::shared_mutex
// and friends go through: a canary shows a std::mutex is counted). A probe device
// (probe_device.hpp) is read and handed the rendered force on every haptic tick, without
// allocating. No timing assertion: the machine may be busy.
#include "core/base/interrupt.hpp"
#include "realtime/coupling_study.hpp"
#include "realtime/realtime_case.hpp"
#include "realtime/realtime_loop.hpp"

#include <gtest/gtest.h>

#include <dlfcn.h>
#include <pthread.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <mutex>
#include <new>
#include <shared_mutex>

namespace {
std::atomic<long> g_allocations{0};
std::atomic<long> g_locks{0};
}  // namespace

// Counting lock entry points for this test executable only: the executable's definitions come
// first in the dynamic lookup, so every pthread mutex / rwlock acquisition in the process (from
// libstdc++'s std::mutex and std::shared_mutex too) lands here, then in glibc's own implementation
// (looked up with dlsym(RTLD_NEXT) once, before main; again if a lock is taken before that).
namespace {
using MutexFn = int (*)(pthread_mutex_t*);
using RwlockFn = int (*)(pthread_rwlock_t*);
struct RealLocks {
  MutexFn lock, trylock;
  RwlockFn rdlock, wrlock;
};
RealLocks resolve_real_locks() {
  return {reinterpret_cast<MutexFn>(dlsym(RTLD_NEXT, "pthread_mutex_lock")),
          reinterpret_cast<MutexFn>(dlsym(RTLD_NEXT, "pthread_mutex_trylock")),
          reinterpret_cast<RwlockFn>(dlsym(RTLD_NEXT, "pthread_rwlock_rdlock")),
          reinterpret_cast<RwlockFn>(dlsym(RTLD_NEXT, "pthread_rwlock_wrlock"))};
}
const RealLocks g_real = resolve_real_locks();
}  // namespace

extern "C" {
int pthread_mutex_lock(pthread_mutex_t* m) {
  g_locks.fetch_add(1, std::memory_order_relaxed);
  return (g_real.lock ? g_real.lock : resolve_real_locks().lock)(m);
}
int pthread_mutex_trylock(pthread_mutex_t* m) {
  g_locks.fetch_add(1, std::memory_order_relaxed);
  return (g_real.trylock ? g_real.trylock : resolve_real_locks().trylock)(m);
}
int pthread_rwlock_rdlock(pthread_rwlock_t* l) {
  g_locks.fetch_add(1, std::memory_order_relaxed);
  return (g_real.rdlock ? g_real.rdlock : resolve_real_locks().rdlock)(l);
}
int pthread_rwlock_wrlock(pthread_rwlock_t* l) {
  g_locks.fetch_add(1, std::memory_order_relaxed);
  return (g_real.wrlock ? g_real.wrlock : resolve_real_locks().wrlock)(l);
}
}

namespace tmlab::rt {
namespace {

TEST(RealtimeLoop, LockCounterSeesStdMutexes) {  // the canary: the lock count below can fail
  std::mutex m;
  std::shared_mutex sm;
  const long before = g_locks.load();
  { const std::lock_guard<std::mutex> g(m); }
  { const std::shared_lock<std::shared_mutex> g(sm); }
  { const std::unique_lock<std::shared_mutex> g(sm); }
  EXPECT_EQ(g_locks.load() - before, 3);
}

TEST(RealtimeLoop, ThreadedPokeReplaysOfflineAndAllocatesNothing) {
  const RealtimeCase c =
      load_realtime_case(std::string(TMLAB_SOURCE_DIR) + "/cases/realtime/liver-poke.json", TMLAB_SOURCE_DIR);
  auto control = c.make_control();
  LoopOptions opt;
  opt.duration = 0.7;  // into contact (from ~0.2 s) and past the peak
  opt.haptic_hz = c.haptic_hz;
  opt.visual_hz = c.visual_hz;
  opt.trajectory = c.trajectory.get();
  opt.keep_frames = true;
  long at_start = -1, during = -1, locks_at_start = -1, locks_during = -1;
  opt.on_phase = [&](int phase) {  // counts between "all threads running" and "stop"
    if (phase == 1) {
      at_start = g_allocations.load();
      locks_at_start = g_locks.load();
    }
    if (phase == 2) {
      during = g_allocations.load() - at_start;
      locks_during = g_locks.load() - locks_at_start;
    }
  };
  const LoopResult r = run_realtime_loop(*control, opt);
  ASSERT_GE(at_start, 0);
  EXPECT_EQ(during, 0) << "allocations while the three threads ran";
  EXPECT_EQ(locks_during, 0) << "mutex / rwlock acquisitions while the three threads ran";

  // Timing report for each thread.
  for (const ThreadTiming* t : {&r.haptic, &r.control, &r.visual}) {
    EXPECT_GT(t->iterations, 0) << t->name;
    EXPECT_GT(t->rate_hz, 0.0) << t->name;
    EXPECT_LE(t->p50_us, t->p99_us) << t->name;
    EXPECT_LE(t->p99_us, t->p999_us) << t->name;
    std::printf(
        "%-8s target %7.1f Hz  rate %7.1f Hz  p50 %8.1f us  p99 %8.1f us  p99.9 %8.1f us  missed %ld\n",
        t->name.c_str(), t->target_hz, t->rate_hz, t->p50_us, t->p99_us, t->p999_us, t->missed);
  }
  ASSERT_FALSE(r.control_probe.empty());
  EXPECT_FALSE(r.frames.empty());

  // Offline replay on the probe positions the control thread used: identical forces.
  auto offline = c.make_control();
  offline->reset(c.trajectory->position(0.0));
  double fmax = 0.0;
  for (std::size_t n = 0; n < r.control_probe.size(); ++n) {
    const Vec3 f = offline->step(r.control_probe[n]);
    ASSERT_EQ(f, r.control_force[n]) << "step " << n;
    fmax = std::max(fmax, f.norm());
  }
  std::printf("control steps %zu (model time %.3f s), peak force %.3f N\n", r.control_probe.size(),
              r.model_time, fmax);
  // Every probe position the control thread read is one the haptic thread published.
  for (std::size_t n = 0; n < r.control_probe.size(); n += 50) {
    bool found = r.control_probe[n] == c.trajectory->position(0.0);
    for (std::size_t k = 0; k < r.x.size() && !found; ++k) found = r.x[k] == r.control_probe[n];
    EXPECT_TRUE(found) << "control step " << n;
  }
}

/// A device held 6 mm into the liver below the probe's start, recording what the haptic thread asks
/// and renders in storage reserved up front (like a driver, it allocates nothing in the loop).
class RecordingDevice : public ProbeDevice {
 public:
  RecordingDevice(const Vec3& at, std::size_t capacity) : at_(at) {
    asked_.reserve(capacity);
    t_.reserve(capacity);
    f_.reserve(capacity);
  }
  Vec3 position(double t) override {
    if (asked_.size() < asked_.capacity()) asked_.push_back(t);
    return at_;
  }
  void render(double t, const Vec3& force) override {
    if (t_.size() < t_.capacity()) {
      t_.push_back(t);
      f_.push_back(force);
    }
  }
  std::vector<double> asked_, t_;
  std::vector<Vec3> f_;

 private:
  Vec3 at_;
};

TEST(RealtimeLoop, DeviceIsReadAndRenderedEveryHapticTick) {
  const RealtimeCase c =
      load_realtime_case(std::string(TMLAB_SOURCE_DIR) + "/cases/realtime/liver-poke.json", TMLAB_SOURCE_DIR);
  auto control = c.make_control();
  const Vec3 pressed = c.probe_start + (c.clearance + 0.006) * c.direction;
  RecordingDevice device(pressed, 4096);
  LoopOptions opt;
  opt.duration = 0.3;
  opt.haptic_hz = c.haptic_hz;
  opt.visual_hz = c.visual_hz;
  opt.rendered = CouplingScheme::Extrapolation;  // not the default: the device gets the rendered one
  opt.trajectory = c.trajectory.get();           // a device takes precedence over a trajectory
  opt.device = &device;
  long at_start = -1, during = -1, locks_at_start = -1, locks_during = -1;
  opt.on_phase = [&](int phase) {
    if (phase == 1) {
      at_start = g_allocations.load();
      locks_at_start = g_locks.load();
    }
    if (phase == 2) {
      during = g_allocations.load() - at_start;
      locks_during = g_locks.load() - locks_at_start;
    }
  };
  const LoopResult r = run_realtime_loop(*control, opt);
  ASSERT_GE(at_start, 0);
  EXPECT_EQ(during, 0) << "allocations while the three threads ran with a device";
  EXPECT_EQ(locks_during, 0) << "locks while the three threads ran with a device";

  // position(0) once for the start, then once per haptic tick, each followed by render(t, F).
  ASSERT_FALSE(r.t.empty());
  ASSERT_EQ(device.asked_.size(), r.t.size() + 1);
  EXPECT_EQ(device.asked_.front(), 0.0);
  ASSERT_EQ(device.t_.size(), r.t.size());
  for (std::size_t n = 0; n < r.t.size(); ++n) {
    EXPECT_EQ(device.asked_[n + 1], r.t[n]) << "tick " << n;
    EXPECT_EQ(device.t_[n], r.t[n]) << "tick " << n;
    EXPECT_EQ(r.x[n], pressed) << "tick " << n;  // the haptic thread used the device's position
    EXPECT_EQ(device.f_[n], r.extrapolation[n]) << "tick " << n;  // and rendered to it
  }
  // The control thread stepped with the device's probe: in contact from its first step.
  ASSERT_FALSE(r.control_probe.empty());
  EXPECT_EQ(r.control_probe.front(), pressed);
  EXPECT_GT(r.control_force.front().norm(), 0.0);
  EXPECT_LT(r.control_force.front().dot(c.direction), 0.0);  // the liver pushes the probe back
}

// A pending SIGINT / SIGTERM stops the three threads at their next tick (issue 26): a 60 s run
// returns at once with the signal; without stop_on_interrupt it is not the loop's business.
TEST(RealtimeLoop, PendingSignalStopsTheThreads) {
  const RealtimeCase c =
      load_realtime_case(std::string(TMLAB_SOURCE_DIR) + "/cases/realtime/liver-poke.json", TMLAB_SOURCE_DIR);
  auto control = c.make_control();
  LoopOptions opt;
  opt.duration = 60.0;
  opt.haptic_hz = c.haptic_hz;
  opt.visual_hz = c.visual_hz;
  opt.trajectory = c.trajectory.get();
  opt.keep_log = false;
  set_pending_interrupt(SIGTERM);
  const LoopResult r = run_realtime_loop(*control, opt);
  set_pending_interrupt(0);
  EXPECT_EQ(r.signal, SIGTERM);
  EXPECT_LT(r.model_time, 30.0);  // it stops at once; half the run is a bound no busy machine reaches
  EXPECT_LT(r.wall_time, 30.0);

  opt.duration = 0.05;
  opt.stop_on_interrupt = false;
  set_pending_interrupt(SIGINT);
  const LoopResult whole = run_realtime_loop(*control, opt);
  set_pending_interrupt(0);
  EXPECT_EQ(whole.signal, 0);
  EXPECT_GE(whole.wall_time, 0.05);
}

}  // namespace
}  // namespace tmlab::rt
