// The stepping of a run: see stepping.hpp.
#include "runner/stepping.hpp"

#include "runner/case_runner.hpp"
#include "runner/contact_stepping.hpp"
#include "runner/linear_solve_log.hpp"
#include "runner/newton_log.hpp"
#include "tensormass/solvers/implicit_dynamics.hpp"
#include "tensormass/solvers/static_solver.hpp"

#include <algorithm>

namespace tmlab::tm::runner {

namespace {

/// Static load stepping: solver.steps increments of the load factor t = t_end k / steps.
nlohmann::json step_static(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                           RunCheckpoint& ck) {
  const CaseConfig& cfg = p.cfg;
  const int n_steps = cfg.solver.steps;
  StaticSolver solver(p.system, newton_options(cfg.solver), cfg.solver.max_cutbacks);
  NewtonLog newton_log;
  long total_newton = 0, total_cutbacks = 0;
  double t = 0.0;
  const LoopState loop{s, t, &newton_log, &total_newton, &total_cutbacks, nullptr, nullptr};
  for (int k = ck.restore(rec, loop) + 1; k <= n_steps; ++k) {
    const double t0 = cfg.solver.t_end * (k - 1) / n_steps, t1 = cfg.solver.t_end * k / n_steps;
    const StaticStepReport rep = solver.advance(t0, t1, s.u);
    total_newton += rep.newton_iterations;
    total_cutbacks += rep.cutbacks;
    newton_log.add(rep.newton, rep.newton_iterations, rep.cutbacks, rep.sub_increments, rep.at_roundoff);
    newton_log.set_linear(solver.linear_solver().stats());
    rec.record(k, t1, s.u, s.v, rep.newton_iterations, field_step(cfg, k));
    t = t1;
    ck.after_step(k, rec, loop);
    progress(k, t1);
  }
  return {{"type", "static"},
          {"load_steps", n_steps},
          {"newton_iterations", total_newton},
          {"cutbacks", total_cutbacks},
          {"newton", newton_log.json(cfg.solver)},
          {"linear_solver", linear_solver_json(cfg.solver, newton_log.linear())}};
}

/// Explicit central differences; the series at most every steps/4000 steps, the fields as asked.
nlohmann::json step_explicit(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                             RunCheckpoint& ck) {
  const CaseConfig& cfg = p.cfg;
  const int n_steps = cfg.solver.steps;
  const double dt = cfg.solver.dt;
  CentralDifference integ(p.system, dt, cfg.solver.check_stability);
  integ.set_displacement_limit(10.0 * p.size);
  integ.initialize(0.0, s.u, s.v);
  const int series_every = std::max(1, n_steps / 4000);
  double t = 0.0;
  const LoopState loop{s, t, nullptr, nullptr, nullptr, &integ, nullptr};
  for (int k = ck.restore(rec, loop) + 1; k <= n_steps; ++k) {
    integ.step(t, dt);
    t = integ.time();
    const bool fields = field_step(cfg, k);
    if (fields || k % series_every == 0) {
      s.u = integ.displacement();
      s.v = integ.velocity();
      rec.record(k, t, s.u, s.v, 0, fields);
      ck.after_step(k, rec, loop);
      progress(k, t);
    }
  }
  return explicit_summary(cfg, integ.stability());
}

/// Implicit dynamics (backward Euler or Newmark), steps of solver.dt up to t_end.
nlohmann::json step_implicit(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                             RunCheckpoint& ck) {
  const CaseConfig& cfg = p.cfg;
  const int n_steps = cfg.solver.steps;
  const ImplicitScheme scheme = cfg.solver.scheme;
  ImplicitDynamics integ(p.system, scheme, newton_options(cfg.solver));
  NewtonLog newton_log;
  long total_newton = 0;
  integ.initialize(0.0, s.u, s.v);
  double t = 0.0;
  const LoopState loop{s, t, &newton_log, &total_newton, nullptr, nullptr, &integ};
  for (int k = ck.restore(rec, loop) + 1; k <= n_steps; ++k) {
    const double dt = std::min(cfg.solver.dt, cfg.solver.t_end - t);
    const NewtonResult nr = integ.step(t, dt);
    t = integ.time();
    total_newton += nr.iterations;
    newton_log.add(nr, nr.iterations, 0, 1, nr.at_roundoff);
    newton_log.set_linear(integ.linear_solver().stats());
    s.u = integ.displacement();
    s.v = integ.velocity();
    rec.record(k, t, s.u, s.v, nr.iterations, field_step(cfg, k));
    ck.after_step(k, rec, loop);
    progress(k, t);
  }
  return {{"type", "implicit"},
          {"scheme", to_string(cfg.solver.scheme)},
          {"dt", cfg.solver.dt},
          {"steps", n_steps},
          {"newton_iterations", total_newton},
          {"newton", newton_log.json(cfg.solver)},
          {"linear_solver", linear_solver_json(cfg.solver, newton_log.linear())},
          {"damping", {{"alpha", cfg.solver.damping_alpha}, {"beta", cfg.solver.damping_beta}}}};
}

}  // namespace

bool field_step(const CaseConfig& cfg, int k) { return k % cfg.output.every == 0 || k == cfg.solver.steps; }

/// The summary's solver block of an explicit run: the step, the stability estimate, the damping.
nlohmann::json explicit_summary(const CaseConfig& cfg, const StabilityEstimate& st) {
  return {{"type", "explicit"},
          {"scheme", "central_difference"},
          {"dt", cfg.solver.dt},
          {"steps", cfg.solver.steps},
          {"dt_critical_estimate", st.dt_critical},
          {"dt_guaranteed", st.dt_guaranteed},
          {"omega_max", st.omega_max},
          {"damping", {{"alpha", cfg.solver.damping_alpha}, {"beta", cfg.solver.damping_beta}}}};
}

/// Steps the case's solver from rest, recording t = 0 first; returns the summary's solver block.
nlohmann::json step(const Problem& p, StepRecorder& rec, std::ostream* log, RunCheckpoint& ck) {
  Progress progress(p.cfg, log);
  State s{VecX::Zero(p.system.num_dofs()), VecX::Zero(p.system.num_dofs())};
  if (p.cfg.contact.enabled) {
    nlohmann::json info = step_contact(p, rec, progress, s, ck);
    progress.finish();
    return info;
  }
  if (!ck.resuming()) rec.record(0, 0.0, s.u, s.v, 0, true);  // resumed: the checkpoint holds it
  nlohmann::json solver_info;
  if (p.cfg.solver.type == SolverSpec::Type::Static)
    solver_info = step_static(p, rec, progress, s, ck);
  else if (p.cfg.solver.type == SolverSpec::Type::Explicit)
    solver_info = step_explicit(p, rec, progress, s, ck);
  else
    solver_info = step_implicit(p, rec, progress, s, ck);
  progress.finish();
  return solver_info;
}

}  // namespace tmlab::tm::runner
