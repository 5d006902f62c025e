// tmlab bench: every force kernel and whole solver step measured side by side (bench/
// bench_suite.hpp), with the machine's limits measured in the same run, written to results/bench/:
// bench.json, bench.md, bench_ns_per_tet.png, bench_threads.png, manifest.json and summary.json
// (last; core/results/run_output.hpp). docs/performance.md shows the latest table.
#include "commands.hpp"

#include "cli_args.hpp"
#include "command_specs.hpp"

#include "core/base/error.hpp"
#include "core/results/run_output.hpp"
#include "core/results/run_protocol.hpp"

#ifdef TMLAB_HAVE_BENCH
#include "bench/bench_report.hpp"
#include "bench/bench_suite.hpp"
#endif

#include <filesystem>
#include <iostream>

namespace tmlab::cli {

namespace fs = std::filesystem;

int cmd_bench(const std::vector<std::string>& args, const std::string& command_line) {
  ParsedOptions p = parse(bench_spec(), args);
  if (!p.positional.empty())
    throw UsageError("bench takes no positional argument (got '" + p.positional[0] + "')");
#ifndef TMLAB_HAVE_BENCH
  (void)command_line;
  throw Error(
      "bench: this build has no benchmarks (configure with TMLAB_BUILD_BENCHMARKS=ON, the release preset)");
#else
  tm::BenchOptions opt;
  opt.quick = p.flag("--quick");
  opt.large = p.flag("--large");
  if (opt.quick && opt.large) throw UsageError("--quick and --large exclude each other");
  opt.max_threads = static_cast<int>(p.whole("--threads"));
  p.set_default("--min-time", opt.quick ? "0.002" : "0.2");
  opt.min_time = p.decimal("--min-time");
  if (p.given("--meshes")) opt.meshes = p.text_list("--meshes");
  if (const std::string bad = tm::check_bench_meshes(opt); !bad.empty()) throw UsageError(bad);
  opt.tmlab_root = tmlab_root();
  opt.log = &std::cerr;
  const fs::path dir = fs::path(results_root(p)) / "bench";
  RunOutput out(dir);
  nlohmann::json config = p.config(kManifest);
  config["meshes"] = opt.meshes;  // the default set when --meshes is not given
  std::string md;
  run_with_protocol(
      out, {split_words(command_line), config, {fs::path(opt.tmlab_root) / "meshes" / "liver.msh"}}, [&] {
        nlohmann::json bench = tm::run_bench(opt);
        bench["command"] = command_line;
        md = tm::bench_markdown(bench);
        return tm::write_bench_report(std::move(bench), out.staging_dir(), !p.flag("--no-plots"),
                                      opt.tmlab_root, &std::cerr);
      });
  std::cout << md << "\nresults     " << dir.string()
            << (p.flag("--no-plots") ? "/ (bench.json, bench.md; no plots: --no-plots)\n"
                                     : "/ (bench.json, bench.md, *.png)\n");
  return 0;
#endif
}

}  // namespace tmlab::cli
