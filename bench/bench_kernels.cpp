// Kernel benchmarks: internal force of the TL oracle, the relative tensor-mass form, Picinbono's
// absolute mesh-level storage; tensor-mass tangent action and in-place tangent assembly. Kuhn-split
// cubes of 3,072 / 24,576 / 196,608 tets. Counter "time/tet" = seconds per tet (ns shown as "n").
// The viscoelastic cost table (docs/theory/viscoelasticity.md "Cost"): trial force, tangent and
// begin+commit of each history option against the elastic tensor-mass model, 10,368 tets.
// Contact surface detection (docs/contact.md): the boundary extraction, the grid's build and its
// per-iteration refit on cubes of 24,576 / 105,456 / 196,608 tets.
// The locking-free tet's explicit-step cost (docs/elements.md): internal force of AveragedPressureTet
// against plain P1 (HyperelasticTL), same neo-Hookean law, same cube, same u (arg 0 = cells per side,
// arg 1 = 0 for P1, 1 for the averaged-pressure tet; run both in one invocation to compare); the same
// for their viscoelastic forms (BM_ViscoElementForce: the trial force after one committed step, two
// Prony terms: ViscoelasticHyperelastic against ViscoelasticAveragedPressureTet).
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "tensormass/contact/surface_grid.hpp"
#include "tensormass/kernels/averaged_pressure_tet.hpp"
#include "tensormass/kernels/fast_force.hpp"
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/kernels/picinbono_storage.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/solvers/explicit_dynamics.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"
#include "tensormass/viscoelastic/viscoelastic_law.hpp"
#include "tensormass/viscoelastic/viscoelastic_law_anp.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <random>

