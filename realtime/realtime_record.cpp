#include "realtime/realtime_record.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/interrupt.hpp"
#include "realtime/coupling_study.hpp"
#include "realtime/frame_renderer.hpp"
#include "realtime/realtime_loop.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>

namespace tmlab::rt {

namespace fs = std::filesystem;

nlohmann::json to_json(const ThreadTiming& t) {
  return {{"target_hz", t.target_hz},   {"rate_hz", t.rate_hz},         {"p50_us", t.p50_us},
          {"p99_us", t.p99_us},         {"p999_us", t.p999_us},         {"missed", t.missed},
          {"iterations", t.iterations}, {"busy_p50_us", t.busy_p50_us}, {"busy_p99_us", t.busy_p99_us},
          {"unrecorded", t.unrecorded}};
}

namespace {

std::string short_number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

}  // namespace

nlohmann::json record_realtime(const RealtimeCase& c, const RecordOptions& opt, const fs::path& dir) {
  const auto log = [&](const std::string& m) {
    if (opt.log) opt.log(m);
  };
  const double duration = opt.duration > 0.0 ? opt.duration : c.duration;

  // 1. The live run.
  log("preparing the control model (" + std::to_string(c.mesh.num_points()) +
      " nodes; the surface compliance of the local-model coupling)");
  auto control = c.make_control();
  check_interrupt("while preparing the control model, before the real-time run: nothing measured");
  LoopOptions lo;
  lo.duration = duration;
  lo.haptic_hz = c.haptic_hz;
  lo.visual_hz = c.visual_hz;
  lo.rendered = c.rendered;
  lo.trajectory = c.trajectory.get();
  lo.keep_frames = opt.frames;
  lo.frame_every = c.png_every;
  log("running the three threads for " + short_number(duration) + " s");
  const LoopResult r = run_realtime_loop(*control, lo);
  // A signal stops the three threads at their next tick: the run is cut short, so nothing is measured.
  check_interrupt("during the real-time run, stopped after " + significant(r.wall_time, 3) + " s of " +
                  short_number(duration) + " s: nothing measured");
  const double pace = r.model_time / duration;
  log("model time reached " + short_number(r.model_time) + " s in " + short_number(duration) +
      " s of wall time (" + short_number(std::round(100.0 * pace)) + " % of real time)" +
      (pace < 0.95 ? ": the control thread fell behind, and the live figures include that lag" : ""));

  // 2. Live coupling measures against the ground truth replayed on the probe path the haptic thread read
  // (the live run's model, reset).
  log("replaying the ground truth on the live run's probe path (" + std::to_string(r.t.size()) +
      " haptic ticks)");
  ControlModel& truth_model = *control;
  const std::vector<Vec3> truth = ground_truth(truth_model, r.x, c.substeps);
  const SchemeMetrics live_e = coupling_metrics(r.x, r.extrapolation, truth);
  const SchemeMetrics live_l = coupling_metrics(r.x, r.local_model, truth);

  // 3. The deterministic coupling study at the case's study control rate.
  const int every = static_cast<int>(std::lround(c.haptic_hz / c.study_control_hz));
  const double study_duration = std::min(duration, std::max(c.trajectory->duration(), 1.0 / c.haptic_hz));
  log("coupling study: control every " + std::to_string(every) + " haptic ticks over " +
      short_number(study_duration) + " s");
  const CouplingStudy s = run_coupling_study(truth_model, *c.trajectory, c.substeps, every, study_duration);
  // Passivity is judged over a closed path: say so when this run's duration cuts the path open.
  const bool closed = !s.x.empty() && (s.x.back() - s.x.front()).norm() <= 1e-9 * c.control.probe_radius;
  const ProbeTrajectory& path = *c.trajectory;
  if (!closed && (path.position(path.duration()) - path.start()).norm() > 1e-9 * c.control.probe_radius)
    log("warning: the trajectory does not end where it starts, so coupling_energy_J is the work over an open "
        "path, not a passivity measure");
  else if (!closed)
    log("warning: the study covers " + short_number(study_duration) + " s of the " +
        short_number(path.duration()) +
        " s trajectory, an open path, so coupling_energy_J is not a passivity measure; record with "
        "--duration " +
        short_number(path.duration()) + " or more for the whole (closed) path");

  // 4. forces.csv and the frames.
  {
    std::ofstream f(dir / "forces.csv");
    f << "# haptic ticks of the live run: time, probe centre, force of each coupling, ground truth (N)\n"
         "t,x,y,z,extrapolation_x,extrapolation_y,extrapolation_z,local_model_x,local_model_y,local_model_z,"
         "truth_x,truth_y,truth_z\n"
      << std::setprecision(10);
    for (std::size_t n = 0; n < r.t.size(); ++n) {
      f << r.t[n];
      for (const Vec3* v : {&r.x[n], &r.extrapolation[n], &r.local_model[n], &truth[n]})
        f << ',' << v->x() << ',' << v->y() << ',' << v->z();
      f << '\n';
    }
    if (!f) throw Error((dir / "forces.csv").string() + ": write failed");
  }
  int written = 0;
  if (opt.frames && !r.frames.empty()) {
    log("writing " + std::to_string(r.frames.size()) + " PNG frames");
    fs::create_directories(dir / "frames");
    FrameRenderer renderer(c.mesh, c.image_width, c.image_height);
    const std::vector<Vec3>& rendered =
        c.rendered == CouplingScheme::Extrapolation ? r.extrapolation : r.local_model;
    double fmax = 1e-3;
    for (const Vec3& f : rendered) fmax = std::max(fmax, f.norm());
    std::vector<double> history;
    for (std::size_t k = 0; k < r.frames.size(); ++k) {
      check_interrupt("while writing the PNG frames (" + std::to_string(k) + " of " +
                      std::to_string(r.frames.size()) + " written)");
      history.clear();
      for (std::size_t n = 0; n < r.t.size() && r.t[n] <= r.frame_t[k]; ++n)
        history.push_back(rendered[n].norm());
      // the strip spans the whole run; ticks after the frame stay empty (0)
      history.resize(r.t.size(), 0.0);
      const auto& img = renderer.render(r.frames[k], r.frame_probe[k], c.control.probe_radius,
                                        r.frame_force[k], 0.05 / fmax, history, fmax);
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04zu.png", k);
      write_png((dir / "frames" / name).string(), renderer.width(), renderer.height(), img);
      ++written;
    }
  }

  nlohmann::json doc;
  doc["case"] = c.name;
  doc["note"] =
      "wall-clock measurements on the machine that ran it (rates, jitter and missed deadlines depend on its "
      "load); "
      "haptic_force_error_rel and coupling_energy_J come from the deterministic coupling study and repeat "
      "exactly";
  doc["threads"] = {
      {"haptic", to_json(r.haptic)}, {"control", to_json(r.control)}, {"visual", to_json(r.visual)}};
  auto scheme = [](const SchemeMetrics& study, const SchemeMetrics& live) {
    return nlohmann::json{{"haptic_force_error_rel", study.force_error_rel},
                          {"coupling_energy_J", study.coupling_energy_J},
                          {"force_error_max_N", study.force_error_max_N},
                          {"live_haptic_force_error_rel", live.force_error_rel},
                          {"live_coupling_energy_J", live.coupling_energy_J}};
  };
  doc["couplings"] = {{"extrapolation", scheme(s.extrapolation_metrics, live_e)},
                      {"local_model", scheme(s.local_model_metrics, live_l)}};
  doc["rendered_coupling"] = to_string(c.rendered);
  doc["study"] = {{"haptic_hz", c.haptic_hz},           {"control_hz", c.study_control_hz},
                  {"duration_s", study_duration},       {"path_closed", closed},
                  {"truth_energy_J", s.truth_energy_J}, {"live_truth_energy_J", path_work(r.x, truth)}};
  doc["control"] = {{"dt_s", control->dt()},
                    {"steps_per_haptic_tick", c.substeps},
                    {"penalty_stiffness_N_per_m", control->penalty_stiffness()},
                    {"dt_critical_tissue_s", control->dt_critical_tissue()},
                    {"dt_critical_with_contact_s", control->dt_critical_contact()},
                    {"coupling_horizon_s", c.control.coupling_horizon},
                    {"model_time_reached_s", r.model_time},
                    {"wall_time_s", duration}};
  doc["frames"] = written;
  return doc;
}

}  // namespace tmlab::rt
