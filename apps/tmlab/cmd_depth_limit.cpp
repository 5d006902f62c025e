// tmlab depth-limit: the depth at which each law first inverts a tet (or loses equilibrium) under the
// paper's sphere indentation, on several meshes (studies/depth_limit/depth_limit.hpp;
// docs/contact.md, "Inversion depth of each law"). Writes <results>/depth-limit/: depth_limit.json,
// depth_limit.md, depth_limit.png, manifest.json and summary.json last (RunOutput protocol).
#include "cli_args.hpp"
#include "command_specs.hpp"
#include "commands.hpp"

#include "core/base/error.hpp"
#include "core/results/run_output.hpp"
#include "core/results/run_protocol.hpp"
#include "studies/common/study_plot.hpp"
#include "studies/depth_limit/depth_limit.hpp"
#include "tensormass/materials/law_factory.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace tmlab::cli {

namespace {

namespace fs = std::filesystem;

}  // namespace

int cmd_depth_limit(const std::vector<std::string>& args, const std::string& command_line) {
  const ParsedOptions p = parse(depth_limit_spec(), args);
  if (!p.positional.empty()) throw UsageError("depth-limit takes no positional arguments");
  tm::DepthLimitOptions o;
  if (p.flag("--quick")) o.cells = {4};  // the test's mesh
  if (p.given("--cells")) {
    o.cells.clear();
    for (const long long c : p.whole_list("--cells")) o.cells.push_back(static_cast<int>(c));
  }
  o.max_depth = p.decimal("--max-depth");
  o.increment = p.decimal("--increment");
  o.grading = p.decimal("--grading");
  const std::vector<tm::DepthLimitLaw> all = tm::default_depth_limit_laws(o.young, o.poisson);
  for (const std::string& name : p.text_list("--laws")) {
    const auto it =
        std::find_if(all.begin(), all.end(), [&](const tm::DepthLimitLaw& l) { return l.name == name; });
    if (it == all.end()) {
      std::string names;
      for (const tm::DepthLimitLaw& l : all) names += (names.empty() ? "" : ", ") + l.name;
      throw UsageError("--laws: unknown law '" + name + "' (known: " + names + ")");
    }
    o.laws.push_back(*it);
  }
  o.log = [](const std::string& m) { std::cerr << "tmlab depth-limit: " << m << "\n"; };
  const fs::path dir = fs::path(results_root(p)) / "depth-limit";

  // Checkpoint after every finished (law, mesh) run (docs/robustness.md); --resume reads it before
  // the result directory is touched, so a refused resume leaves the interrupted study as it was.
  const nlohmann::json config = tm::depth_limit_fingerprint(o);
  o.checkpoint = dir / RunOutput::kStaging / "checkpoint.h5";
  o.fingerprint = config;
  if (p.flag("--resume")) o.resume = read_checkpoint(o.checkpoint, "depth_limit", config);
  RunOutput out(dir, nullptr,
                p.flag("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  // The manifest records the effective options (the fingerprint); the runs are the result.
  std::vector<tm::DepthLimitRun> runs;
  run_with_protocol(out, {split_words(command_line), config, {}}, [&] {
    runs = tm::run_depth_limit_study(o);  // validates the options
    const nlohmann::json doc = tm::depth_limit_json(o, runs);
    out.write_json("depth_limit.json", doc);
    remove_checkpoint(o.checkpoint);  // a complete result holds no checkpoint
    {
      std::ofstream md(out.file("depth_limit.md"));
      md << tm::depth_limit_markdown(o, runs, command_line);
      if (!md) throw Error(out.file("depth_limit.md").string() + ": cannot write");
    }
    std::string plots = "skipped (--no-plots)";
    if (!p.flag("--no-plots")) {
      const ProcessStatus ps =
          tm::draw_study_plot(tmlab_root(), "depth_limit", "tmlab_depth_limit_plot.py", out.staging_dir());
      plots = ps.ok() ? "ok" : "failed (" + ps.describe() + ")";
      if (!ps.ok()) std::cerr << "tmlab depth-limit: plot " << plots << "\n";
    }
    nlohmann::json summary = {{"plots", plots}, {"runs", nlohmann::json::array()}};
    for (const nlohmann::json& r : doc["runs"])
      summary["runs"].push_back({{"law", r["law"]},
                                 {"cells", r["cells"]},
                                 {"outcome", r["outcome"]},
                                 {"inversion_depth_m", r["inversion_depth_m"]},
                                 {"deepest_converged_m", r["deepest_converged_m"]},
                                 {"deepest_min_J", r["deepest_min_J"]}});
    return summary;
  });
  std::cout << tm::depth_limit_markdown(o, runs, command_line);
  std::cout << "results " << dir.string() << "/ (depth_limit.json, depth_limit.md, summary.json"
            << (p.flag("--no-plots") ? ")\n" : ", depth_limit.png)\n");
  return 0;
}

}  // namespace tmlab::cli
