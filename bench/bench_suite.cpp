// The measurements of tmlab bench; what each record means is in bench_suite.hpp, the flop and
// byte counts are derived in docs/performance.md ("Counting").
// Tests: the mesh selection (bench_mesh_names, check_bench_meshes) in tests/test_bench_suite.cpp;
// run_bench itself end to end, since it measures through Google Benchmark for seconds: ctest
// test_cli_bench (apps/tmlab/tests/test_cli_bench.cpp) runs `tmlab bench --quick` and checks every
// record field of the documented schema, the contact ladder's records, and --meshes selecting the
// measured meshes; test_bench_report checks the report written from such a document.
#include "bench/bench_suite.hpp"

#include "bench/machine_limits.hpp"
#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "tensormass/contact/contact_implicit.hpp"
#include "tensormass/contact/kinematic_contact.hpp"
#include "tensormass/kernels/fast_force.hpp"
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/solvers/explicit_dynamics.hpp"
#include "tensormass/solvers/implicit_dynamics.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <random>

namespace tmlab::tm {

namespace {

using json = nlohmann::json;

/// Collects the real time per iteration of the benchmarks run (no console output).
class Collector : public benchmark::BenchmarkReporter {
 public:
  double ns = -1.0, cpu_ns = -1.0;
  std::string error;
  bool ReportContext(const Context&) override { return true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Iteration) continue;
      if (r.error_occurred)
        error = r.error_message;
      else {
        ns = r.GetAdjustedRealTime();
        cpu_ns = r.GetAdjustedCPUTime();
      }
    }
  }
};

/// Nanoseconds per call: wall time, and the CPU time of the whole process (all threads).
struct Timing {
  double wall = 0.0, cpu = 0.0;
  /// What a record reports: the CPU time for one thread (robust on a shared machine: time spent
  /// descheduled is not counted), the wall time for several (the speed-up is a wall-time quantity).
  double reported(int threads) const { return threads == 1 ? cpu : wall; }
};

/// Times fn by Google Benchmark (at least one call, min_time seconds of wall time).
Timing measure_ns(const std::function<void()>& fn, double min_time) {
  check_interrupt("bench: stopped between two measurements");  // SIGINT/SIGTERM: a safe point
  benchmark::ClearRegisteredBenchmarks();
  benchmark::RegisterBenchmark("tmlab_bench",
                               [&fn](benchmark::State& st) {
                                 for (auto _ : st) {
                                   fn();
                                   benchmark::ClobberMemory();
                                 }
                               })
      ->UseRealTime()
      ->MeasureProcessCPUTime()
      ->Unit(benchmark::kNanosecond)
      ->MinTime(min_time);
  Collector c;
  benchmark::RunSpecifiedBenchmarks(&c);
  benchmark::ClearRegisteredBenchmarks();
  if (c.ns < 0.0) throw Error("bench: a measurement failed: " + c.error);
  return {c.ns, c.cpu_ns};
}

struct MeshCase {
  std::string name;
  Mesh mesh;
  double h_min = 0.0;   ///< shortest edge, m
  double h_mean = 0.0;  ///< (mean tet volume)^(1/3), m
};

MeshCase make_case(std::string name, Mesh mesh) {
  MeshCase c{std::move(name), std::move(mesh), 1e300, 0.0};
  double vol = 0.0;
  for (const Tet& t : c.mesh.tets) {
    const Vec3& p0 = c.mesh.points[static_cast<std::size_t>(t[0])];
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        c.h_min = std::min(c.h_min, (c.mesh.points[static_cast<std::size_t>(t[a])] -
                                     c.mesh.points[static_cast<std::size_t>(t[b])])
                                        .norm());
    const Mat3 J = (Mat3() << c.mesh.points[static_cast<std::size_t>(t[1])] - p0,
                    c.mesh.points[static_cast<std::size_t>(t[2])] - p0,
                    c.mesh.points[static_cast<std::size_t>(t[3])] - p0)
                       .finished();
    vol += std::abs(J.determinant()) / 6.0;
  }
  c.h_mean = std::cbrt(vol / static_cast<double>(c.mesh.num_tets()));
  return c;
}

