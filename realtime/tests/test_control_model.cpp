// Test 1 of issue 17: the real-time control step (explicit, viscoelastic liver, penalty probe) gives
// the same contact force history on a scripted poke as the library's offline explicit solver
// (tm::CentralDifference on the same model plus the probe's penalty energy, ProbePenaltyModel) at
// the same rate. Test 3: the hot-path operations allocate nothing (a counting operator new).
#include "core/base/error.hpp"
#include "realtime/control_model.hpp"
#include "realtime/haptic_coupling.hpp"
#include "realtime/realtime_case.hpp"
#include "realtime/seqlock.hpp"
#include "realtime/triple_buffer.hpp"
#include "tensormass/solvers/explicit_dynamics.hpp"
#include "tensormass/system/lumped_mass.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

// Counting global allocation functions for this test executable only.
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

RealtimeCase liver_case() {
  return load_realtime_case(std::string(TMLAB_SOURCE_DIR) + "/cases/realtime/liver-poke.json",
                            TMLAB_SOURCE_DIR);
}

TEST(ControlModel, PokeMatchesTheOfflineExplicitSolver) {
  const RealtimeCase c = liver_case();
  auto rt = c.make_control();
  // The offline model: the same viscoelastic liver, the probe's penalty as part of the model, the
  // library's central-difference solver, same dt and damping.
  tm::ViscoelasticOptions vo = c.viscoelastic;
  vo.energy_bookkeeping = false;
  tm::ViscoelasticStVK visco(c.mesh, c.material, c.prony, vo);
  ProbePenaltyModel model(visco, rt->contact());
  const VecX node_mass = tm::lumped_node_mass(c.mesh, c.density);
  DirichletCondition base;
  base.name = "base";
  base.nodes = c.fixed_nodes;
  tm::MechanicalSystem system(model, tm::lumped_dof_mass(node_mass),
                              tm::DirichletSet(c.mesh.num_points(), {base}),
                              tm::ExternalLoads(c.mesh, node_mass), {c.control.mass_damping, 0.0});
  const double dt = rt->dt();
  tm::CentralDifference cd(system, dt);
  const ProbeTrajectory& poke = *c.trajectory;
  model.set_probe(poke.position(0.0));
  const VecX zero = VecX::Zero(3 * c.mesh.num_points());
  cd.initialize(0.0, zero, zero);
  rt->reset(poke.position(0.0));

  const long steps = static_cast<long>(std::lround(poke.duration() / dt));
  double fmax = 0.0, diff = 0.0;
  VecX scratch = zero;
  for (long n = 0; n < steps; ++n) {
    const double t = static_cast<double>(n) * dt;
    const Vec3 x = poke.position(t);
    const Vec3 f_rt = rt->step(x);
    scratch.setZero();
    const Vec3 f_cd = rt->contact().add_node_forces(cd.displacement(), x, 1.0, scratch);
    model.set_probe(x);
    cd.step(t, dt);
    fmax = std::max(fmax, f_cd.norm());
    diff = std::max(diff, (f_rt - f_cd).norm());
  }
  std::printf("peak force %.4f N, max difference %.3e N over %ld steps (penalty %.1f N/m)\n", fmax, diff,
              steps, rt->penalty_stiffness());
  EXPECT_GT(fmax, 0.1);
  // Same scheme, different code: equal to round-off (far inside the time-step error).
  EXPECT_LE(diff, 1e-9 * fmax);
  EXPECT_LE((rt->displacement() - cd.displacement()).lpNorm<Eigen::Infinity>(),
            1e-9 * cd.displacement().lpNorm<Eigen::Infinity>());
}

TEST(ControlModel, UnstableStepAndStiffnessAreRefused) {
  RealtimeCase c = liver_case();
  c.control.dt = 2e-3;  // beyond the liver's 0.99 ms limit
  EXPECT_THROW(c.make_control(), Error);
  c.control.dt = 5e-4;
  c.control.penalty_stiffness = 1e6;  // far too stiff for this step
  EXPECT_THROW(c.make_control(), Error);
}

TEST(ControlModel, SnapshotStiffnessIsSymmetricAndSofterThanTheFrozenContact) {
  // With an infinitely stiff tissue (G -> 0) K_p would be -sum K_c (the frozen contact); with the
  // real compliance it is softer along the press. K_p is symmetric; it need not be definite: the
  // curvature term eps g H of a frictionless sphere pushes it sideways (a positive tangential value).
  const RealtimeCase c = liver_case();
  auto rt = c.make_control();
  const Vec3 x = c.trajectory->position(0.5);
  for (int i = 0; i < 400; ++i) rt->step(x);
  ContactSnapshot s, s2;
  rt->fill_snapshot(x, s);
  ASSERT_GT(s.active, 0);
  EXPECT_EQ(s.dropped, 0);
  EXPECT_LT((s.stiffness - s.stiffness.transpose()).norm(), 1e-9 * s.stiffness.norm());
  const double h = 1e-6;
  rt->fill_snapshot(x + Vec3(0, 0, h), s2);
  const double frozen = (s2.force.z() - s.force.z()) / h;  // dF_z/dz with the nodes frozen
  EXPECT_LT(frozen, 0.0);
  EXPECT_LT(s.stiffness(2, 2), 0.0);
  EXPECT_GT(s.stiffness(2, 2), frozen);  // softer than the frozen contact
}

TEST(HotPath, NoAllocation) {
  const RealtimeCase c = liver_case();
  auto rt = c.make_control();
  TripleBuffer<ContactSnapshot> snapshots;
  TripleBuffer<std::vector<float>> surface(
      std::vector<float>(3 * static_cast<std::size_t>(c.mesh.num_points())));
  struct Probe {
    double t;
    double x[3];
  };
  SeqLock<Probe> probe;
  ExtrapolationCoupling extrapolation;
  LocalModelCoupling local;
  auto iterate = [&](int n) {
    Vec3 f = Vec3::Zero();
    for (int i = 0; i < n; ++i) {
      const double t = 0.3 + 1e-3 * i;
      const Vec3 x = c.trajectory->position(t);  // haptic: probe input
      probe.store({t, {x.x(), x.y(), x.z()}});
      const Probe p = probe.load();  // control: probe read
      rt->step(Vec3(p.x[0], p.x[1], p.x[2]));
      rt->fill_snapshot(Vec3(p.x[0], p.x[1], p.x[2]), snapshots.write_buffer());
      snapshots.publish();
      rt->positions(surface.write_buffer().data());
      surface.publish();
      if (snapshots.update()) {  // haptic: newest snapshot, both couplings
        extrapolation.on_snapshot(snapshots.read_buffer());
        local.on_snapshot(snapshots.read_buffer());
      }
      f += extrapolation.force(t, x) + local.force(t, x);
      surface.update();  // visual
    }
    return f;
  };
  iterate(5);  // warm-up (nothing should allocate here either, but the first calls may size scratch)
  const long before = g_allocations.load();
  const Vec3 f = iterate(200);
  const long after = g_allocations.load();
  EXPECT_EQ(after - before, 0) << "allocations on the hot path";
  EXPECT_GT(f.norm(), 0.0);  // the loop did real work (the probe is in contact)
}

}  // namespace
}  // namespace tmlab::rt
