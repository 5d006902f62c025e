// tmlab workprecision: error against CPU time of the fixed-step viscoelastic tensor-mass solvers and
// the SUNDIALS integrators (studies/workprecision/work_precision.hpp), written to results/workprecision/:
// workprecision.h5, workprecision.md (the tables), workprecision_<problem>.png, manifest.json and
// summary.json (last; core/results/run_output.hpp).
#include "commands.hpp"

#include "cli_args.hpp"
#include "command_specs.hpp"

#include "core/results/run_output.hpp"
#include "core/results/run_protocol.hpp"
#include "studies/workprecision/work_precision.hpp"

#include <filesystem>
#include <iostream>

namespace tmlab::cli {

namespace fs = std::filesystem;

int cmd_workprecision(const std::vector<std::string>& args, const std::string& command_line) {
  const ParsedOptions p = parse(workprecision_spec(), args);
  if (!p.positional.empty())
    throw UsageError("workprecision takes no positional argument (got '" + p.positional[0] + "')");
  tm::WorkPrecisionOptions opt;
  const std::string problem = p.text("--problem");
  opt.problems = problem == "all" ? std::vector<std::string>{"liver", "incompressible"}
                                  : std::vector<std::string>{problem};
  opt.quick = p.flag("--quick");
  opt.reference_rtol = p.decimal("--reference-rtol");
  opt.tmlab_root = tmlab_root();
  opt.log = &std::cerr;
  const fs::path dir = fs::path(results_root(p)) / "workprecision";

  nlohmann::json config = p.config(kFingerprint);
  config["tmlab_root"] = opt.tmlab_root;
  // Checkpoint after every run (docs/robustness.md); --resume reads it before the result directory
  // is touched, so a refused resume leaves the interrupted study as it was.
  opt.checkpoint = dir / RunOutput::kStaging / "checkpoint.h5";
  opt.fingerprint = config;
  if (p.flag("--resume")) opt.resume = read_checkpoint(opt.checkpoint, "workprecision", config);
  RunOutput out(dir, nullptr,
                p.flag("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  std::vector<fs::path> inputs;
  for (const auto& name : opt.problems)
    if (name == "liver")
      inputs = {fs::path(opt.tmlab_root) / "meshes" / "liver.msh",
                fs::path(opt.tmlab_root) / "cases" / "paper" / "xu2011_liver.json"};
  std::vector<tm::WorkPrecisionProblem> results;
  // The checkpoint goes before the files are written (a complete result holds none), as before.
  run_with_protocol(out, {split_words(command_line), config, inputs}, [&] {
    results = tm::run_work_precision(opt);
    remove_checkpoint(opt.checkpoint);
    return tm::write_work_precision(results, command_line, out.staging_dir(), !p.flag("--no-plots"),
                                    opt.tmlab_root, &std::cerr);
  });
  std::cout << tm::work_precision_table(results) << "results     " << dir.string()
            << "/ (workprecision.h5, workprecision.md, *.png)\n";
  return 0;
}

}  // namespace tmlab::cli