MeshCase cube(const std::string& name, int nx, int ny, int nz) {
  const double L = 0.1;  // 10 cm, cells as equal as the counts allow
  const int n = std::max({nx, ny, nz});
  return make_case(name, make_box_mesh(Vec3::Zero(), Vec3(L * nx / n, L * ny / n, L * nz / n), nx, ny, nz));
}

const StVenantKirchhoff kKernelMaterial = StVenantKirchhoff::from_young_poisson(3000.0, 0.45);
const StVenantKirchhoff kStepMaterial = StVenantKirchhoff::from_young_poisson(300e3, 0.45);
PronySeries two_terms() { return PronySeries::from_long_term({0.8, 0.4}, {0.5, 5.0}); }

json force_record(const MeshCase& m, const std::string& kernel, const std::string& history,
                  const std::string& law, int threads, Timing ns, double flops, double bytes, double memory) {
  const double nt = static_cast<double>(m.mesh.num_tets());
  return {{"kind", "force"},
          {"kernel", kernel},
          {"history", history},
          {"law", law},
          {"mesh", m.name},
          {"tets", m.mesh.num_tets()},
          {"threads", threads},
          {"ns_per_tet", ns.reported(threads) / nt},
          {"wall_ns_per_tet", ns.wall / nt},
          {"time", threads == 1 ? "cpu" : "wall"},
          {"flops_per_tet", flops},
          {"bytes_per_tet", bytes},
          {"memory_per_tet", memory}};
}

json step_record(const MeshCase& m, const std::string& step, const std::string& kernel,
                 const std::string& history, int threads, Timing ns, bool bookkeeping = false,
                 const std::string& linear = "none") {
  return {{"kind", "step"},
          {"step", step},
          {"linear", linear},
          {"kernel", kernel},
          {"history", history},
          {"law", "stvk"},
          {"mesh", m.name},
          {"tets", m.mesh.num_tets()},
          {"threads", threads},
          {"us_per_step", ns.reported(threads) * 1e-3},
          {"wall_us_per_step", ns.wall * 1e-3},
          {"time", threads == 1 ? "cpu" : "wall"},
          {"energy_bookkeeping", bookkeeping}};
}

// ---- hand counts per tet (docs/performance.md, "Counting") ----
constexpr double kFlopsBaseline = 285, kFlopsBaselineNeo = 400, kFlopsBaselineObjective = 300;
constexpr double kFlopsTensorMass = 630, kFlopsFast = 249, kFlopsFastNeo = 315, kFlopsFastObjective = 258;
constexpr double kBytesBaseline = sizeof(TetRest) + sizeof(Tet);               // 104 + 16
constexpr double kBytesTensorMass = sizeof(TensorMassTet) + sizeof(Tet);       // 960 + 16
constexpr double kBytesFast = 10 * sizeof(double) + 5 * sizeof(std::int32_t);  // 116

