// tmlab workprecision: error against CPU time of the fixed-step viscoelastic tensor-mass solvers and
// the SUNDIALS integrators (tensormass/work_precision.hpp), written to results/workprecision/:
// workprecision.h5, workprecision.md (the tables), workprecision_<problem>.png, manifest.json and
// summary.json (last; core/run_output.hpp).
#include "commands.hpp"

#include "cli_args.hpp"

#include "core/base/error.hpp"
#include "core/base/process.hpp"
#include "core/results/run_output.hpp"
#include "verification/studies/work_precision.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace tmlab::cli {

namespace fs = std::filesystem;

int cmd_workprecision(const std::vector<std::string>& args, const std::string& command_line) {
  const Parsed p = parse(args, {"--problem", "--results", "--reference-rtol"}, {"--quick", "--no-plots"});
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

  RunOutput out(dir);
  try {
    const nlohmann::json config = {{"problems", opt.problems},
                                   {"quick", opt.quick},
                                   {"reference_rtol", opt.reference_rtol},
                                   {"tmlab_root", opt.tmlab_root}};
    std::vector<fs::path> inputs;
    for (const auto& name : opt.problems)
      if (name == "liver")
        inputs = {fs::path(opt.tmlab_root) / "meshes" / "liver.msh",
                  fs::path(opt.tmlab_root) / "cases" / "paper" / "xu2011_liver.json"};
    out.write_json("manifest.json", make_manifest({split_words(command_line), config, inputs}));
    const std::vector<tm::WorkPrecisionProblem> results = tm::run_work_precision(opt);
    tm::write_work_precision_h5(results, out.file("workprecision.h5").string());
    const std::string table = tm::work_precision_table(results);
    std::ofstream(out.file("workprecision.md"))
        << "# Work-precision tables\n\n"
        << "Command: `" << command_line << "`\n\n"
        << "Error: max over the output times of |u - u_ref|_inf / max |u_ref|_inf;"
        << " CPU: process CPU time of the run.\n\n"
        << table;
    std::string plot_status = "skipped";
    if (!p.has("--no-plots")) {
      const fs::path script =
          fs::path(opt.tmlab_root) / "verification" / "studies" / "python" / "tmlab_workprecision_plot.py";
      const ProcessStatus ps =
          run_python(script, {out.staging_dir().string()}, ProcessOutput::to_file(out.file("plots.log")));
      const int rc = ps.ok() ? 0 : 1;
      plot_status = rc == 0 ? "ok" : "failed (see plots.log)";
      if (rc != 0)
        std::cerr << "tmlab workprecision: warning: plotting failed (see plots.log); the numbers are in "
                     "workprecision.h5\n";
    }
    nlohmann::json summary = {
        {"command", "workprecision"}, {"plots", plot_status}, {"problems", nlohmann::json::array()}};
    for (const auto& P : results) {
      nlohmann::json pj = {{"name", P.name},
                           {"ode_size", P.ode_size},
                           {"dt_critical", P.dt_critical},
                           {"max_displacement_m", P.max_displacement},
                           {"reference",
                            {{"method", P.reference.method},
                             {"rtol", P.reference.value},
                             {"steps", P.reference.steps},
                             {"cpu_seconds", P.reference.cpu_seconds}}},
                           {"runs", P.points.size()}};
      long failed = 0;
      for (const auto& pt : P.points) failed += pt.failure.empty() ? 0 : 1;
      pj["failed_runs"] = failed;
      summary["problems"].push_back(pj);
    }
    out.finalize(summary);
    std::cout << table << "results     " << dir.string() << "/ (workprecision.h5, workprecision.md, *.png)\n";
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
  return 0;
}

}  // namespace tmlab::cli
