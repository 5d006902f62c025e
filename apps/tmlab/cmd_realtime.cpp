// tmlab realtime CASE [--record] [--duration S] [--results DIR] [--coupling extrapolation|local_model]
// tmlab realtime CASE --serve [--port P] [--duration S] [--coupling ...]
// The paper's three-thread real-time loop (docs/realtime.md). Without --record: runs the loop for the
// case's duration and prints each thread's timing. With --record: the same run offscreen, then the
// coupling measurements, PNG frames and <results>/realtime/timing.json (RunOutput protocol). With
// --serve: the loop with the probe steered from a web page served on 127.0.0.1:P (live_server.hpp)
// until SIGINT/SIGTERM (or --duration), then the timing.
#include "cli_args.hpp"
#include "command_specs.hpp"
#include "commands.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/interrupt.hpp"
#include "core/results/run_output.hpp"
#include "core/results/run_protocol.hpp"
#include "realtime/live_server.hpp"
#include "realtime/realtime_loop.hpp"
#include "realtime/realtime_record.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>

namespace tmlab::cli {

namespace {

namespace fs = std::filesystem;

std::string resolve_realtime_case(const std::string& arg) {
  if (fs::is_regular_file(arg)) return arg;
  const fs::path shipped = fs::path(tmlab_root()) / "cases" / "realtime" / (arg + ".json");
  if (fs::is_regular_file(shipped)) return shipped.string();
  throw UsageError("realtime: no case file '" + arg + "' and no shipped case " + shipped.string());
}

void print_timing(const rt::ThreadTiming& t) {
  std::printf(
      "  %-8s target %7.1f Hz  achieved %7.1f Hz  jitter p50 %9.1f us  p99 %9.1f us  p99.9 %9.1f us  "
      "missed %ld\n",
      t.name.c_str(), t.target_hz, t.rate_hz, t.p50_us, t.p99_us, t.p999_us, t.missed);
}

/// --serve: the loop with the interactive probe and the live server, until a signal or `duration`.
int serve(const rt::RealtimeCase& c, int port, double duration) {
  const fs::path root = tmlab_root();
  const fs::path three = root / "build" / "npm" / "node_modules" / "three";
  rt::LiveServerOptions so;
  so.port = port;
  so.files.mount("/", root / "realtime" / "web" / "page");
  so.files.mount("/vendor/three/", three / "build");
  so.files.mount("/vendor/three-addons/", three / "examples" / "jsm");
  so.probe_box = rt::probe_box(c.mesh, 2.0 * c.control.probe_radius);
  so.hello =
      rt::hello_message(c.mesh, c.control.probe_radius, c.probe_start, so.probe_box, c.name, c.visual_hz);
  so.nodes = static_cast<int>(c.mesh.num_points());
  so.log = [](const std::string& m) { std::cerr << "tmlab realtime --serve: " << m << "\n"; };
  auto control = c.make_control();
  rt::SeqLock<rt::ProbeSample> target(
      rt::ProbeSample{0.0, {c.probe_start.x(), c.probe_start.y(), c.probe_start.z()}});
  rt::LiveServer server(std::move(so), target);
  if (!fs::is_regular_file(three / "build" / "three.module.js"))
    std::cerr
        << "tmlab realtime --serve: three.js is not installed in " << three.string()
        << ": the page can only say so. Install it with './tmlab build' (needs npm: apt-get install npm) or "
           "'npm ci --prefix build/npm' after copying realtime/web/package*.json there (docs/realtime.md)\n";
  std::cout << "serving http://127.0.0.1:" << server.port() << "/  (Ctrl-C stops)" << std::endl;

  rt::LoopOptions lo;
  lo.duration = duration;
  lo.haptic_hz = c.haptic_hz;
  lo.visual_hz = c.visual_hz;
  lo.rendered = c.rendered;
  lo.interactive = &target;
  lo.keep_log = false;       // an interactive run may last hours
  lo.timing_window = 600.0;  // percentiles over the first 10 minutes
  lo.on_frame = [&server](const std::vector<float>& xyz, const Vec3& f, const Vec3& x) {
    server.publish(xyz, f, x);
  };
  // SIGINT / SIGTERM stop the loop at its next tick (LoopOptions::stop_on_interrupt): the normal end
  // of an interactive session, so the timing is printed and the exit code is 0.
  const rt::LoopResult r = rt::run_realtime_loop(*control, lo);
  server.stop();
  const int sig = r.signal;
  const rt::LiveServerStats st = server.stats();
  std::cout << "stopped (" << (sig ? signal_name(sig) : std::string("--duration reached")) << ")\n"
            << "timing (wall clock, this machine's load included):\n";
  for (const rt::ThreadTiming* t : {&r.haptic, &r.control, &r.visual}) print_timing(*t);
  std::printf("  model time reached %.3f s in %.3f s of wall time\n", r.model_time, r.haptic.elapsed_s);
  std::printf(
      "  page: %ld frames published, %ld sent, %ld skipped (busy page), %ld probe moves, %ld refused, %ld "
      "pages\n",
      st.frames_published, st.frames_sent, st.frames_skipped, st.probe_moves, st.refused, st.pages);
  return 0;
}

}  // namespace

int cmd_realtime(const std::vector<std::string>& args, const std::string& command_line) {
  const ParsedOptions p = parse(realtime_spec(), args);
  if (p.positional.size() != 1)
    throw UsageError("realtime needs one case (a file or a name in cases/realtime/)");
  if (p.flag("--serve") && p.flag("--record")) throw UsageError("--serve and --record exclude each other");
  if (p.given("--port") && !p.flag("--serve")) throw UsageError("--port goes with --serve");
  for (const char* opt : {"--results", "--no-frames"})
    if (p.given(opt) && !p.flag("--record"))
      throw UsageError(std::string(opt) +
                       " only applies with --record (where the recording goes, whether it keeps PNG "
                       "frames); add --record to record the run");
  const int port = static_cast<int>(p.whole("--port"));
  const std::string file = resolve_realtime_case(p.positional[0]);
  rt::RealtimeCase c = rt::load_realtime_case(file, tmlab_root());
  const double duration = p.given("--duration") ? p.decimal("--duration") : c.duration;
  if (p.given("--coupling")) {
    try {
      c.rendered = rt::parse_coupling(p.text("--coupling"));
    } catch (const tmlab::Error& e) {
      throw UsageError(e.what());
    }
  }
  if (p.flag("--serve")) {
    std::cerr << "tmlab realtime --serve: " << c.name << " (" << c.mesh.num_points() << " nodes), haptic "
              << c.haptic_hz << " Hz, control dt " << c.control.dt << " s, visual " << c.visual_hz << " Hz\n";
    // Without --duration: until SIGINT/SIGTERM (a day at most).
    return serve(c, port, p.given("--duration") ? duration : 86400.0);
  }
  std::cerr << "tmlab realtime: " << c.name << " (" << c.mesh.num_points() << " nodes), haptic "
            << c.haptic_hz << " Hz, control dt " << c.control.dt << " s, visual " << c.visual_hz << " Hz, "
            << duration << " s\n";

  if (!p.flag("--record")) {
    std::cerr << "tmlab realtime: preparing the control model (the surface compliance of the local-model "
                 "coupling), then the run\n";
    auto control = c.make_control();
    rt::LoopOptions lo;
    lo.duration = duration;
    lo.haptic_hz = c.haptic_hz;
    lo.visual_hz = c.visual_hz;
    lo.rendered = c.rendered;
    lo.trajectory = c.trajectory.get();
    check_interrupt("while preparing the control model, before the real-time run");
    const rt::LoopResult r = rt::run_realtime_loop(*control, lo);
    // A signal stops the threads at their next tick; the cut-short run is reported as interrupted.
    check_interrupt("during the real-time run, stopped after " + significant(r.wall_time) + " s of " +
                    significant(duration) + " s");
    std::cout << "timing (wall clock, this machine's load included):\n";
    for (const rt::ThreadTiming* t : {&r.haptic, &r.control, &r.visual}) print_timing(*t);
    std::printf("  model time reached %.3f s in %.3f s of wall time\n", r.model_time, duration);
    return 0;
  }

  const fs::path dir = fs::path(results_root(p)) / "realtime";
  RunOutput out(dir);
  nlohmann::json doc;
  // The options as given, with the case's duration and coupling when they were not.
  nlohmann::json config = p.config(kManifest);
  config.update({{"case", file}, {"duration", duration}, {"coupling", rt::to_string(c.rendered)}});
  rt::RecordOptions ro;
  ro.duration = duration;
  ro.frames = !p.flag("--no-frames");
  ro.log = [](const std::string& m) { std::cerr << "tmlab realtime: " << m << "\n"; };
  run_with_protocol(out, {split_words(command_line), config, {file, c.mesh_file}}, [&] {
    doc = rt::record_realtime(c, ro, out.staging_dir());
    out.write_json("timing.json", doc);
    return doc;
  });
  std::cout << "timing (wall clock, this machine's load included):\n";
  for (const char* name : {"haptic", "control", "visual"}) {
    const auto& t = doc["threads"][name];
    std::printf(
        "  %-8s target %7.1f Hz  achieved %7.1f Hz  jitter p50 %9.1f us  p99 %9.1f us  p99.9 %9.1f us  "
        "missed %ld\n",
        name, t["target_hz"].get<double>(), t["rate_hz"].get<double>(), t["p50_us"].get<double>(),
        t["p99_us"].get<double>(), t["p999_us"].get<double>(), t["missed"].get<long>());
  }
  std::printf("  model time reached %.3f s in %.3f s of wall time\n",
              doc["control"]["model_time_reached_s"].get<double>(), duration);
  std::cout << "couplings (deterministic study, control " << c.study_control_hz << " Hz, haptic "
            << c.haptic_hz << " Hz):\n";
  for (const char* name : {"extrapolation", "local_model"}) {
    const auto& s = doc["couplings"][name];
    std::printf("  %-14s force error %.4f  coupling energy %.4e J   (live run: %.4f, %.4e J)\n", name,
                s["haptic_force_error_rel"].get<double>(), s["coupling_energy_J"].get<double>(),
                s["live_haptic_force_error_rel"].get<double>(), s["live_coupling_energy_J"].get<double>());
  }
  std::cout << "results " << dir.string() << "/ (timing.json, forces.csv, "
            << (doc["frames"].get<int>() > 0 ? std::to_string(doc["frames"].get<int>()) + " frames/*.png, "
                                             : "")
            << "summary.json)\n";
  return 0;
}

}  // namespace tmlab::cli