void force_records(const MeshCase& m, const BenchOptions& o, json& records) {
  const double nt = static_cast<double>(m.mesh.num_tets());
  const double nn = static_cast<double>(m.mesh.num_points());
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> d(-0.1 * m.h_mean, 0.1 * m.h_mean);
  VecX u(3 * m.mesh.num_points());
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = d(rng);
  VecX f;
  auto log = [&](const json& r) {
    if (o.log)
      *o.log << "  " << r["mesh"].get<std::string>() << " " << r["kernel"].get<std::string>() << "/"
             << r["history"].get<std::string>() << "/" << r["law"].get<std::string>() << " "
             << r["threads"].get<int>() << "t: " << r["ns_per_tet"].get<double>() << " ns/tet\n";
    records.push_back(r);
  };
  const NeoHookean neo(kKernelMaterial.lambda, kKernelMaterial.mu);
  {
    const TotalLagrangianStVK model(m.mesh, kKernelMaterial);
    log(force_record(m, "baseline", "none", "stvk", 1,
                     measure_ns([&] { model.internal_force(u, f); }, o.min_time), kFlopsBaseline,
                     kBytesBaseline, kBytesBaseline));
  }
  {
    const HyperelasticTL model(m.mesh, Law(neo));
    log(force_record(m, "baseline", "none", "neo_hookean", 1,
                     measure_ns([&] { model.internal_force(u, f); }, o.min_time), kFlopsBaselineNeo,
                     kBytesBaseline, kBytesBaseline));
  }
  auto visco = [&](ViscoelasticOptions::History h) {
    ViscoelasticOptions vo;
    vo.history = h;
    vo.energy_bookkeeping = false;
    auto m2 = std::make_unique<ViscoelasticStVK>(m.mesh, kKernelMaterial, two_terms(), vo);
    m2->begin_step(0.01);
    m2->commit_step(u);
    m2->begin_step(0.01);
    return m2;
  };
  {
    const auto model = visco(ViscoelasticOptions::History::Pk2);
    // per tet: rest 104 + tet 16 + s_hist 48 streamed; held: + tensors 960 + 2 x 6 history + 6 driver
    log(force_record(m, "baseline", "objective", "stvk", 1,
                     measure_ns([&] { model->internal_force(u, f); }, o.min_time), kFlopsBaselineObjective,
                     kBytesBaseline + 48, kBytesTensorMass + 104 + 8 * (12 + 6 + 6)));
  }
  {
    const TensorMassStVK model(m.mesh, kKernelMaterial);
    log(force_record(m, "tensor_mass", "none", "stvk", 1,
                     measure_ns([&] { model.internal_force(u, f); }, o.min_time), kFlopsTensorMass,
                     kBytesTensorMass, kBytesTensorMass));
  }
  {
    const auto model = visco(ViscoelasticOptions::History::NodalForce);
    // + f = (1+g) f_e + f_hist over the nodes; held: + K_0^+ 144 + 2 x 12 history + 12 driver
    log(force_record(m, "tensor_mass", "xu2011", "stvk", 1,
                     measure_ns([&] { model->internal_force(u, f); }, o.min_time),
                     kFlopsTensorMass + 6 * nn / nt, kBytesTensorMass + 48 * nn / nt,
                     kBytesTensorMass + 8 * (144 + 24 + 12)));
  }
  // S_hist in the fast kernel's lane order: random, so only its size matters (>= 6 num_slots(); the
  // padding slots' values meet zero volumes and gradients)
  std::vector<double> s_hist(
      6 * (static_cast<std::size_t>(m.mesh.num_tets()) + FastTetForce::kParts * FastTetForce::kLanes));
  for (double& s : s_hist) s = 10.0 * d(rng) / m.h_mean;
  const VecX f_hist = VecX::Constant(u.size(), 1e-3);
  for (int threads = 1; threads <= o.max_threads; ++threads) {
    const FastTetForce stvk(m.mesh, FastLaw::StVK, kKernelMaterial.lambda, kKernelMaterial.mu, threads);
    const double mem = static_cast<double>(stvk.storage_bytes()) / nt;
    log(force_record(m, "fast", "none", "stvk", threads,
                     measure_ns([&] { stvk.internal_force(u, f); }, o.min_time), kFlopsFast, kBytesFast,
                     mem));
    // xu2011 trial force on the fast kernel: f = (1 + g) f_e(u) + f_hist (one axpy over the nodes)
    log(force_record(m, "fast", "xu2011", "stvk", threads,
                     measure_ns(
                         [&] {
                           stvk.internal_force(u, f);
                           f = 1.3 * f + f_hist;
                         },
                         o.min_time),
                     kFlopsFast + 6 * nn / nt, kBytesFast + 48 * nn / nt, mem + 8 * (24 + 12)));
    log(force_record(m, "fast", "objective", "stvk", threads,
                     measure_ns(
                         [&] {
                           stvk.trial_force_pk2(u, 1.3 * kKernelMaterial.lambda, 1.3 * kKernelMaterial.mu,
                                                s_hist.data(), f);
                         },
                         o.min_time),
                     kFlopsFastObjective, kBytesFast + 48, mem + 8 * (12 + 6 + 6)));
    const FastTetForce nh(m.mesh, FastLaw::NeoHookean, neo.lambda(), neo.mu(), threads);
    log(force_record(m, "fast", "none", "neo_hookean", threads,
                     measure_ns([&] { nh.internal_force(u, f); }, o.min_time), kFlopsFastNeo, kBytesFast,
                     mem));
  }
}

