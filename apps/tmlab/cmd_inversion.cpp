// tmlab inversion: the depth at which each law first inverts a tet (or loses equilibrium) under the
// paper's sphere indentation, on several meshes (studies/inversion/inversion_depth.hpp;
// docs/contact.md, "Inversion depth of each law"). Writes <results>/inversion/: inversion.json,
// inversion.md, inversion_depth.png, manifest.json and summary.json last (RunOutput protocol).
#include "cli_args.hpp"
#include "command_specs.hpp"
#include "commands.hpp"

#include "core/base/error.hpp"
#include "core/results/run_output.hpp"
#include "studies/common/study_plot.hpp"
#include "studies/inversion/inversion_depth.hpp"
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

int cmd_inversion(const std::vector<std::string>& args, const std::string& command_line) {
  const ParsedOptions p = parse(inversion_spec(), args);
  if (!p.positional.empty()) throw UsageError("inversion takes no positional arguments");
  tm::InversionStudyOptions o;
  if (p.flag("--quick")) o.cells = {4};  // the test's mesh
  if (p.given("--cells")) {
    o.cells.clear();
    for (const long long c : p.whole_list("--cells")) o.cells.push_back(static_cast<int>(c));
  }
  o.max_depth = p.decimal("--max-depth");
  o.increment = p.decimal("--increment");
  o.grading = p.decimal("--grading");
  const std::vector<tm::InversionLaw> all = tm::default_inversion_laws(o.young, o.poisson);
  for (const std::string& name : p.text_list("--laws")) {
    const auto it =
        std::find_if(all.begin(), all.end(), [&](const tm::InversionLaw& l) { return l.name == name; });
    if (it == all.end()) {
      std::string names;
      for (const tm::InversionLaw& l : all) names += (names.empty() ? "" : ", ") + l.name;
      throw UsageError("--laws: unknown law '" + name + "' (known: " + names + ")");
    }
    o.laws.push_back(*it);
  }
  o.log = [](const std::string& m) { std::cerr << "tmlab inversion: " << m << "\n"; };
  const fs::path dir = fs::path(results_root(p)) / "inversion";

  // Checkpoint after every finished (law, mesh) run (docs/robustness.md); --resume reads it before
  // the result directory is touched, so a refused resume leaves the interrupted study as it was.
  const nlohmann::json config = tm::inversion_fingerprint(o);
  o.checkpoint = dir / RunOutput::kStaging / "checkpoint.h5";
  o.fingerprint = config;
  if (p.flag("--resume")) o.resume = read_checkpoint(o.checkpoint, "inversion", config);
  RunOutput out(dir, nullptr,
                p.flag("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  try {
    const std::vector<tm::InversionRun> runs = tm::run_inversion_study(o);  // validates the options
    nlohmann::json doc = tm::inversion_json(o, runs);
    out.write_json("manifest.json", make_manifest({split_words(command_line), doc, {}}));
    out.write_json("inversion.json", doc);
    remove_checkpoint(o.checkpoint);  // a complete result holds no checkpoint
    {
      std::ofstream md(out.file("inversion.md"));
      md << tm::inversion_markdown(o, runs, command_line);
      if (!md) throw Error(out.file("inversion.md").string() + ": cannot write");
    }
    std::string plots = "skipped (--no-plots)";
    if (!p.flag("--no-plots")) {
      const ProcessStatus ps =
          tm::draw_study_plot(tmlab_root(), "inversion", "tmlab_inversion_plot.py", out.staging_dir());
      plots = ps.ok() ? "ok" : "failed (" + ps.describe() + ")";
      if (!ps.ok()) std::cerr << "tmlab inversion: plot " << plots << "\n";
    }
    nlohmann::json summary = {{"plots", plots}, {"runs", nlohmann::json::array()}};
    for (const nlohmann::json& r : doc["runs"])
      summary["runs"].push_back({{"law", r["law"]},
                                 {"cells", r["cells"]},
                                 {"outcome", r["outcome"]},
                                 {"inversion_depth_m", r["inversion_depth_m"]},
                                 {"deepest_converged_m", r["deepest_converged_m"]},
                                 {"deepest_min_J", r["deepest_min_J"]}});
    out.finalize(summary);
    std::cout << tm::inversion_markdown(o, runs, command_line);
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
  std::cout << "results " << dir.string()
            << "/ (inversion.json, inversion.md, summary.json, inversion_depth.png)\n";
  return 0;
}

}  // namespace tmlab::cli
