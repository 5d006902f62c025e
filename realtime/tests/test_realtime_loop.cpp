// The threaded loop (issue 17, tests 1 and 3): a scripted poke run through the three threads gives
// the same contact force history as the offline model replayed on the probe positions the control
// thread read (bit for bit: the hand-over corrupts nothing), each thread reports its timing, and no
// thread allocates once all three are running (a counting operator new). No timing assertion:
// the machine may be busy.
#include "realtime/coupling_study.hpp"
#include "realtime/realtime_case.hpp"
#include "realtime/realtime_loop.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long> g_allocations{0};
}
void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace tmlab::rt {
namespace {

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
  long at_start = -1, during = -1;
  opt.on_phase = [&](int phase) {  // counts allocations between "all threads running" and "stop"
    if (phase == 1) at_start = g_allocations.load();
    if (phase == 2) during = g_allocations.load() - at_start;
  };
  const LoopResult r = run_realtime_loop(*control, opt);
  ASSERT_GE(at_start, 0);
  EXPECT_EQ(during, 0) << "allocations while the three threads ran";

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

}  // namespace
}  // namespace tmlab::rt
