// Work-precision study (work_precision.hpp).
#include "studies/workprecision/work_precision.hpp"

#include "core/base/format.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/base/stopwatch.hpp"
#include "core/config/config_reader.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "reference_fem/sundials/ode_references.hpp"
#include "studies/common/liver_problem.hpp"
#include "studies/common/study_plot.hpp"
#include "tensormass/solvers/explicit_dynamics.hpp"
#include "tensormass/solvers/implicit_dynamics.hpp"
#include "tensormass/system/lumped_mass.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <ostream>
#include <sstream>

namespace tmlab::tm {
namespace {

constexpr double kPi = 3.14159265358979323846;
using Integ = ViscoelasticOptions::Integration;

/// One problem: mesh, long-term material, Prony series, density, constraints, loads, times, and the
/// component scales of the SUNDIALS absolute tolerances.
struct Setup {
  std::string name, description;
  Mesh mesh;
  StVenantKirchhoff material;
  PronySeries prony = PronySeries::from_long_term({0.0}, {1.0});
  double density = 1000.0;
  std::vector<DirichletCondition> bcs;
  std::vector<NodalForce> forces;
  double t_end = 0.0, t_out = 0.0;
  double u_scale = 1e-3, v_scale = 0.05, z_scale = 100.0;  ///< m, m/s, Pa
};

/// The probe pulse: a raised cosine (1 - cos(2 pi t / T))/2, press and release over [0, T] (smooth:
/// the problems end at t = T, where load, its rate and the acceleration it drives are back to 0).
TimeFunction pulse(double T) { return TimeFunction::sine(0.5, 1.0 / T, -kPi / 2.0, 0.5); }

/// The load of a problem: `force` on `nodes` as a pulse over [0, T], the problem's end; outputs every t_out.
void add_pulse(Setup& s, const std::string& name, std::vector<Index> nodes, const Vec3& force, double T,
               double t_out) {
  NodalForce f;
  f.name = name;
  f.nodes = std::move(nodes);
  f.force = force;
  f.function = pulse(T);
  s.forces.push_back(f);
  s.t_end = T;
  s.t_out = t_out;
}

Setup liver_setup(const std::string& root) {
  const std::string where = (std::filesystem::path(root) / "cases" / "paper" / "xu2011_liver.json").string();
  const nlohmann::json p = ConfigReader::parse_file(where);
  LiverProblem liver = liver_problem(p, where, root);
  Setup s;
  s.name = "liver";
  s.mesh = std::move(liver.mesh);
  s.material = liver.material;
  s.density = liver.density;
  s.prony = liver.prony;
  s.bcs.push_back(std::move(liver.base));
  const auto node = p.at("fig5").at("node").get<std::vector<double>>();
  NodeSelector patch;
  patch.kind = NodeSelector::Kind::Sphere;
  patch.center = Vec3(node.at(0), node.at(1), node.at(2));
  patch.radius = p.at("fig5").at("patch_radius").get<double>();
  // 0.2 N, the largest creep force of fig5, over 80 ms.
  add_pulse(s, "probe", select_nodes(s.mesh, patch), Vec3(0.0, 0.0, -0.2), 0.08, 0.005);
  s.u_scale = 2e-3;
  s.v_scale = 0.1;
  s.z_scale = 100.0;
  std::ostringstream d;
  d << "liver (" << s.mesh.num_points() << " nodes, " << s.mesh.tets.size()
    << " tets), E_inf = " << liver.young << " Pa, nu = " << liver.poisson << ", rho = " << s.density
    << ", Prony of cases/paper/xu2011_liver.json, base fixed; 0.2 N on the nodes within "
    << patch.radius * 100 << " cm of the fig5 probe node, raised-cosine pulse over 80 ms; t_end 80 ms";
  s.description = d.str();
  return s;
}

Setup incompressible_setup(bool quick) {
  // A slow pulse (0.2 s, far longer than the elastic wave periods): the response is smooth, but
  // explicit stepping is held to the compressional-wave limit, ~7x below the shear-wave one at nu = 0.49.
  Setup s;
  s.name = "incompressible";
  const int nx = quick ? 3 : 12, ny = quick ? 1 : 4;
  s.mesh = make_box_mesh(Vec3::Zero(), Vec3(0.03, 0.01, 0.01), nx, ny, ny);
  s.material = StVenantKirchhoff::from_young_poisson(5e3, 0.49);
  s.prony = PronySeries::from_long_term({1.0, 0.5}, {0.01, 0.1});
  NodeSelector clamp_sel;
  clamp_sel.kind = NodeSelector::Kind::Plane;
  clamp_sel.axis = 0;
  clamp_sel.value = 0.0;
  clamp_sel.tol = 1e-9;
  DirichletCondition clamp;
  clamp.name = "clamp";
  clamp.nodes = select_nodes(s.mesh, clamp_sel);
  s.bcs.push_back(clamp);
  NodeSelector tip_sel = clamp_sel;
  tip_sel.value = 0.03;
  add_pulse(s, "tip", select_nodes(s.mesh, tip_sel), Vec3(0.0, 0.0, -2e-3), 0.2, 0.02);
  s.u_scale = 1e-3;
  s.v_scale = 0.01;
  s.z_scale = 100.0;
  std::ostringstream d;
  d << "cantilever 3 x 1 x 1 cm (" << nx << "x" << ny << "x" << ny << " cells, " << s.mesh.num_points()
    << " nodes, " << s.mesh.tets.size()
    << " tets), E_inf = 5 kPa, nu = 0.49, rho = 1000, Prony alpha (1, 0.5), tau (10, 100) ms, "
    << "clamped at x = 0; 2 mN on the free end, raised-cosine pulse over 200 ms; t_end 200 ms";
  s.description = d.str();
  return s;
}

/// Model, system and ODE of one run (the ViscoelasticStVK model is used by the fixed-step solvers,
/// the ODE by SUNDIALS; both are built so that the set-up cost is part of each run's CPU time).
struct Instance {
  ViscoelasticStVK model;
  MechanicalSystem system;
  Instance(const Setup& s, Integ integration)
      : model(s.mesh, s.material, s.prony, options(integration)),
        system(model, lumped_dof_mass(lumped_node_mass(s.mesh, s.density)),
               DirichletSet(s.mesh.num_points(), s.bcs), loads(s)) {}
  static ViscoelasticOptions options(Integ integration) {
    ViscoelasticOptions o;
    o.history = ViscoelasticOptions::History::Pk2;
    o.relaxation = ViscoelasticOptions::Relaxation::Full;
    o.integration = integration;
    o.energy_bookkeeping = false;
    return o;
  }
  static ExternalLoads loads(const Setup& s) {
    ExternalLoads l(s.mesh, lumped_node_mass(s.mesh, s.density));
    for (const NodalForce& f : s.forces) l.add(f);
    return l;
  }
};

int outputs(const Setup& s) { return static_cast<int>(std::lround(s.t_end / s.t_out)); }

/// The point of a run before it is made: what runs, with which step or tolerance.
WorkPrecisionPoint point_of(const std::string& family, const std::string& method,
                            const std::string& parameter, double value) {
  WorkPrecisionPoint pt;
  pt.family = family;
  pt.method = method;
  pt.parameter = parameter;
  pt.value = value;
  return pt;
}

/// The study's checkpoint: every finished unit (a problem's reference, a run's point) by key,
/// written after each one; on --resume the units of the interrupted study are found here.
class StudyCheckpoint {
 public:
  explicit StudyCheckpoint(const WorkPrecisionOptions& o) : o_(o) {
    if (o.resume) data_ = *o.resume;
  }
  std::optional<WorkPrecisionPoint> point(const std::string& key) const {
    if (!data_.has(key + ".num")) return std::nullopt;
    const std::vector<double>& v = data_.doubles(key + ".num");
    const nlohmann::json t = nlohmann::json::parse(data_.text(key + ".text"));
    if (v.size() != 9 || t.size() != 4) throw Error(data_.source() + ": bad entry " + key);
    WorkPrecisionPoint p;
    p.method = t[0], p.family = t[1], p.parameter = t[2], p.failure = t[3];
    p.value = v[0], p.error = v[1], p.cpu_seconds = v[2], p.wall_seconds = v[3];
    p.steps = static_cast<long>(v[4]), p.rhs_evals = static_cast<long>(v[5]);
    p.newton_iterations = static_cast<long>(v[6]), p.linear_iterations = static_cast<long>(v[7]);
    p.preconditioner_setups = static_cast<long>(v[8]);
    return p;
  }
  void put_point(const std::string& key, const WorkPrecisionPoint& p) {
    data_.put(key + ".num",
              std::vector<double>{
                  p.value, p.error, p.cpu_seconds, p.wall_seconds, static_cast<double>(p.steps),
                  static_cast<double>(p.rhs_evals), static_cast<double>(p.newton_iterations),
                  static_cast<double>(p.linear_iterations), static_cast<double>(p.preconditioner_setups)});
    data_.put_text(key + ".text", nlohmann::json::array({p.method, p.family, p.parameter, p.failure}).dump());
  }
  /// A reference trajectory (the displacements at the output times).
  bool trajectory(const std::string& key, std::vector<VecX>& us) const {
    if (!data_.has(key + ".u")) return false;
    const std::vector<double>& flat = data_.doubles(key + ".u");
    const auto n = static_cast<std::size_t>(data_.integer(key + ".n"));
    us.clear();
    if (n == 0 || flat.size() % n != 0) throw Error(data_.source() + ": bad entry " + key);
    const std::size_t size = flat.size() / n;
    for (std::size_t i = 0; i < n; ++i)
      us.push_back(Eigen::Map<const VecX>(flat.data() + i * size, static_cast<Eigen::Index>(size)));
    return true;
  }
  void put_trajectory(const std::string& key, const std::vector<VecX>& us) {
    std::vector<double> flat;
    for (const VecX& u : us) flat.insert(flat.end(), u.data(), u.data() + u.size());
    data_.put(key + ".u", flat);
    data_.put_int(key + ".n", static_cast<std::int64_t>(us.size()));
  }
  /// Writes the checkpoint (when the study has one), then stops here if a signal is pending.
  void commit(const std::string& after) {
    if (o_.checkpoint.empty()) return;
    write_checkpoint(o_.checkpoint, "workprecision", o_.fingerprint, data_);
    check_interrupt("after " + after + "; the finished runs are in the checkpoint " + o_.checkpoint.string() +
                    ": continue with the same command and --resume");
  }

