// The stepping of a contact run: see contact_stepping.hpp.
#include "runner/contact_stepping.hpp"

#include "runner/case_runner.hpp"
#include "runner/contact_checkpoint.hpp"
#include "runner/contact_log.hpp"
#include "runner/linear_solve_log.hpp"
#include "runner/newton_log.hpp"
#include "runner/stepping.hpp"
#include "tensormass/contact/contact_checks.hpp"
#include "tensormass/contact/contact_config.hpp"
#include "tensormass/contact/contact_implicit.hpp"
#include "tensormass/contact/contact_solver.hpp"
#include "tensormass/contact/kinematic_contact.hpp"
#include "tensormass/solvers/explicit_dynamics.hpp"

#include <algorithm>

namespace tmlab::tm::runner {

namespace {

/// Static load stepping with contact (ContactStaticSolver: augmented Lagrangian or penalty around
/// the static Newton; a viscoelastic model's history advances once per accepted increment).
nlohmann::json step_static_contact(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                                   RunCheckpoint& ck) {
  const CaseConfig& cfg = p.cfg;
  const ContactSettings cs = contact_settings(cfg.contact, cfg.file);
  ContactStaticSolver solver(p.system, p.mesh, p.quadratic.get(), cs.bodies, cs.options,
                             newton_options(cfg.solver), 0.0, s.u, cfg.solver.max_cutbacks);
  check_contact_rig(p.mesh, solver.surface(), solver.bodies(), cs.options.max_initial_gap, 0.0,
                    cfg.solver.t_end, s.u);
  rec.set_contact(&solver.state());
  if (!ck.resuming()) rec.record(0, 0.0, s.u, s.v, 0, true);  // resumed: the checkpoint holds it
  const int n_steps = cfg.solver.steps;
  NewtonLog newton_log;
  ContactLog contact_log(cfg);
  long total_newton = 0, total_cutbacks = 0;
  double t = 0.0;
  const LoopState loop{s, t, &newton_log, &total_newton, &total_cutbacks, nullptr, nullptr};
  const ContactLoop contact{&solver, nullptr, nullptr, &contact_log};
  for (int k = ck.restore(rec, loop, &contact) + 1; k <= n_steps; ++k) {
    const double t0 = cfg.solver.t_end * (k - 1) / n_steps, t1 = cfg.solver.t_end * k / n_steps;
    const ContactStepReport rep = solver.advance(t0, t1, s.u);
    total_newton += rep.solver.newton_iterations;
    total_cutbacks += rep.solver.cutbacks;
    newton_log.add(rep.solver.newton, rep.solver.newton_iterations, rep.solver.cutbacks,
                   rep.solver.sub_increments, rep.solver.at_roundoff);
    newton_log.set_linear(solver.linear_solver().stats());
    contact_log.add(rep);
    rec.record(k, t1, s.u, s.v, rep.solver.newton_iterations, field_step(cfg, k));
    t = t1;
    ck.after_step(k, rec, loop, &contact);
    progress(k, t1);
  }
  return {{"type", "static"},
          {"load_steps", n_steps},
          {"newton_iterations", total_newton},
          {"cutbacks", total_cutbacks},
          {"newton", newton_log.json(cfg.solver)},
          {"linear_solver", linear_solver_json(cfg.solver, newton_log.linear())},
          {"contact", contact_log.json("augmented_lagrangian_static", solver.stiffness(), solver.gap_tol(),
                                       solver.state())}};
}

/// Explicit central differences with kinematic contact (KinematicContact: penetrating nodes are
/// put back on the body after each predictor; no stiffness, so the stable step is the sample's).
nlohmann::json step_explicit_contact(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                                     RunCheckpoint& ck) {
  const CaseConfig& cfg = p.cfg;
  const int n_steps = cfg.solver.steps;
  const double dt = cfg.solver.dt;
  const ContactSettings cs = contact_settings(cfg.contact, cfg.file);
  CentralDifference integ(p.system, dt, cfg.solver.check_stability);
  integ.set_displacement_limit(10.0 * p.size);
  KinematicContact contact(p.system, p.mesh, cs.bodies, cs.options, 0.0, s.u);
  check_contact_rig(p.mesh, contact.surface(), contact.bodies(), cs.options.max_initial_gap, 0.0,
                    cfg.solver.t_end, s.u);
  rec.set_contact(&contact.state());
  if (!ck.resuming()) rec.record(0, 0.0, s.u, s.v, 0, true);  // resumed: the checkpoint holds it
  integ.initialize(0.0, s.u, s.v);
  const int series_every = std::max(1, n_steps / 4000);
  double t = 0.0;
  const LoopState loop{s, t, nullptr, nullptr, nullptr, &integ, nullptr};
  const ContactLoop ckc{nullptr, &contact, nullptr, nullptr};
  for (int k = ck.restore(rec, loop, &ckc) + 1; k <= n_steps; ++k) {
    integ.step(t, dt);
    t = integ.time();
    integ.correct(contact.correct(t, dt, integ.displacement()));
    const bool fields = field_step(cfg, k);
    if (fields || k % series_every == 0) {
      s.u = integ.displacement();
      s.v = integ.velocity();
      rec.record(k, t, s.u, s.v, 0, fields);
      ck.after_step(k, rec, loop, &ckc);
      progress(k, t);
    }
  }
  nlohmann::json j = explicit_summary(cfg, integ.stability());
  j["contact"] = ContactLog(cfg).json("kinematic_explicit", 0.0, contact.gap_tol(), contact.state());
  return j;
}

/// Implicit dynamics with contact (ContactImplicitDynamics: the augmented-Lagrangian loop around the
/// implicit step's Newton solve).
nlohmann::json step_implicit_contact(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                                     RunCheckpoint& ck) {
  const CaseConfig& cfg = p.cfg;
  const int n_steps = cfg.solver.steps;
  const ContactSettings cs = contact_settings(cfg.contact, cfg.file);
  ContactImplicitDynamics integ(p.system, p.mesh, cs.bodies, cs.options, cfg.solver.scheme,
                                newton_options(cfg.solver), cfg.solver.dt, p.quadratic.get());
  integ.initialize(0.0, s.u, s.v);
  check_contact_rig(p.mesh, integ.contact().surface(), integ.contact().bodies(), cs.options.max_initial_gap,
                    0.0, cfg.solver.t_end, s.u);
  rec.set_contact(&integ.contact().state());
  if (!ck.resuming()) rec.record(0, 0.0, s.u, s.v, 0, true);  // resumed: the checkpoint holds it
  NewtonLog newton_log;
  ContactLog contact_log(cfg);
  long total_newton = 0;
  double t = 0.0;
  const LoopState loop{s, t, &newton_log, &total_newton, nullptr, nullptr, nullptr};
  const ContactLoop contact{&integ.contact(), nullptr, &integ, &contact_log};
  for (int k = ck.restore(rec, loop, &contact) + 1; k <= n_steps; ++k) {
    const double dt = std::min(cfg.solver.dt, cfg.solver.t_end - t);
    const ContactStepReport rep = integ.step(t, dt);
    t = integ.time();
    total_newton += rep.solver.newton_iterations;
    newton_log.add(rep.solver.newton, rep.solver.newton_iterations, 0, 1, rep.solver.at_roundoff);
    newton_log.set_linear(integ.contact().linear_solver().stats());
    contact_log.add(rep);
    s.u = integ.displacement();
    s.v = integ.velocity();
    rec.record(k, t, s.u, s.v, rep.solver.newton_iterations, field_step(cfg, k));
    ck.after_step(k, rec, loop, &contact);
    progress(k, t);
  }
  return {{"type", "implicit"},
          {"scheme", to_string(cfg.solver.scheme)},
          {"dt", cfg.solver.dt},
          {"steps", n_steps},
          {"newton_iterations", total_newton},
          {"newton", newton_log.json(cfg.solver)},
          {"linear_solver", linear_solver_json(cfg.solver, newton_log.linear())},
          {"damping", {{"alpha", cfg.solver.damping_alpha}, {"beta", cfg.solver.damping_beta}}},
          {"contact", contact_log.json("augmented_lagrangian_implicit", integ.contact().stiffness(),
                                       integ.contact().gap_tol(), integ.contact().state())}};
}

}  // namespace

/// Steps a case with a `contact` section (t = 0 recorded by the stepping function, once the
/// contact outputs exist).
nlohmann::json step_contact(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                            RunCheckpoint& ck) {
  if (p.cfg.solver.type == SolverSpec::Type::Static) return step_static_contact(p, rec, progress, s, ck);
  if (p.cfg.solver.type == SolverSpec::Type::Explicit) return step_explicit_contact(p, rec, progress, s, ck);
  return step_implicit_contact(p, rec, progress, s, ck);
}

}  // namespace tmlab::tm::runner
