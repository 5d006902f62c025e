// tmlab workprecision: error against CPU time of the fixed-step viscoelastic tensor-mass solvers and
// the SUNDIALS integrators (studies/workprecision/work_precision.hpp), written to results/workprecision/:
// workprecision.h5, workprecision.md (the tables), workprecision_<problem>.png, manifest.json and
// summary.json (last; core/results/run_output.hpp).
#include "commands.hpp"

#include "cli_args.hpp"

#include "core/results/run_output.hpp"
#include "studies/workprecision/work_precision.hpp"

#include <filesystem>
#include <iostream>

namespace tmlab::cli {

namespace fs = std::filesystem;

int cmd_workprecision(const std::vector<std::string>& args, const std::string& command_line) {
  const Parsed p =
      parse(args, {"--problem", "--results", "--reference-rtol"}, {"--quick", "--no-plots", "--resume"});
  if (!p.positional.empty())
    throw UsageError("workprecision takes no positional argument (got '" + p.positional[0] + "')");
  tm::WorkPrecisionOptions opt;
  const std::string problem = p.get("--problem", "all");
  if (problem == "all")
    opt.problems = {"liver", "incompressible"};
  else if (problem == "liver" || problem == "incompressible")
    opt.problems = {problem};
  else
    throw UsageError("--problem must be liver, incompressible or all (got '" + problem + "')");
  opt.quick = p.has("--quick");
  if (p.has("--reference-rtol")) {
    opt.reference_rtol = parse_double("--reference-rtol", p.get("--reference-rtol"));
    if (!(opt.reference_rtol > 0.0 && opt.reference_rtol < 1e-6))
      throw UsageError("--reference-rtol must be in (0, 1e-6)");
  }
  opt.tmlab_root = tmlab_root();
  opt.log = &std::cerr;
  const fs::path dir =
      fs::path(p.get("--results", (fs::path(tmlab_root()) / "results").string())) / "workprecision";

  const nlohmann::json config = {{"problems", opt.problems},
                                 {"quick", opt.quick},
                                 {"reference_rtol", opt.reference_rtol},
                                 {"tmlab_root", opt.tmlab_root}};
  // Checkpoint after every run (docs/robustness.md); --resume reads it before the result directory
  // is touched, so a refused resume leaves the interrupted study as it was.
  opt.checkpoint = dir / RunOutput::kStaging / "checkpoint.h5";
  opt.fingerprint = config;
  if (p.has("--resume")) opt.resume = read_checkpoint(opt.checkpoint, "workprecision", config);
  RunOutput out(dir, nullptr,
                p.has("--resume") ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  try {
    std::vector<fs::path> inputs;
    for (const auto& name : opt.problems)
      if (name == "liver")
        inputs = {fs::path(opt.tmlab_root) / "meshes" / "liver.msh",
                  fs::path(opt.tmlab_root) / "cases" / "paper" / "xu2011_liver.json"};
    out.write_json("manifest.json", make_manifest({split_words(command_line), config, inputs}));
    const std::vector<tm::WorkPrecisionProblem> results = tm::run_work_precision(opt);
    remove_checkpoint(opt.checkpoint);  // a complete result holds no checkpoint
    out.finalize(tm::write_work_precision(results, command_line, out.staging_dir(), !p.has("--no-plots"),
                                          opt.tmlab_root, &std::cerr));
    std::cout << tm::work_precision_table(results) << "results     " << dir.string()
              << "/ (workprecision.h5, workprecision.md, *.png)\n";
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
  return 0;
}

}  // namespace tmlab::cli
