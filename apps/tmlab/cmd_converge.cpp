// tmlab converge: a convergence study in space (meshes) or time (--refine-in time: time steps) of a
// rig (the options of `tmlab rig`) or a case file (convergence/convergence_study.hpp;
// docs/convergence.md). Writes <results>/converge/NAME/ (or --out): converge.json, converge.md,
// converge.png, meshes/ and levels/ (each level's run), manifest.json and summary.json last
// (run_with_protocol). Every option is checked before the folder is touched: bad options exit 2 and
// leave nothing behind. --resume checks the level runs an interrupted or failed study left
// (check_resume) before the folder is touched, then reuses the complete ones.
#include "cli_args.hpp"
#include "command_specs.hpp"
#include "commands.hpp"
#include "rig_options.hpp"

#include "convergence/convergence_report.hpp"
#include "convergence/convergence_study.hpp"
#include "core/base/error.hpp"
#include "core/results/result_dir.hpp"
#include "core/results/run_output.hpp"
#include "core/results/run_protocol.hpp"
#include "core/results/unit_checkpoint.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>

namespace tmlab::cli {

namespace {

namespace fs = std::filesystem;

/// The study's options from the command line (UsageError for a bad combination).
convergence::StudyOptions study_options(const ParsedOptions& p, const std::string& command_line) {
  if (p.positional.size() != 1)
    throw UsageError(
        "converge needs one rig test (indentation | unconfined | confined | tension) or one case");
  convergence::StudyOptions o;
  const std::string& what = p.positional[0];
  if (is_rig_test(what)) {
    const rigs::RigTest test = rig_test(what);
    o.rig = rig_from_options(p, test, p.given("--name") ? p.text("--name") : rigs::rig_test_name(test));
  } else {
    if (const std::string opt = first_rig_option_given(p); !opt.empty())
      throw UsageError(opt + " is a rig option (tmlab converge indentation|unconfined|confined|tension " +
                       opt + " ...); a case's own mesh is refined uniformly");
    if (p.given("--name")) throw UsageError("--name names a rig; a case study takes the case's name");
    o.case_config = load_case(resolve_case(what), tmlab_root());  // a bad case file: tmlab::Error, as run
  }
  o.tmlab_root = tmlab_root();
  o.levels = static_cast<int>(p.whole("--levels"));
  o.refine = p.text("--refine-in") == "time" ? convergence::Refine::Time : convergence::Refine::Space;
  o.ratio = p.decimal("--ratio");
  o.quantities = p.all("--quantity");
  if (p.given("--linear")) o.linear = p.text("--linear");
  for (const std::string& t : p.all("--time")) o.times.push_back(parse_double("--time", t));
  o.command_line = split_words(command_line);
  o.log = [](const std::string& m) { std::cerr << "tmlab converge: " << m << "\n"; };
  return o;
}

}  // namespace

int cmd_converge(const std::vector<std::string>& args, const std::string& command_line) {
  const ParsedOptions p = parse(converge_spec(), args);
  const convergence::StudyOptions o = study_options(p, command_line);
  convergence::StudyPlan plan;
  try {
    plan = convergence::plan_study(o);  // every option checked: nothing is written yet
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  const fs::path dir =
      p.given("--out") ? fs::path(p.text("--out")) : fs::path(results_root(p)) / "converge" / plan.name;
  // --resume: the levels the stopped study left are checked against this plan before the folder is
  // touched (a refused resume leaves it as it was); a complete level of the same plan is reused.
  const bool resume = p.flag("--resume");
  std::vector<convergence::LevelAction> actions;
  if (resume) {
    refuse_resume_of_complete(result_dir::resolve(dir), "convergence study");
    actions = convergence::check_resume(plan, result_dir::resolve(dir) / RunOutput::kStaging);
  }
  RunOutput out(dir, &std::cerr, resume ? RunOutput::Previous::ResumeStopped : RunOutput::Previous::Discard);
  ManifestInput mi;
  mi.command_line = split_words(command_line);
  mi.config = {{"options", p.config(kManifest)}, {"study", convergence::plan_json(plan)}};
  if (plan.kind == "case") mi.input_files = {plan.base.file, plan.base.mesh.file};
  convergence::StudyResult result;
  run_with_protocol(out, mi, [&] {
    result = convergence::run_study(plan, o, out.staging_dir(), actions);
    out.write_json("converge.json", convergence::study_json(plan, result));
    {
      std::ofstream md(out.file("converge.md"));
      md << convergence::study_markdown(plan, result, command_line);
      if (!md) throw Error(out.file("converge.md").string() + ": cannot write");
    }
    std::string plots = "skipped (--no-plots)";
    if (!p.flag("--no-plots")) {
      const ProcessStatus ps = convergence::draw_plot(tmlab_root(), out.staging_dir());
      plots = ps.ok() ? "ok" : "failed (" + ps.describe() + ", see plot.log)";
      if (!ps.ok()) std::cerr << "tmlab converge: plot " << plots << "\n";
    }
    nlohmann::json summary = convergence::study_summary(result);
    summary["plots"] = plots;
    return summary;
  });
  std::cout << convergence::study_markdown(plan, result, command_line);
  std::cout << "results " << out.dir().string() << "/ (converge.json, converge.md"
            << (p.flag("--no-plots") ? "" : ", converge.png") << ", levels/, summary.json)\n";
  return 0;
}

}  // namespace tmlab::cli