/// The bottom 10 % of the mesh (in z) clamped, gravity, the step material.
struct StepProblem {
  const MeshCase& m;
  std::unique_ptr<ElasticModel> model;
  std::unique_ptr<MechanicalSystem> system;
  StepProblem(const MeshCase& mc, std::unique_ptr<ElasticModel> em, bool ramp = false)
      : m(mc), model(std::move(em)) {
    double zlo = 1e300, zhi = -1e300;
    for (const Vec3& p : m.mesh.points) {
      zlo = std::min(zlo, p.z());
      zhi = std::max(zhi, p.z());
    }
    DirichletCondition clamp;
    clamp.name = "base";
    for (Index i = 0; i < m.mesh.num_points(); ++i)
      if (m.mesh.points[static_cast<std::size_t>(i)].z() <= zlo + 0.1 * (zhi - zlo)) clamp.nodes.push_back(i);
    const VecX node_mass = lumped_node_mass(m.mesh, 1000.0);
    ExternalLoads loads(m.mesh, node_mass);
    Gravity g;
    g.acceleration = Vec3(0, 0, -9.81);
    if (ramp) g.function = TimeFunction::ramp(0.0, 1.0);  // static: the load grows with pseudo-time
    loads.add(g);
    system = std::make_unique<MechanicalSystem>(*model, lumped_dof_mass(node_mass),
                                                DirichletSet(m.mesh.num_points(), {clamp}), loads);
  }
};

std::unique_ptr<ElasticModel> step_model(const MeshCase& m, const std::string& kernel,
                                         const std::string& history, int threads, bool bookkeeping = true) {
  if (history != "none") {
    ViscoelasticOptions vo;
    vo.history =
        history == "xu2011" ? ViscoelasticOptions::History::NodalForce : ViscoelasticOptions::History::Pk2;
    vo.energy_bookkeeping = bookkeeping;
    if (kernel == "fast") vo.fast_threads = threads;
    return std::make_unique<ViscoelasticStVK>(m.mesh, kStepMaterial, two_terms(), vo);
  }
  if (kernel == "fast")
    return std::make_unique<FastHyperelastic>(m.mesh, FastLaw::StVK, kStepMaterial.lambda, kStepMaterial.mu,
                                              threads);
  return std::make_unique<TensorMassStVK>(m.mesh, kStepMaterial);
}

