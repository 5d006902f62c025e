// tmlab hereditary: the Prony recursions (midpoint = the seed's eq. 20, exact_linear, backward_euler)
// against the exact hereditary integral, on prescribed strain histories and on the liver relaxation
// experiment (studies/hereditary/hereditary_report.hpp; docs/hereditary.md).
// Writes <results>/hereditary/: hereditary.h5, hereditary.md (tables), PNG plots, manifest.json and
// summary.json last (RunOutput protocol).
#include "cli_args.hpp"
#include "commands.hpp"

#include "core/base/format.hpp"
#include "core/constitutive/prony.hpp"
#include "core/results/run_output.hpp"
#include "studies/hereditary/hereditary_report.hpp"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

namespace tmlab::cli {

namespace {

namespace fs = std::filesystem;

}  // namespace

int cmd_hereditary(const std::vector<std::string>& args, const std::string& command_line) {
  const Parsed p = parse(args, {"--histories", "--results", "--params", "--seed", "--liver-history"},
                         {"--liver", "--no-liver", "--quick", "--no-plots", "--resume"});
  if (!p.positional.empty()) throw UsageError("hereditary takes no positional arguments");
  if (p.has("--liver") && p.has("--no-liver")) throw UsageError("give --liver or --no-liver, not both");
  tm::HereditaryRunOptions o;
  o.study.quick = p.has("--quick");
  o.liver = !p.has("--no-liver");
  const std::vector<std::string> groups = split_list(p.get("--histories", "ramp_hold,sine,random"));
  if (groups.empty()) throw UsageError("--histories needs a comma-separated list (ramp_hold, sine, random)");
  if (p.has("--seed")) {
    o.study.seed = static_cast<std::uint64_t>(parse_whole("--seed", p.get("--seed"), 0, 9000000000000000LL));
  }
  o.histories = tm::study_histories(groups, o.study);
  // Quick runs only the seed's form (a pk2 liver step costs ~7x a nodal_force one).
  // The history forms by core/constitutive's names (PronyHistory), parsed once; "both" is all of them.
  const std::string lh = p.get("--liver-history", o.study.quick ? "nodal_force" : "both");
  if (lh != "both") {
    const std::optional<PronyHistory> h = prony_history_from_string(lh);
    if (!h) {
      std::vector<std::string> names = prony_history_names();
      names.push_back("both");
      throw UsageError("--liver-history must be " + choice_list(names, "") + " (got '" + lh + "')");
    }
    o.liver_histories = {to_string(*h)};
  }
  o.params_file =
      p.get("--params", (fs::path(tmlab_root()) / "cases" / "paper" / "xu2011_liver.json").string());
  o.tmlab_root = tmlab_root();
  o.command_line = command_line;
  o.plots = !p.has("--no-plots");
  o.log = [](const std::string& m) { std::cerr << "tmlab hereditary: " << m << "\n"; };
  const fs::path dir =
      fs::path(p.get("--results", (fs::path(tmlab_root()) / "results").string())) / "hereditary";

  const nlohmann::json config = {{"histories", groups},    {"quick", o.study.quick},
                                 {"liver", o.liver},       {"liver_history", o.liver_histories},
                                 {"alpha", o.study.alpha}, {"tau", o.study.tau},
                                 {"seed", o.study.seed},   {"params", o.params_file}};
  // Checkpoint after every sweep and liver study (docs/robustness.md); --resume reads it before the
  // result directory is touched, so a refused resume leaves the interrupted study as it was.
  o.checkpoint = dir / RunOutput::kStaging / "checkpoint.h5";
  o.fingerprint = config;
  if (p.has("--resume")) o.resume = read_checkpoint(o.checkpoint, "hereditary", config);
  RunOutput out(dir, nullptr,
                p.has("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  try {
    std::vector<fs::path> inputs;
    if (o.liver) inputs.push_back(o.params_file);
    out.write_json("manifest.json", make_manifest({split_words(command_line), config, inputs}));
    const nlohmann::json summary = tm::write_hereditary_study(o, out.staging_dir());
    remove_checkpoint(o.checkpoint);  // a complete result holds no checkpoint
    out.finalize(summary);
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
  std::cout << "results " << dir.string() << "/ (hereditary.h5, hereditary.md, summary.json, *.png)\n";
  return 0;
}

}  // namespace tmlab::cli