namespace {

using namespace tmlab;
using namespace tmlab::tm;

struct Setup {
  Mesh mesh;
  VecX u, v;
};

Setup make_setup(int n) {
  Setup s;
  const double h = 1e-3;
  s.mesh = make_box_mesh(Vec3::Zero(), Vec3::Constant(n * h), n, n, n);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> d(-0.1 * h, 0.1 * h);
  s.u.resize(3 * s.mesh.num_points());
  s.v.resize(3 * s.mesh.num_points());
  for (Eigen::Index i = 0; i < s.u.size(); ++i) {
    s.u(i) = d(rng);
    s.v(i) = d(rng);
  }
  return s;
}

StVenantKirchhoff material() { return StVenantKirchhoff::from_young_poisson(3000.0, 0.45); }

void set_counters(benchmark::State& state, Index ntets) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * ntets);
  state.counters["tets"] = static_cast<double>(ntets);
  state.counters["time/tet"] =
      benchmark::Counter(static_cast<double>(ntets),
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <class Model>
void force_bench(benchmark::State& state, const Setup& s, const Model& model) {
  VecX f;
  for (auto _ : state) {
    model.internal_force(s.u, f);
    benchmark::DoNotOptimize(f.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, s.mesh.num_tets());
}

void BM_OracleForce(benchmark::State& state) {
  const Setup s = make_setup(static_cast<int>(state.range(0)));
  const TotalLagrangianStVK model(s.mesh, material());
  force_bench(state, s, model);
  state.counters["bytes/tet"] = static_cast<double>(sizeof(TetRest) + sizeof(Tet));
}

void BM_TensorMassForce(benchmark::State& state) {
  const Setup s = make_setup(static_cast<int>(state.range(0)));
  const TensorMassStVK model(s.mesh, material());
  force_bench(state, s, model);
  state.counters["bytes/tet"] = static_cast<double>(sizeof(TensorMassTet) + sizeof(Tet));
}

void BM_TensorMassEnergy(benchmark::State& state) {
  const Setup s = make_setup(static_cast<int>(state.range(0)));
  const TensorMassStVK model(s.mesh, material());
  for (auto _ : state) benchmark::DoNotOptimize(model.energy(s.u));
  set_counters(state, s.mesh.num_tets());
}

void BM_PicinbonoAbsoluteForce(benchmark::State& state) {
  const Setup s = make_setup(static_cast<int>(state.range(0)));
  const PicinbonoAbsoluteStVK model(s.mesh, material());
  force_bench(state, s, model);
  state.counters["bytes/tet"] =
      static_cast<double>(model.storage_bytes()) / static_cast<double>(s.mesh.num_tets());
}

void BM_TensorMassTangentApply(benchmark::State& state) {
  const Setup s = make_setup(static_cast<int>(state.range(0)));
  const TensorMassStVK model(s.mesh, material());
  VecX Kv;
  for (auto _ : state) {
    model.tangent_apply(s.u, s.v, Kv);
    benchmark::DoNotOptimize(Kv.data());
  }
  set_counters(state, s.mesh.num_tets());
}

void BM_OracleTangentApply(benchmark::State& state) {
  const Setup s = make_setup(static_cast<int>(state.range(0)));
  const TotalLagrangianStVK model(s.mesh, material());
  VecX Kv;
  for (auto _ : state) {
    model.tangent_apply(s.u, s.v, Kv);
    benchmark::DoNotOptimize(Kv.data());
  }
  set_counters(state, s.mesh.num_tets());
}

void BM_TensorMassTangentAssembly(benchmark::State& state) {
  const Setup s = make_setup(static_cast<int>(state.range(0)));
  const TensorMassStVK model(s.mesh, material());
  SpMat K;
  model.tangent(s.u, K);  // first call sets the pattern; the loop measures in-place refills
  for (auto _ : state) {
    model.tangent(s.u, K);
    benchmark::DoNotOptimize(K.valuePtr());
  }
  set_counters(state, s.mesh.num_tets());
}

// cubes of 8^3, 16^3, 32^3 hexes x 6 = 3,072 / 24,576 / 196,608 tets
void BM_ElementForce(benchmark::State& state) {
  const Setup s = make_setup(static_cast<int>(state.range(0)));
  const Law law = NeoHookean::from_young_poisson(3000.0, 0.45);
  if (state.range(1) == 0)
    force_bench(state, s, HyperelasticTL(s.mesh, law));
  else
    force_bench(state, s, AveragedPressureTet(s.mesh, law));
}

template <class Model>
void visco_element_bench(benchmark::State& state, const Setup& s, Model&& m) {
  m.begin_step(0.01);
  m.commit_step(s.u);
  m.begin_step(0.01);
  force_bench(state, s, m);
}
void BM_ViscoElementForce(benchmark::State& state) {
  const Setup s = make_setup(static_cast<int>(state.range(0)));
  const Law law = NeoHookean::from_young_poisson(3000.0, 0.45);
  const PronySeries prony = PronySeries::from_long_term({0.8, 0.4}, {0.5, 5.0});
  if (state.range(1) == 0)
    visco_element_bench(state, s, ViscoelasticHyperelastic(s.mesh, law, prony));
  else
    visco_element_bench(state, s, ViscoelasticAveragedPressureTet(s.mesh, law, prony));
}

#define TM_SIZES ->Arg(8)->Arg(16)->Arg(32)->Unit(benchmark::kMicrosecond)
/// Viscoelastic trial force (2 Prony terms) after one committed step: the overhead over the
/// elastic tensor-mass force is the seed paper's "about 5 %" claim (docs/theory/seed-errata.md "Flaws" 4).
void visco_force_bench(benchmark::State& state, ViscoelasticOptions::History history) {
  const Setup s = make_setup(static_cast<int>(state.range(0)));
  ViscoelasticOptions o;
  o.history = history;
  o.integration = ViscoelasticOptions::Integration::Midpoint;
  o.energy_bookkeeping = false;
  ViscoelasticStVK m(s.mesh, material(), PronySeries::from_long_term({0.8, 0.4}, {0.5, 5.0}), o);
  m.begin_step(0.01);
  m.commit_step(s.u);
  m.begin_step(0.01);
  force_bench(state, s, m);
}
void BM_ViscoSeedForce(benchmark::State& state) {
  visco_force_bench(state, ViscoelasticOptions::History::NodalForce);
}
void BM_ViscoObjectiveForce(benchmark::State& state) {
  visco_force_bench(state, ViscoelasticOptions::History::Pk2);
}

// ---- viscoelastic cost table (docs/theory/viscoelasticity.md "Cost", errata "Flaws" 4) ----
// 12^3-cell box (10,368 tets), three Prony terms, a smooth u with a small perturbation. range(0):
// 0 the elastic TensorMassStVK, 1 nodal_force, 2 pk2 full, 3 pk2 deviatoric (all midpoint).

struct CostSetup {
  Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Constant(0.01), 12, 12, 12);
  StVenantKirchhoff mat = StVenantKirchhoff::from_young_poisson(5e3, 0.4);
  PronySeries prony = PronySeries::from_long_term({0.5, 0.3, 0.2}, {0.1, 1.0, 10.0});
  VecX u;
  CostSetup() : u(3 * mesh.num_points()) {
    for (Index i = 0; i < mesh.num_points(); ++i) {
      const Vec3& x = mesh.points[static_cast<std::size_t>(i)];
      const Vec3 wiggle(std::sin(12.9898 * i), std::sin(12.9898 * i + 78.233 + 0.5 * i),
                        std::sin(12.9898 * i + 156.466 + i));
      u.segment<3>(3 * i) = 0.05 * Vec3(x.y(), x.z(), x.x()) + 1e-5 * wiggle;
    }
  }
};

/// The model of range(0) after one committed step, in a fresh trial step (nullptr: elastic).
std::unique_ptr<ViscoelasticStVK> cost_visco(const CostSetup& c, std::int64_t kind, bool bookkeeping) {
  if (kind == 0) return nullptr;
  ViscoelasticOptions o;
  o.history = kind == 1 ? ViscoelasticOptions::History::NodalForce : ViscoelasticOptions::History::Pk2;
  o.integration = ViscoelasticOptions::Integration::Midpoint;
  o.relaxation =
      kind == 3 ? ViscoelasticOptions::Relaxation::Deviatoric : ViscoelasticOptions::Relaxation::Full;
  o.energy_bookkeeping = bookkeeping;
  auto m = std::make_unique<ViscoelasticStVK>(c.mesh, c.mat, c.prony, o);
  m->begin_step(0.01);
  m->commit_step(c.u);
  m->begin_step(0.01);
  return m;
}

void BM_ViscoCostForce(benchmark::State& state) {
  const CostSetup c;
  const TensorMassStVK elastic(c.mesh, c.mat);
  const auto visco = cost_visco(c, state.range(0), true);
  const ElasticModel& model = visco ? static_cast<const ElasticModel&>(*visco) : elastic;
  VecX f;
  for (auto _ : state) {
    model.internal_force(c.u, f);
    benchmark::DoNotOptimize(f.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, c.mesh.num_tets());
}

void BM_ViscoCostTangent(benchmark::State& state) {
  const CostSetup c;
  const TensorMassStVK elastic(c.mesh, c.mat);
  const auto visco = cost_visco(c, state.range(0), true);
  const ElasticModel& model = visco ? static_cast<const ElasticModel&>(*visco) : elastic;
  SpMat K;
  model.tangent(c.u, K);  // the pattern; the loop measures refills
  for (auto _ : state) {
    model.tangent(c.u, K);
    benchmark::DoNotOptimize(K.valuePtr());
  }
  set_counters(state, c.mesh.num_tets());
}

/// begin_step + commit_step; range(1): energy bookkeeping on (1) or off (0).
void BM_ViscoCostBeginCommit(benchmark::State& state) {
  const CostSetup c;
  const auto visco = cost_visco(c, state.range(0), state.range(1) != 0);
  for (auto _ : state) {
    visco->begin_step(0.01);
    visco->commit_step(c.u);
    benchmark::ClobberMemory();
  }
  set_counters(state, c.mesh.num_tets());
  state.counters["history_doubles"] =
      static_cast<double>(visco->committed_history().size() + visco->committed_driver().size());
}

/// The contact surface of a deformed cube: extracted once (boundary faces, tributary areas).
void BM_ContactSurfaceExtract(benchmark::State& state) {
  const Setup s = make_setup(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    ContactSurface surface = ContactSurface::extract(s.mesh);
    benchmark::DoNotOptimize(surface.nodes.data());
  }
  set_counters(state, s.mesh.num_tets());
}

/// The candidate-search grid built over the deformed surface (once per contact object).
void BM_SurfaceGridBuild(benchmark::State& state) {
  const Setup s = make_setup(static_cast<int>(state.range(0)));
  const ContactSurface surface = ContactSurface::extract(s.mesh);
  for (auto _ : state) {
    SurfaceGrid grid(s.mesh, surface, s.u);
    benchmark::DoNotOptimize(&grid);
  }
  set_counters(state, s.mesh.num_tets());
  state.counters["surface_nodes"] = static_cast<double>(surface.size());
}

/// The grid re-binned at new positions (every outer iteration of the contact solve).
void BM_SurfaceGridRefit(benchmark::State& state) {
  const Setup s = make_setup(static_cast<int>(state.range(0)));
  const ContactSurface surface = ContactSurface::extract(s.mesh);
  SurfaceGrid grid(s.mesh, surface, s.u);
  for (auto _ : state) {
    grid.refit(s.mesh, surface, s.v);
    benchmark::DoNotOptimize(&grid);
  }
  set_counters(state, s.mesh.num_tets());
  state.counters["surface_nodes"] = static_cast<double>(surface.size());
}

// cubes of 16^3, 26^3, 32^3 hexes x 6 = 24,576 / 105,456 / 196,608 tets
#define CONTACT_SIZES ->Arg(16)->Arg(26)->Arg(32)->Unit(benchmark::kMicrosecond)

// ---- the liver's explicit step on the fast kernel (issue 16 target: viscoelastic <= 50 us) ----
// The step of `tmlab bench` (bench_suite.cpp): bottom 10 % of the liver clamped, gravity, E 300 kPa,
// nu 0.45, the two-term Prony series, dt = 0.3 h_min / c_p, energy bookkeeping off, 1 thread.

Mesh liver_mesh() { return read_mesh(std::string(TMLAB_SOURCE_DIR) + "/meshes/liver.msh"); }
StVenantKirchhoff step_material() { return StVenantKirchhoff::from_young_poisson(300e3, 0.45); }
PronySeries step_prony() { return PronySeries::from_long_term({0.8, 0.4}, {0.5, 5.0}); }

/// The liver's explicit step with `model` (range 0: elastic FastHyperelastic, 1: objective
/// ViscoelasticStVK on the fast kernel).
void BM_LiverExplicitStep(benchmark::State& state) {
  const Mesh mesh = liver_mesh();
  const StVenantKirchhoff mat = step_material();
  std::unique_ptr<ElasticModel> model;
  if (state.range(0) == 0) {
    model = std::make_unique<FastHyperelastic>(mesh, FastLaw::StVK, mat.lambda, mat.mu, 1);
  } else {
    ViscoelasticOptions vo;
    vo.energy_bookkeeping = false;
    vo.fast_threads = 1;
    model = std::make_unique<ViscoelasticStVK>(mesh, mat, step_prony(), vo);
  }
  double zlo = 1e300, zhi = -1e300, h_min = 1e300;
  for (const Vec3& p : mesh.points) {
    zlo = std::min(zlo, p.z());
    zhi = std::max(zhi, p.z());
  }
  for (const Tet& t : mesh.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        h_min = std::min(
            h_min, (mesh.points[static_cast<std::size_t>(t[a])] - mesh.points[static_cast<std::size_t>(t[b])])
                       .norm());
  DirichletCondition clamp;
  clamp.name = "base";
  for (Index i = 0; i < mesh.num_points(); ++i)
    if (mesh.points[static_cast<std::size_t>(i)].z() <= zlo + 0.1 * (zhi - zlo)) clamp.nodes.push_back(i);
  const VecX node_mass = lumped_node_mass(mesh, 1000.0);
  ExternalLoads loads(mesh, node_mass);
  Gravity g;
  g.acceleration = Vec3(0, 0, -9.81);
  loads.add(g);
  MechanicalSystem system(*model, lumped_dof_mass(node_mass), DirichletSet(mesh.num_points(), {clamp}),
                          loads);
  const double dt = 0.3 * h_min / std::sqrt((mat.lambda + 2 * mat.mu) / 1000.0);
  CentralDifference integ(system, dt, false);
  integ.initialize(0.0, VecX::Zero(system.num_dofs()), VecX::Zero(system.num_dofs()));
  for (auto _ : state) {
    integ.step(integ.time(), dt);
    benchmark::ClobberMemory();
  }
  set_counters(state, mesh.num_tets());
}

/// The fast kernel alone on the liver at a random u: range 0 the elastic force, 1 the fused
/// objective step (force_and_commit_pk2, two terms).
void BM_LiverFastKernel(benchmark::State& state) {
  const Mesh mesh = liver_mesh();
  const StVenantKirchhoff mat = step_material();
  const FastTetForce fast(mesh, FastLaw::StVK, mat.lambda, mat.mu, 1);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> d(-1e-4, 1e-4);
  VecX u(3 * mesh.num_points()), f;
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = d(rng);
  FastTetForce::PronyStep step;
  step.terms = 2;
  const PronySeries prony = step_prony();
  for (int j = 0; j < 2; ++j) {
    const RecursionFactors rf = recursion_factors(PronyIntegration::Midpoint, 1e-5, prony.tau(j));
    step.alpha[j] = prony.alpha(j);
    step.a[j] = rf.a;
    step.c[j] = rf.c;
  }
  std::vector<double> hist(12 * fast.num_slots(), 0.0), driver(6 * fast.num_slots(), 0.0);  // lane order
  for (auto _ : state) {
    if (state.range(0) == 0)
      fast.internal_force(u, f);
    else
      fast.force_and_commit_pk2(u, step, hist.data(), driver.data(), f);
    benchmark::DoNotOptimize(f.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, mesh.num_tets());
}

BENCHMARK(BM_LiverExplicitStep)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond)->MeasureProcessCPUTime();
BENCHMARK(BM_LiverFastKernel)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond)->MeasureProcessCPUTime();
BENCHMARK(BM_OracleForce) TM_SIZES;
BENCHMARK(BM_ElementForce)->ArgsProduct({{16, 32}, {0, 1}})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ViscoElementForce)->ArgsProduct({{16, 32}, {0, 1}})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ViscoSeedForce) TM_SIZES;
BENCHMARK(BM_ViscoObjectiveForce) TM_SIZES;
BENCHMARK(BM_TensorMassForce) TM_SIZES;
BENCHMARK(BM_ViscoCostForce)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ViscoCostTangent)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ViscoCostBeginCommit)->ArgsProduct({{1, 2, 3}, {1, 0}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TensorMassEnergy) TM_SIZES;
BENCHMARK(BM_PicinbonoAbsoluteForce) TM_SIZES;
BENCHMARK(BM_OracleTangentApply) TM_SIZES;
BENCHMARK(BM_TensorMassTangentApply) TM_SIZES;
BENCHMARK(BM_TensorMassTangentAssembly) TM_SIZES;
BENCHMARK(BM_ContactSurfaceExtract) CONTACT_SIZES;
BENCHMARK(BM_SurfaceGridBuild) CONTACT_SIZES;
BENCHMARK(BM_SurfaceGridRefit) CONTACT_SIZES;

}  // namespace

BENCHMARK_MAIN();
