// tmlab realtime CASE [--record] [--duration S] [--results DIR] [--coupling extrapolation|local_model]
// The paper's three-thread real-time loop (docs/realtime.md). Without --record: runs the loop for the
// case's duration and prints each thread's timing. With --record: the same run offscreen, then the
// coupling measurements, PNG frames and <results>/realtime/timing.json (RunOutput protocol).
#include "cli_args.hpp"
#include "commands.hpp"

#include "core/base/error.hpp"
#include "core/results/run_output.hpp"
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

}  // namespace

int cmd_realtime(const std::vector<std::string>& args, const std::string& command_line) {
  const Parsed p =
      parse(args, {"--duration", "--results", "--coupling"}, {"--record", "--no-frames", "--serve"});
  if (p.positional.size() != 1)
    throw UsageError("realtime needs one case (a file or a name in cases/realtime/)");
  if (p.has("--serve")) throw UsageError("realtime --serve is not built yet (docs/realtime.md, 'Not done')");
  const std::string file = resolve_realtime_case(p.positional[0]);
  rt::RealtimeCase c = rt::load_realtime_case(file, tmlab_root());
  double duration = c.duration;
  if (p.has("--duration")) {
    duration = parse_double("--duration", p.get("--duration"));
    if (!(duration > 0.0) || duration > 3600.0) throw UsageError("--duration must be in (0, 3600] seconds");
  }
  if (p.has("--coupling")) {
    try {
      c.rendered = rt::parse_coupling(p.get("--coupling"));
    } catch (const tmlab::Error& e) {
      throw UsageError(e.what());
    }
  }
  std::cerr << "tmlab realtime: " << c.name << " (" << c.mesh.num_points() << " nodes), haptic "
            << c.haptic_hz << " Hz, control dt " << c.control.dt << " s, visual " << c.visual_hz << " Hz, "
            << duration << " s\n";

  if (!p.has("--record")) {
    auto control = c.make_control();
    rt::LoopOptions lo;
    lo.duration = duration;
    lo.haptic_hz = c.haptic_hz;
    lo.visual_hz = c.visual_hz;
    lo.rendered = c.rendered;
    lo.trajectory = c.trajectory.get();
    const rt::LoopResult r = rt::run_realtime_loop(*control, lo);
    std::cout << "timing (wall clock, this machine's load included):\n";
    for (const rt::ThreadTiming* t : {&r.haptic, &r.control, &r.visual}) print_timing(*t);
    std::printf("  model time reached %.3f s of %.3f s\n", r.model_time, duration);
    return 0;
  }

  const fs::path dir =
      fs::path(p.get("--results", (fs::path(tmlab_root()) / "results").string())) / "realtime";
  RunOutput out(dir);
  nlohmann::json doc;
  try {
    const nlohmann::json config = {{"case", file},
                                   {"duration", duration},
                                   {"coupling", rt::to_string(c.rendered)},
                                   {"frames", !p.has("--no-frames")}};
    out.write_json("manifest.json", make_manifest({split_words(command_line), config, {file, c.mesh_file}}));
    rt::RecordOptions ro;
    ro.duration = duration;
    ro.frames = !p.has("--no-frames");
    ro.log = [](const std::string& m) { std::cerr << "tmlab realtime: " << m << "\n"; };
    doc = rt::record_realtime(c, ro, out.staging_dir());
    out.write_json("timing.json", doc);
    out.finalize(doc);
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
  std::cout << "timing (wall clock, this machine's load included):\n";
  for (const char* name : {"haptic", "control", "visual"}) {
    const auto& t = doc["threads"][name];
    std::printf(
        "  %-8s target %7.1f Hz  achieved %7.1f Hz  jitter p50 %9.1f us  p99 %9.1f us  p99.9 %9.1f us  "
        "missed %ld\n",
        name, t["target_hz"].get<double>(), t["rate_hz"].get<double>(), t["p50_us"].get<double>(),
        t["p99_us"].get<double>(), t["p999_us"].get<double>(), t["missed"].get<long>());
  }
  std::cout << "couplings (deterministic study, control " << c.study_control_hz << " Hz, haptic "
            << c.haptic_hz << " Hz):\n";
  for (const char* name : {"extrapolation", "local_model"}) {
    const auto& s = doc["couplings"][name];
    std::printf("  %-14s force error %.4f  coupling energy %.4e J   (live run: %.4f, %.4e J)\n", name,
                s["haptic_force_error_rel"].get<double>(), s["coupling_energy_J"].get<double>(),
                s["live_haptic_force_error_rel"].get<double>(), s["live_coupling_energy_J"].get<double>());
  }
  std::cout << "results " << dir.string() << "/ (timing.json, forces.csv, frames/*.png, summary.json)\n";
  return 0;
}

}  // namespace tmlab::cli