void step_records(const MeshCase& m, const BenchOptions& o, bool solvers, json& records) {
  auto log = [&](const json& r) {
    if (o.log)
      *o.log << "  " << r["mesh"].get<std::string>() << " " << r["step"].get<std::string>() << " "
             << r["kernel"].get<std::string>() << "/" << r["history"].get<std::string>() << "/"
             << r["linear"].get<std::string>() << " " << r["threads"].get<int>()
             << "t: " << r["us_per_step"].get<double>() << " us/step\n";
    records.push_back(r);
  };
  // Explicit: dt = 0.3 h_min / c_p (stable; the cost per step does not depend on dt).
  const double cp = std::sqrt((kStepMaterial.lambda + 2 * kStepMaterial.mu) / 1000.0);
  const double dt = 0.3 * m.h_min / cp;
  struct Variant {
    std::string kernel, history;
    int threads;
    bool bookkeeping;
  };
  // The viscoelastic models as the case runner builds them (energy bookkeeping on), and with the
  // bookkeeping off (a run that records no energies), on the reference and the fast kernels.
  std::vector<Variant> variants = {{"tensor_mass", "none", 1, false},
                                   {"tensor_mass", "xu2011", 1, true},
                                   {"baseline", "objective", 1, true},
                                   {"tensor_mass", "xu2011", 1, false},
                                   {"baseline", "objective", 1, false}};
  for (int t = 1; t <= o.max_threads; ++t) {
    variants.push_back({"fast", "none", t, false});
    variants.push_back({"fast", "xu2011", t, false});
    variants.push_back({"fast", "objective", t, false});
  }
  for (const Variant& v : variants) {
    StepProblem p(m, step_model(m, v.kernel, v.history, v.threads, v.bookkeeping));
    CentralDifference integ(*p.system, dt, false);
    integ.initialize(0.0, VecX::Zero(p.system->num_dofs()), VecX::Zero(p.system->num_dofs()));
    // With bookkeeping, the committed energies are read after every step, as the case runner does
    // when it records every step (the spring energy is computed when read).
    const auto* visco = v.bookkeeping ? dynamic_cast<const ViscoelasticStVK*>(p.model.get()) : nullptr;
    double t = 0.0, energy = 0.0;
    const Timing ns = measure_ns(
        [&] {
          integ.step(t, dt);
          t = integ.time();
          if (visco) energy += visco->committed_elastic_energy() + visco->committed_branch_energy();
        },
        o.min_time);
    benchmark::DoNotOptimize(energy);
    log(step_record(m, "explicit", v.kernel, v.history, v.threads, ns, v.bookkeeping && v.history != "none"));
  }
  if (!solvers) return;
  // The Newton steps with each sparse direct solver (NewtonOptions::linear_solver): Eigen's
  // SimplicialLDLT (the default) and CHOLMOD's supernodal LL^T.
  for (const auto& [linear, kind] : {std::pair{std::string("ldlt"), NewtonLinearSolver::Direct},
                                     std::pair{std::string("cholmod"), NewtonLinearSolver::Cholmod}}) {
    NewtonOptions no;
    no.linear_solver = kind;
    {
      StepProblem p(m, step_model(m, "tensor_mass", "none", 1));
      ImplicitDynamics integ(*p.system, ImplicitScheme::Newmark, no);
      integ.initialize(0.0, VecX::Zero(p.system->num_dofs()), VecX::Zero(p.system->num_dofs()));
      double t = 0.0;
      const Timing ns = measure_ns(
          [&] {
            integ.step(t, 1e-3);
            t = integ.time();
          },
          o.min_time);
      log(step_record(m, "implicit", "tensor_mass", "none", 1, ns, false, linear));
    }
    {
      StepProblem p(m, step_model(m, "tensor_mass", "none", 1), true);
      StaticSolver solver(*p.system, no);
      VecX u;
      const Timing ns = measure_ns(
          [&] {
            u = VecX::Zero(p.system->num_dofs());
            solver.advance(0.0, 1.0, u);
          },
          o.min_time);
      log(step_record(m, "static_newton", "tensor_mass", "none", 1, ns, false, linear));
    }
  }
}

// ---- Whole steps with rigid contact (issue 16: the 1 ms target with viscoelasticity and contact) ----

/// The contact ladder: cubes of 2.4k to 132k tets, close enough in size for the 1 ms crossing to be
/// interpolated between neighbours (quick: the 2.4k cube only).
std::vector<std::array<int, 3>> contact_cells(bool quick) {
  if (quick) return {{7, 7, 8}};
  return {{7, 7, 8}, {12, 12, 12}, {16, 16, 16}, {20, 20, 20}, {24, 24, 24}, {28, 28, 28}};
}

/// A rigid frictionless sphere of radius 0.3 x the top face's width, centred over the top face and
/// touching its plane at t = 0, pushed down by 5 % of the height over [0, t_ramp], then held.
RigidBody contact_sphere(const Mesh& mesh, double t_ramp) {
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& p : mesh.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double R = 0.3 * std::min(hi.x() - lo.x(), hi.y() - lo.y());
  RigidBody s =
      RigidBody::sphere("indenter", Vec3(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), hi.z() + R), R);
  s.displacement = Vec3(0.0, 0.0, -0.05 * (hi.z() - lo.z()));
  s.function = TimeFunction::ramp(0.0, t_ramp);
  return s;
}

json contact_record(const MeshCase& m, const std::string& step, int threads, Timing ns,
                    const std::string& linear, double dt, int active_nodes) {
  json r = step_record(m, step, "fast", "objective", threads, ns, false, linear);
  r["contact"] = "sphere";
  r["dt"] = dt;
  r["active_nodes"] = active_nodes;
  return r;
}