 private:
  const WorkPrecisionOptions& o_;
  CheckpointData data_;
};

/// "explicit + midpoint", "newmark + exact_linear": a fixed-step method by solver and recursion.
std::string fixed_step_method(const std::string& solver, Integ integ) {
  return solver + " + " + ViscoelasticOptions::to_string(integ);
}

/// The CPU and wall time of a run since `timer` started.
void stop_clock(WorkPrecisionPoint& pt, const Stopwatch& timer) {
  pt.cpu_seconds = timer.cpu();
  pt.wall_seconds = timer.wall();
}

/// A fixed-step run of the point's method at dt = pt.value: the solver `make(system)` builds, started at
/// rest and advanced by `step(solver, t, pt)` per step, u recorded at each output time into `us`; the
/// model set-up counts in the point's time. Fills steps and the clocks.
template <class Make, class Step>
WorkPrecisionPoint run_fixed_step(const Setup& s, Integ integ, WorkPrecisionPoint pt, std::vector<VecX>& us,
                                  Make&& make, Step&& step) {
  const double dt = pt.value;
  const Stopwatch timer;
  Instance in(s, integ);
  const auto solver = make(in.system);
  const Index n = in.system.num_dofs();
  solver->initialize(0.0, VecX::Zero(n), VecX::Zero(n));
  const long per = std::lround(s.t_out / dt);
  us.clear();
  for (int k = 1; k <= outputs(s); ++k) {
    for (long i = 0; i < per; ++i, ++pt.steps) step(*solver, pt.steps * dt, pt);
    us.push_back(solver->displacement());
  }
  stop_clock(pt, timer);
  return pt;
}

/// Runs the SUNDIALS integrator; fills `us` with u at the output times.
WorkPrecisionPoint run_sundials(const Setup& s, OdeMethod m, LinearSolverKind k, double rtol,
                                std::vector<VecX>& us, int order = 0) {
  WorkPrecisionPoint pt = point_of("sundials", "", "rtol", rtol);
  const Stopwatch timer;
  Instance in(s, Integ::ExactLinear);
  TensorMassViscoelasticOde ode(s.mesh, s.material, s.prony, Instance::options(Integ::ExactLinear),
                                in.system);
  OdeOptions o;
  o.rtol = rtol;
  o.linear = k;
  o.order = order;
  // atol = 1e-3 rtol of the component scales (sundials-references.md 5: z crosses zero)
  o.atol_vector =
      ode.absolute_tolerances(1e-3 * rtol * s.u_scale, 1e-3 * rtol * s.v_scale, 1e-3 * rtol * s.z_scale);
  const Index n = ode.num_dofs();
  OdeIntegrator integ(ode, m, o, 0.0, ode.initial_state(0.0, VecX::Zero(n), VecX::Zero(n)));
  pt.method = integ.describe();
  us.clear();
  VecX y;
  for (int k_out = 1; k_out <= outputs(s); ++k_out) {
    const double t = k_out * s.t_out;
    integ.advance(t, y);
    us.push_back(ode.displacement(t, y));
  }
  stop_clock(pt, timer);
  const IntegratorStats st = integ.stats();
  pt.steps = st.steps;
  pt.rhs_evals = st.rhs_evals + st.explicit_rhs_evals;
  pt.newton_iterations = st.nonlinear_iterations;
  pt.linear_iterations = st.linear_iterations;
  pt.preconditioner_setups = st.preconditioner_setups;
  return pt;
}

WorkPrecisionPoint run_explicit(const Setup& s, Integ integ, double dt, std::vector<VecX>& us) {
  WorkPrecisionPoint pt = run_fixed_step(
      s, integ, point_of("explicit", fixed_step_method("explicit", integ), "dt", dt), us,
      [dt](const MechanicalSystem& system) {
        auto cd = std::make_unique<CentralDifference>(system, dt);
        cd->set_displacement_limit(
            1.0);  // 1 m: no stable run of these centimetre-scale problems gets near it
        return cd;
      },
      [dt](CentralDifference& cd, double t, WorkPrecisionPoint&) { cd.step(t, dt); });
  pt.rhs_evals = pt.steps;
  return pt;
}

WorkPrecisionPoint run_implicit(const Setup& s, Integ integ, double dt, std::vector<VecX>& us) {
  WorkPrecisionPoint pt = run_fixed_step(
      s, integ, point_of("implicit", fixed_step_method("newmark", integ), "dt", dt), us,
      [](const MechanicalSystem& system) {
        // Newton to 1e-10 of the force scale: far below every error measured here.
        return std::make_unique<ImplicitDynamics>(system, ImplicitScheme::Newmark,
                                                  NewtonOptions{40, 1e-10, 1e-15});
      },
      [dt](ImplicitDynamics& im, double t, WorkPrecisionPoint& p) {
        const NewtonResult r = im.step(t, dt);
        p.newton_iterations += r.iterations;
        p.rhs_evals += 2 + r.iterations + r.backtracks;
      });
  pt.linear_iterations = pt.newton_iterations;  // one sparse direct solve per Newton iteration
  return pt;
}

double error_against(const std::vector<VecX>& us, const std::vector<VecX>& ref, double scale) {
  double e = 0.0;
  for (std::size_t k = 0; k < ref.size(); ++k) e = std::max(e, (us.at(k) - ref[k]).cwiseAbs().maxCoeff());
  return e / scale;
}

std::string fmt(double v) { return significant(v, 3); }

void log_point(std::ostream* log, const std::string& problem, const WorkPrecisionPoint& p) {
  if (!log) return;
  *log << "[workprecision] " << problem << ": " << p.method << ", " << p.parameter << " "
       << scientific(p.value, 3) << ": ";
  if (p.failure.empty())
    *log << "error " << scientific(p.error, 2) << ", cpu " << significant(p.cpu_seconds, 3) << " s, "
         << p.steps << " steps\n";
  else
    *log << "FAILED (" << p.failure << ")\n";
  log->flush();
}

}  // namespace

std::string method_slug(const std::string& method) {
  std::string out;
  for (char c : method) {
    if (std::isalnum(static_cast<unsigned char>(c)))
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else if (!out.empty() && out.back() != '_')
      out += '_';
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out;
}

std::vector<WorkPrecisionProblem> run_work_precision(const WorkPrecisionOptions& opt) {
  if (opt.problems.empty()) throw Error("workprecision: no problem chosen (liver, incompressible)");
  if (!(opt.reference_rtol > 0.0 && opt.reference_rtol < 1e-6))
    throw Error("workprecision: the reference rtol must be in (0, 1e-6), got " + fmt(opt.reference_rtol));
  std::vector<WorkPrecisionProblem> results;
  StudyCheckpoint ck(opt);
  for (const std::string& name : opt.problems) {
    Setup s;
    if (name == "liver")
      s = liver_setup(opt.tmlab_root);
    else if (name == "incompressible")
      s = incompressible_setup(opt.quick);
    else
      throw Error("workprecision: unknown problem '" + name + "' (expected liver or incompressible)");
    WorkPrecisionProblem P;
    P.name = s.name;
    P.description = s.description;
    P.nodes = s.mesh.num_points();
    P.tets = static_cast<Index>(s.mesh.tets.size());
    P.t_end = s.t_end;
    P.output_interval = s.t_out;
    {
      Instance in(s, Integ::ExactLinear);
      P.dt_critical = estimate_critical_time_step(in.system).dt_critical;
      TensorMassViscoelasticOde ode(s.mesh, s.material, s.prony, Instance::options(Integ::ExactLinear),
                                    in.system);
      P.ode_size = ode.size();
    }
    if (opt.log)
      *opt.log << "[workprecision] " << name << ": " << s.description << "; ODE size " << P.ode_size
               << ", explicit critical step " << scientific(P.dt_critical, 3) << " s\n";

    // Reference: CVODE BDF + preconditioned SPGMR at reference_rtol.
    std::vector<VecX> ref, us;
    const double ref_rtol = opt.quick ? std::max(opt.reference_rtol, 1e-9) : opt.reference_rtol;
    const std::string ref_key = "ref." + name;
    if (const auto done = ck.point(ref_key); done && ck.trajectory(ref_key, ref)) {
      P.reference = *done;
      if (opt.log)
        *opt.log << "[workprecision] " << name
                 << ": the reference from the checkpoint of the interrupted study\n";
    } else {
      P.reference =
          run_sundials(s, OdeMethod::CvodeBdf, LinearSolverKind::SpgmrPreconditioned, ref_rtol, ref);
      P.reference.error = 0.0;
      ck.put_point(ref_key, P.reference);
      ck.put_trajectory(ref_key, ref);
      ck.commit("the reference of " + name);
    }
    for (const VecX& u : ref) P.max_displacement = std::max(P.max_displacement, u.cwiseAbs().maxCoeff());
    if (!(P.max_displacement > 0.0))
      throw Error("workprecision: the reference of '" + name + "' does not move");
    if (opt.log)
      *opt.log << "[workprecision] " << name << ": reference " << P.reference.method << " rtol "
               << fmt(ref_rtol) << ": " << P.reference.steps << " steps, cpu "
               << fixed_point(P.reference.cpu_seconds, 2) << " s, max |u| " << fmt(P.max_displacement * 1e3)
               << " mm\n";

    // A run's point; a failing run keeps its plan (method, step or tolerance) and the reason.
    // Runs finished before an interruption are taken from the checkpoint (key: problem and index).
    auto record = [&](const std::function<WorkPrecisionPoint()>& run, const WorkPrecisionPoint& plan) {
      const std::string key = "run." + name + "." + std::to_string(P.points.size());
      if (const auto done = ck.point(key)) {
        if (done->method != plan.method || done->value != plan.value)
          throw Error(opt.resume->source() + ": run " + key + " is " + done->method + " at " +
                      fmt(done->value) + ", this study's is " + plan.method + " at " + fmt(plan.value) +
                      "; run without --resume");
        if (opt.log)
          *opt.log << "[workprecision] " << name << ": from the checkpoint of the interrupted study:\n";
        log_point(opt.log, name, *done);
        P.points.push_back(*done);
        return;
      }
      WorkPrecisionPoint pt;
      try {
        pt = run();
        pt.error = error_against(us, ref, P.max_displacement);
      } catch (const Interrupted&) {
        throw;
      } catch (const Error& e) {
        pt = plan;
        pt.failure = e.what();
      }
      log_point(opt.log, name, pt);
      P.points.push_back(pt);
      ck.put_point(key, pt);
      ck.commit(pt.method + " " + pt.parameter + " " + fmt(pt.value) + " of " + name);
    };

    // Fixed-step explicit: the largest dt dividing the output interval below 0.9 of the critical step,
    // then halved.
    const long n0 = static_cast<long>(std::ceil(s.t_out / (0.9 * P.dt_critical)));
    const int explicit_levels = opt.quick ? 1 : 3;
    for (Integ integ : {Integ::Midpoint, Integ::ExactLinear})
      for (int l = 0; l < explicit_levels; ++l) {
        const double dt = s.t_out / static_cast<double>(n0 << l);
        record([&] { return run_explicit(s, integ, dt, us); },
               point_of("explicit", fixed_step_method("explicit", integ), "dt", dt));
      }
    // Fixed-step implicit Newmark: dt = t_out / 1, 2, 4, ...
    const int implicit_levels = opt.quick ? 2 : 5;
    for (Integ integ : {Integ::Midpoint, Integ::ExactLinear})
      for (int l = 0; l < implicit_levels; ++l) {
        const double dt = s.t_out / static_cast<double>(1L << l);
        record([&] { return run_implicit(s, integ, dt, us); },
               point_of("implicit", fixed_step_method("newmark", integ), "dt", dt));
      }
    // SUNDIALS
    struct Sun {
      OdeMethod m;
      LinearSolverKind k;
      std::vector<double> rtols, quick_rtols;
      int order = 0;  // 0: the integrator's default (CVODE: BDF up to order 5)
    };
    const std::vector<Sun> suns = {
        {OdeMethod::CvodeBdf,
         LinearSolverKind::SpgmrPreconditioned,
         {1e-4, 1e-5, 1e-6, 1e-7, 1e-8},
         {1e-4, 1e-6}},
        // BDF limited to order 2 (A-stable; orders 3-5 are not, and lightly damped modes with
        // eigenvalues near the imaginary axis then hold the step by stability, not accuracy).
        {OdeMethod::CvodeBdf, LinearSolverKind::SpgmrPreconditioned, {1e-4, 1e-6, 1e-8}, {}, 2},
        {OdeMethod::CvodeBdf, LinearSolverKind::Spgmr, {1e-4, 1e-6, 1e-8}, {}},
        {OdeMethod::ArkodeDirk, LinearSolverKind::SpgmrPreconditioned, {1e-4, 1e-5, 1e-6}, {1e-4}},
        {OdeMethod::ArkodeImex, LinearSolverKind::Spgmr, {1e-4, 1e-6}, {}},
    };
    for (const Sun& su : suns)
      for (double rtol : opt.quick ? su.quick_rtols : su.rtols)
        record(
            [&] { return run_sundials(s, su.m, su.k, rtol, us, su.order); },
            point_of("sundials",
                     to_string(su.m) + (su.order > 0 ? " (max order " + std::to_string(su.order) + ")" : "") +
                         " + " + to_string(su.k),
                     "rtol", rtol));
    results.push_back(std::move(P));
  }
  return results;
}

void write_work_precision_h5(const std::vector<WorkPrecisionProblem>& problems, const std::string& path) {
  H5File f = H5File::create(path);
  f.set_attribute("/", "error_definition",
                  "max over output times t_k of |u(t_k) - u_ref(t_k)|_inf / max_k |u_ref(t_k)|_inf");
  f.set_attribute("/", "cpu_definition", "process CPU time (std::clock) of the run, model set-up included");
  for (const WorkPrecisionProblem& P : problems) {
    const std::string g = "/" + P.name;
    f.create_group(g);
    f.set_attribute(g, "description", P.description);
    f.set_attribute(g, "nodes", static_cast<std::int64_t>(P.nodes));
    f.set_attribute(g, "tets", static_cast<std::int64_t>(P.tets));
    f.set_attribute(g, "ode_size", static_cast<std::int64_t>(P.ode_size));
    f.set_attribute(g, "t_end", P.t_end);
    f.set_attribute(g, "output_interval", P.output_interval);
    f.set_attribute(g, "dt_critical", P.dt_critical);
    f.set_attribute(g, "max_displacement", P.max_displacement);
    f.set_attribute(g, "reference_method", P.reference.method);
    f.set_attribute(g, "reference_rtol", P.reference.value);
    f.set_attribute(g, "reference_cpu_seconds", P.reference.cpu_seconds);
    f.set_attribute(g, "reference_steps", static_cast<std::int64_t>(P.reference.steps));
    f.set_attribute(g, "reference_rhs_evals", static_cast<std::int64_t>(P.reference.rhs_evals));
    f.set_attribute(g, "reference_newton_iterations",
                    static_cast<std::int64_t>(P.reference.newton_iterations));
    f.set_attribute(g, "reference_linear_iterations",
                    static_cast<std::int64_t>(P.reference.linear_iterations));
    std::map<std::string, std::vector<const WorkPrecisionPoint*>> by;
    std::vector<std::string> order;
    for (const WorkPrecisionPoint& p : P.points) {
      if (!by.count(p.method)) order.push_back(p.method);
      by[p.method].push_back(&p);
    }
    for (const std::string& m : order) {
      const auto& pts = by[m];
      const std::string mg = g + "/" + method_slug(m);
      f.create_group(mg);
      f.set_attribute(mg, "method", m);
      f.set_attribute(mg, "family", pts.front()->family);
      f.set_attribute(mg, "parameter", pts.front()->parameter);
      auto col = [&](const char* ds, const std::function<double(const WorkPrecisionPoint&)>& get) {
        std::vector<double> v;
        for (const auto* p : pts) v.push_back(get(*p));
        f.write(mg + "/" + ds, v, {v.size()});
      };
      auto icol = [&](const char* ds, const std::function<long(const WorkPrecisionPoint&)>& get) {
        std::vector<std::int64_t> v;
        for (const auto* p : pts) v.push_back(get(*p));
        f.write(mg + "/" + ds, v, {v.size()});
      };
      col("value", [](const WorkPrecisionPoint& p) { return p.value; });
      col("error", [](const WorkPrecisionPoint& p) { return p.error; });
      col("cpu_seconds", [](const WorkPrecisionPoint& p) { return p.cpu_seconds; });
      col("wall_seconds", [](const WorkPrecisionPoint& p) { return p.wall_seconds; });
      icol("steps", [](const WorkPrecisionPoint& p) { return p.steps; });
      icol("rhs_evals", [](const WorkPrecisionPoint& p) { return p.rhs_evals; });
      icol("newton_iterations", [](const WorkPrecisionPoint& p) { return p.newton_iterations; });
      icol("linear_iterations", [](const WorkPrecisionPoint& p) { return p.linear_iterations; });
      icol("preconditioner_setups", [](const WorkPrecisionPoint& p) { return p.preconditioner_setups; });
    }
  }
  f.close();
}

std::string work_precision_table(const std::vector<WorkPrecisionProblem>& problems) {
  std::ostringstream os;
  for (const WorkPrecisionProblem& P : problems) {
    os << "### " << P.name << "\n\n"
       << P.description << ". ODE size " << P.ode_size << ", explicit critical step "
       << scientific(P.dt_critical, 3) << " s, max |u_ref| " << fmt(P.max_displacement * 1e3)
       << " mm. Reference: " << P.reference.method << " at rtol " << fmt(P.reference.value) << " ("
       << P.reference.steps << " steps, " << P.reference.newton_iterations << " Newton, "
       << P.reference.linear_iterations << " linear iterations, " << fixed_point(P.reference.cpu_seconds, 2)
       << " s CPU).\n\n"
       << "| method | dt [s] / rtol | error | CPU [s] | steps | f evals | Newton | linear | prec setups |\n"
       << "|---|---|---|---|---|---|---|---|---|\n";
    for (const WorkPrecisionPoint& p : P.points) {
      os << "| " << p.method << " | "
         << (p.parameter == "dt" ? scientific(p.value, 3) : scientific(p.value, 0)) << " | ";
      if (!p.failure.empty()) {
        os << "failed | " << significant(p.cpu_seconds, 3) << " | | | | | |\n";
        continue;
      }
      os << scientific(p.error, 2) << " | " << significant(p.cpu_seconds, 3) << " | " << p.steps << " | "
         << p.rhs_evals << " | " << p.newton_iterations << " | " << p.linear_iterations << " | "
         << p.preconditioner_setups << " |\n";
    }
    os << "\n";
    for (const WorkPrecisionPoint& p : P.points)
      if (!p.failure.empty())
        os << "* " << p.method << " at " << p.parameter << " " << fmt(p.value) << " failed: " << p.failure
           << "\n";
    os << "\n";
  }
  return os.str();
}

nlohmann::json write_work_precision(const std::vector<WorkPrecisionProblem>& problems,
                                    const std::string& command_line, const std::filesystem::path& dir,
                                    bool plots, const std::string& tmlab_root, std::ostream* warn) {
  write_work_precision_h5(problems, (dir / "workprecision.h5").string());
  std::ofstream(dir / "workprecision.md")
      << "# Work-precision tables\n\n"
      << "Command: `" << command_line << "`\n\n"
      << "Error: max over the output times of |u - u_ref|_inf / max |u_ref|_inf;"
      << " CPU: process CPU time of the run.\n\n"
      << work_precision_table(problems);
  std::string plot_status = "skipped";
  if (plots) {
    const ProcessStatus ps = draw_study_plot(tmlab_root, "workprecision", "tmlab_workprecision_plot.py", dir,
                                             ProcessOutput::to_file(dir / "plots.log"));
    plot_status = ps.ok() ? "ok" : "failed (see plots.log)";
    if (!ps.ok() && warn)
      *warn << "tmlab workprecision: warning: plotting failed (see plots.log); the numbers are in "
               "workprecision.h5\n";
  }
  nlohmann::json summary = {
      {"command", "workprecision"}, {"plots", plot_status}, {"problems", nlohmann::json::array()}};
  for (const auto& P : problems) {
    nlohmann::json pj = {{"name", P.name},
                         {"ode_size", P.ode_size},
                         {"dt_critical", P.dt_critical},
                         {"max_displacement_m", P.max_displacement},
                         {"reference",
                          {{"method", P.reference.method},
                           {"rtol", P.reference.value},
                           {"steps", P.reference.steps},
                           {"cpu_seconds", P.reference.cpu_seconds}}},
                         {"runs", P.points.size()}};
    long failed = 0;
    for (const auto& pt : P.points) failed += pt.failure.empty() ? 0 : 1;
    pj["failed_runs"] = failed;
    summary["problems"].push_back(pj);
  }
  return summary;
}

}  // namespace tmlab::tm
