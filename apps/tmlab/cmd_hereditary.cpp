// tmlab hereditary: the Prony recursions (midpoint = the seed's eq. 20, exact_linear, backward_euler)
// against the exact hereditary integral, on prescribed strain histories and on the liver relaxation
// experiment (studies/hereditary/hereditary_report.hpp; docs/hereditary.md).
// Writes <results>/hereditary/: hereditary.h5, hereditary.md (tables), PNG plots, manifest.json and
// summary.json last (RunOutput protocol).
#include "cli_args.hpp"
#include "command_specs.hpp"
#include "commands.hpp"

#include "core/base/format.hpp"
#include "core/constitutive/prony.hpp"
#include "core/results/run_output.hpp"
#include "core/results/run_protocol.hpp"
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
  ParsedOptions p = parse(hereditary_spec(), args);
  if (!p.positional.empty()) throw UsageError("hereditary takes no positional arguments");
  if (p.flag("--liver") && p.flag("--no-liver")) throw UsageError("give --liver or --no-liver, not both");
  if (p.flag("--no-liver") && p.given("--liver-history"))
    throw UsageError("--liver-history chooses the liver study's history: it has no use with --no-liver");
  tm::HereditaryRunOptions o;
  o.study.quick = p.flag("--quick");
  o.liver = !p.flag("--no-liver");
  const std::vector<std::string> groups = p.text_list("--histories");
  o.study.seed = static_cast<std::uint64_t>(p.whole("--seed"));
  o.histories = tm::study_histories(groups, o.study);
  // Quick runs only the seed's form (a pk2 liver step costs ~7x a nodal_force one).
  // The history forms by core/constitutive's names (PronyHistory); "both" is all of them.
  p.set_default("--liver-history", o.study.quick ? "nodal_force" : "both");
  if (p.text("--liver-history") != "both")
    o.liver_histories = {to_string(*prony_history_from_string(p.text("--liver-history")))};
  p.set_default("--params", (fs::path(tmlab_root()) / "cases" / "paper" / "xu2011_liver.json").string());
  o.params_file = p.text("--params");
  o.tmlab_root = tmlab_root();
  o.command_line = command_line;
  o.plots = !p.flag("--no-plots");
  o.log = [](const std::string& m) { std::cerr << "tmlab hereditary: " << m << "\n"; };
  const fs::path dir = fs::path(results_root(p)) / "hereditary";

  // The options that change the result, and the study's own constants.
  nlohmann::json config = p.config(kFingerprint);
  config.update({{"alpha", o.study.alpha}, {"tau", o.study.tau}});
  // Checkpoint after every sweep and liver study (docs/robustness.md); --resume reads it before the
  // result directory is touched, so a refused resume leaves the interrupted study as it was.
  o.checkpoint = dir / RunOutput::kStaging / "checkpoint.h5";
  o.fingerprint = config;
  if (p.flag("--resume")) o.resume = read_checkpoint(o.checkpoint, "hereditary", config);
  RunOutput out(dir, nullptr,
                p.flag("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  std::vector<fs::path> inputs;
  if (o.liver) inputs.push_back(o.params_file);
  run_with_protocol(out, {split_words(command_line), config, inputs},
                    [&] { return tm::write_hereditary_study(o, out.staging_dir()); },
                    {[&] { remove_checkpoint(o.checkpoint); }, {}});
  std::cout << "results " << dir.string() << "/ (hereditary.h5, hereditary.md, summary.json"
            << (p.flag("--no-plots") ? ")\n" : ", *.png)\n");
  return 0;
}

}  // namespace tmlab::cli