/// Explicit central differences of the fast objective viscoelastic model (fast_threads = threads,
/// energy bookkeeping off) with kinematic contact (KinematicContact, as the case runner steps it),
/// the sphere pressed in over `ramp` steps before the measurement, then held in contact while measured.
void explicit_contact_records(const MeshCase& m, const BenchOptions& o,
                              const std::function<void(json)>& log) {
  const double cp = std::sqrt((kStepMaterial.lambda + 2 * kStepMaterial.mu) / 1000.0);
  const double dt = 0.3 * m.h_min / cp;
  const int ramp = o.quick ? 20 : 200;
  {
    // The same step without the body (1 thread), measured in the same run: what contact adds.
    StepProblem p(m, step_model(m, "fast", "objective", 1, false));
    CentralDifference integ(*p.system, dt, false);
    integ.initialize(0.0, VecX::Zero(p.system->num_dofs()), VecX::Zero(p.system->num_dofs()));
    double t = 0.0;
    const Timing ns = measure_ns(
        [&] {
          integ.step(t, dt);
          t = integ.time();
        },
        o.min_time);
    json r = contact_record(m, "explicit", 1, ns, "none", dt, 0);
    r["contact"] = "none";
    log(r);
  }
  for (int threads = 1; threads <= o.max_threads; ++threads) {
    StepProblem p(m, step_model(m, "fast", "objective", threads, false));
    CentralDifference integ(*p.system, dt, false);
    const VecX zero = VecX::Zero(p.system->num_dofs());
    integ.initialize(0.0, zero, zero);
    KinematicContact contact(*p.system, m.mesh, {contact_sphere(m.mesh, ramp * dt)}, ContactOptions{}, 0.0,
                             zero);
    double t = 0.0;
    const auto step = [&] {
      integ.step(t, dt);
      t = integ.time();
      integ.correct(contact.correct(t, dt, integ.displacement()));
    };
    for (int k = 0; k < ramp; ++k) step();
    const Timing ns = measure_ns(step, o.min_time);
    json r =
        contact_record(m, "explicit_contact", threads, ns, "none", dt, contact.state().at(0).active_nodes);
    r["dt_critical"] = integ.stability().dt_critical;
    log(r);
  }
}

/// Implicit Newmark steps of dt = 1 ms (a haptic-rate step) of the same model with the
/// augmented-Lagrangian contact (ContactImplicitDynamics), with each sparse direct solver.
void implicit_contact_records(const MeshCase& m, const BenchOptions& o,
                              const std::function<void(json)>& log) {
  const double dt = 1e-3;
  const int ramp = o.quick ? 2 : 5;
  for (const auto& [linear, kind] : {std::pair{std::string("ldlt"), NewtonLinearSolver::Direct},
                                     std::pair{std::string("cholmod"), NewtonLinearSolver::Cholmod}}) {
    NewtonOptions no;
    no.linear_solver = kind;
    StepProblem p(m, step_model(m, "fast", "objective", 1, false));
    ContactImplicitDynamics integ(*p.system, m.mesh, {contact_sphere(m.mesh, ramp * dt)}, ContactOptions{},
                                  ImplicitScheme::Newmark, no, dt);
    const VecX zero = VecX::Zero(p.system->num_dofs());
    integ.initialize(0.0, zero, zero);
    int active = 0;
    const auto step = [&] { active = integ.step(integ.time(), dt).bodies.at(0).active_nodes; };
    Timing ns;
    try {
      for (int k = 0; k < ramp; ++k) step();
      ns = measure_ns(step, o.min_time);
    } catch (const Error& e) {  // a step that does not converge: no record, the rest of the suite runs
      if (o.log)
        *o.log << "  " << m.name << " implicit_contact " << linear << ": not measured (" << e.what() << ")\n";
      continue;
    }
    json r = contact_record(m, "implicit_contact", 1, ns, linear, dt, active);
    r["linear_fallbacks_to_ldlt"] = integ.contact().linear_solver().fallbacks();
    log(r);
  }
}

/// The contact ladder's records ("step": explicit_contact | implicit_contact, "contact": "sphere",
/// "dt", "active_nodes"; and "step": explicit, "contact": "none", the same explicit step without the
/// body, 1 thread); the implicit ones on the smallest cube only: one implicit contact step
/// (Newton inside the Uzawa loop, a factorisation per Newton iteration) costs hundreds of ms there
/// already, so no larger mesh can hold a 1 ms implicit step.
void contact_step_records(const BenchOptions& o, json& records) {
  const auto log = [&](const json& r) {
    if (o.log)
      *o.log << "  " << r["mesh"].get<std::string>() << " " << r["step"].get<std::string>() << " "
             << r["linear"].get<std::string>() << " " << r["threads"].get<int>()
             << "t: " << r["us_per_step"].get<double>() << " us/step, " << r["active_nodes"].get<int>()
             << " nodes in contact\n";
    records.push_back(r);
  };
  for (const auto& c : contact_cells(o.quick)) {
    check_interrupt("bench: stopped before the contact records");
    const int tets = 6 * c[0] * c[1] * c[2];
    const MeshCase m = cube("contact_" + std::to_string(tets), c[0], c[1], c[2]);
    if (o.log) *o.log << "tmlab bench: " << m.name << " (contact steps)\n";
    explicit_contact_records(m, o, log);
    if (tets <= 3000) implicit_contact_records(m, o, log);
  }
}

}  // namespace

