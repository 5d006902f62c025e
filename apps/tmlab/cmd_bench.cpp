// tmlab bench: every force kernel and whole solver step measured side by side (bench/
// bench_suite.hpp), with the machine's limits measured in the same run, written to results/bench/:
// bench.json, bench.md, bench_ns_per_tet.png, bench_threads.png, manifest.json and summary.json
// (last; core/results/run_output.hpp). docs/performance.md shows the latest table.
#include "commands.hpp"

#include "cli_args.hpp"

#include "core/base/error.hpp"
#include "core/results/run_output.hpp"

#ifdef TMLAB_HAVE_BENCH
#include "bench/bench_report.hpp"
#include "bench/bench_suite.hpp"
#endif

#include <filesystem>
#include <iostream>

namespace tmlab::cli {

namespace fs = std::filesystem;

int cmd_bench(const std::vector<std::string>& args, const std::string& command_line) {
  const Parsed p =
      parse(args, {"--results", "--threads", "--min-time", "--meshes"}, {"--quick", "--large", "--no-plots"});
  if (!p.positional.empty())
    throw UsageError("bench takes no positional argument (got '" + p.positional[0] + "')");
#ifndef TMLAB_HAVE_BENCH
  (void)command_line;
  throw Error(
      "bench: this build has no benchmarks (configure with TMLAB_BUILD_BENCHMARKS=ON, the release preset)");
#else
  tm::BenchOptions opt;
  opt.quick = p.has("--quick");
  opt.large = p.has("--large");
  if (opt.quick && opt.large) throw UsageError("--quick and --large exclude each other");
  opt.max_threads = static_cast<int>(parse_whole("--threads", p.get("--threads", "2"), 1, 64));
  opt.min_time = parse_double("--min-time", p.get("--min-time", opt.quick ? "0.002" : "0.2"));
  if (!(opt.min_time > 0.0 && opt.min_time <= 60.0))
    throw UsageError("--min-time must be in (0, 60] seconds");
  if (p.has("--meshes")) {
    opt.meshes = split_list(p.get("--meshes"));
    if (opt.meshes.empty()) throw UsageError("--meshes needs at least one mesh name");
  }
  if (const std::string bad = tm::check_bench_meshes(opt); !bad.empty()) throw UsageError(bad);
  opt.tmlab_root = tmlab_root();
  opt.log = &std::cerr;
  const fs::path dir = fs::path(p.get("--results", (fs::path(tmlab_root()) / "results").string())) / "bench";
  RunOutput out(dir);
  try {
    const nlohmann::json config = {{"quick", opt.quick},
                                   {"large", opt.large},
                                   {"meshes", opt.meshes},
                                   {"max_threads", opt.max_threads},
                                   {"min_time", opt.min_time}};
    out.write_json("manifest.json", make_manifest({split_words(command_line),
                                                   config,
                                                   {fs::path(opt.tmlab_root) / "meshes" / "liver.msh"}}));
    nlohmann::json bench = tm::run_bench(opt);
    bench["command"] = command_line;
    const std::string md = tm::bench_markdown(bench);
    out.finalize(tm::write_bench_report(std::move(bench), out.staging_dir(), !p.has("--no-plots"),
                                        opt.tmlab_root, &std::cerr));
    std::cout << md << "\nresults     " << dir.string()
              << (p.has("--no-plots") ? "/ (bench.json, bench.md; no plots: --no-plots)\n"
                                      : "/ (bench.json, bench.md, *.png)\n");
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
  return 0;
#endif
}

}  // namespace tmlab::cli