std::vector<std::string> bench_mesh_names() {
  return {"liver", "cube_2k", "cube_24k", "cube_240k", "cube_2m", "contact"};
}

std::string check_bench_meshes(const BenchOptions& o) {
  const std::vector<std::string> known = bench_mesh_names();
  for (const std::string& name : o.meshes) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      return "--meshes: unknown mesh '" + name + "' (known: " + list + ")";
    }
    if (name == "cube_2m" && !o.large) return "--meshes: 'cube_2m' needs --large";
    if (o.quick && (name == "cube_24k" || name == "cube_240k"))
      return "--meshes: '" + name + "' is not measured with --quick";
  }
  return "";
}

json run_bench(const BenchOptions& o) {
  if (o.max_threads < 1) throw Error("bench: --threads must be >= 1");
  if (const std::string bad = check_bench_meshes(o); !bad.empty()) throw Error("bench: " + bad);
  int argc = 1;
  char name[] = "tmlab";
  char* argv[] = {name, nullptr};
  benchmark::Initialize(&argc, argv);

  json out;
  if (o.log) *o.log << "tmlab bench: machine limits\n";
  const MachineLimits lim =
      o.quick ? measure_machine_limits(0.02, std::size_t(96) << 20) : measure_machine_limits();
  out["limits"] = {{"peak_gflops_1t", lim.peak_gflops_1t},
                   {"peak_gflops_2t", lim.peak_gflops_2t},
                   {"triad_gbs_1t", lim.triad_gbs_1t},
                   {"triad_gbs_2t", lim.triad_gbs_2t}};
  json records = json::array(), meshes = json::array();
  std::vector<std::pair<std::string, std::function<MeshCase()>>> cases;
  const std::filesystem::path liver = std::filesystem::path(o.tmlab_root) / "meshes" / "liver.msh";
  cases.emplace_back("liver", [liver] { return make_case("liver", read_mesh(liver.string())); });
  cases.emplace_back("cube_2k", [] { return cube("cube_2k", 7, 7, 8); });
  if (!o.quick) {
    cases.emplace_back("cube_24k", [] { return cube("cube_24k", 16, 16, 16); });
    cases.emplace_back("cube_240k", [] { return cube("cube_240k", 34, 34, 34); });
    if (o.large) cases.emplace_back("cube_2m", [] { return cube("cube_2m", 74, 74, 74); });
  }
  const auto selected = [&o](const std::string& mesh) {
    return o.meshes.empty() || std::find(o.meshes.begin(), o.meshes.end(), mesh) != o.meshes.end();
  };
  for (const auto& [mesh_name, make] : cases) {
    if (!selected(mesh_name)) continue;
    check_interrupt("bench: stopped before the " + mesh_name + " records");
    const MeshCase m = make();
    if (o.log) *o.log << "tmlab bench: " << m.name << " (" << m.mesh.num_tets() << " tets)\n";
    meshes.push_back({{"name", m.name}, {"tets", m.mesh.num_tets()}, {"nodes", m.mesh.num_points()}});
    force_records(m, o, records);
    const bool small = m.mesh.num_tets() <= 30000;
    if (m.mesh.num_tets() <= 300000) step_records(m, o, small, records);
  }
  if (selected("contact")) contact_step_records(o, records);
  out["records"] = records;
  out["meshes"] = meshes;
  out["options"] = {{"quick", o.quick},
                    {"large", o.large},
                    {"max_threads", o.max_threads},
                    {"min_time", o.min_time},
                    {"meshes", o.meshes}};
  return out;
}

}  // namespace tmlab::tm
