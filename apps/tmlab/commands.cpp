#include "commands.hpp"

#include "cli_args.hpp"

#include "demo_case.hpp"

#include "tmlab/build_info.hpp"
#include "tmlab/core/case_config.hpp"
#include "tmlab/core/config_reader.hpp"
#include "tmlab/core/error.hpp"
#include "tmlab/core/gmsh_reader.hpp"
#include "tmlab/core/hdf5_file.hpp"
#include "tmlab/core/mesh_generator.hpp"
#include "tmlab/core/mesh_ops.hpp"
#include "tmlab/core/mesh_quality.hpp"
#include "tmlab/core/process.hpp"
#include "tmlab/core/result_compare.hpp"
#include "tmlab/tensormass/case_runner.hpp"
#include "tmlab/tensormass/paper_experiments.hpp"

#ifdef TMLAB_HAVE_REFERENCE
#include "tmlab/reference_fem/reference_runner.hpp"
#endif

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#ifndef TMLAB_SOURCE_DIR
#define TMLAB_SOURCE_DIR "."
#endif

namespace tmlab::cli {

namespace fs = std::filesystem;

std::string tmlab_root() {
  if (const char* env = std::getenv("TMLAB_ROOT"); env && *env) return env;
  return TMLAB_SOURCE_DIR;
}

namespace {

void print_summary(const tm::RunResult& r) {
  const auto& s = r.summary;
  std::cout << "case        " << s.value("case", "") << " (" << s.value("model", "") << ")\n"
            << "mesh        " << s["mesh"]["points"] << " nodes, " << s["mesh"]["tets"] << " tets, volume "
            << std::setprecision(4) << s["mesh"]["volume_m3"].get<double>() * 1e6 << " cm^3\n"
            << "solver      " << s["solver"].dump() << "\n"
            << "final time  " << s["final_time"].get<double>() << " s\n"
            << "max |u|     " << s["max_displacement_m"].get<double>() * 1e3 << " mm\n"
            << "energy      " << s["elastic_energy_J"].get<double>() << " J\n";
  for (auto it = s["final_reactions_N"].begin(); it != s["final_reactions_N"].end(); ++it) {
    const auto& v = it.value();
    std::cout << "reaction    " << it.key() << ": (" << v[0].get<double>() << ", " << v[1].get<double>()
              << ", " << v[2].get<double>() << ") N\n";
  }
  std::cout << "min J       " << s["min_volume_ratio"].get<double>()
            << " (smallest deformed/rest tet volume)\n"
            << "wall time   " << s["run_seconds"].get<double>() << " s\n"
            << "results     " << r.dir << "/ (summary.json, timeseries.h5, fields.xdmf, result.pvd, *.png)\n";
}

tm::RunResult run_model(const CaseConfig& cfg, const tm::RunOptions& opt, const std::string& model,
                        int degree, const std::string& time_integration = "fixed_step") {
  if (model == "reference") {
#ifdef TMLAB_HAVE_REFERENCE
    ref::ReferenceOptions ro;
    ro.degree = degree;
    ro.time_integration = time_integration;
    return ref::run_reference_case(cfg, opt, ro);
#else
    (void)degree;
    (void)time_integration;
    throw Error(
        "this tmlab was built without the deal.II reference (reference_fem/): install libdeal.ii-dev and "
        "rebuild");
#endif
  }
  return tm::run_case(cfg, opt);
}

int run_config(const CaseConfig& cfg, const Parsed& p, const std::string& command_line) {
  tm::RunOptions opt;
  opt.tmlab_root = tmlab_root();
  opt.results_root = p.get("--results", (fs::path(tmlab_root()) / "results").string());
  opt.command_line = split_words(command_line);
  opt.plots = !p.has("--no-plots");
  opt.log = &std::cerr;
  const std::string model = p.get("--model", cfg.model);
  const int degree = p.has("--degree") ? static_cast<int>(parse_double("--degree", p.get("--degree"))) : 1;
  const std::string time_integration = p.get("--time-integration", "fixed_step");
  if (time_integration != "fixed_step" && time_integration != "ida")
    throw UsageError("--time-integration must be fixed_step or ida");
  if (time_integration == "ida" && model != "reference")
    throw UsageError("--time-integration ida needs --model reference");
  std::cerr << "tmlab: running '" << cfg.name << "' (" << model << ")\n";
  const tm::RunResult r = run_model(cfg, opt, model, degree, time_integration);
  print_summary(r);
  return 0;
}

}  // namespace

int cmd_demo(const std::vector<std::string>& args, const std::string& command_line) {
  const Parsed p = parse(args, {"--results"}, {"--no-plots"});
  if (!p.positional.empty()) throw UsageError("demo takes no positional arguments");
  const nlohmann::json doc = nlohmann::json::parse(kDemoCase);
  const CaseConfig cfg = parse_case(doc, "<embedded demo case>", {tmlab_root()});
  return run_config(cfg, p, command_line);
}

int cmd_run(const std::vector<std::string>& args, const std::string& command_line) {
  Parsed p = parse(args, {"--results", "--model", "--degree", "--time-integration"}, {"--no-plots"});
  if (p.positional.size() != 1) throw UsageError("run needs exactly one case name or case file");
  std::string path = p.positional[0];
  if (!fs::exists(path)) {
    const fs::path named = fs::path(tmlab_root()) / "cases" / (path + ".json");
    if (!fs::exists(named))
      throw Error(path + ": no such case file, and no shipped case of that name (see 'tmlab cases')");
    path = named.string();
  }
  CaseConfig cfg = load_case(path, tmlab_root());
  if (p.has("--model")) {
    const std::string m = p.get("--model");
    if (m != "tensor_mass" && m != "tl_oracle" && m != "reference")
      throw UsageError("--model must be tensor_mass, tl_oracle or reference");
    if (m != "reference") {
      cfg.model = m;
      cfg.effective["model"] = m;
    }
  }
  return run_config(cfg, p, command_line);
}

std::string resolve_case(const std::string& arg) {
  if (fs::exists(arg)) return arg;
  const fs::path named = fs::path(tmlab_root()) / "cases" / (arg + ".json");
  if (!fs::exists(named))
    throw Error(arg + ": no such case file, and no shipped case of that name (see 'tmlab cases')");
  return named.string();
}

int cmd_compare(const std::vector<std::string>& args, const std::string& command_line) {
  const Parsed p = parse(args, {"--results", "--against", "--degree", "--time-integration"}, {"--no-plots"});
  if (p.positional.size() != 1) throw UsageError("compare needs exactly one case name or case file");
  const CaseConfig cfg = load_case(resolve_case(p.positional[0]), tmlab_root());
  const std::string against = p.get("--against", "reference");
  if (against != "reference" && against != "tl_oracle")
    throw UsageError("--against must be reference or tl_oracle");
  const int degree = p.has("--degree") ? static_cast<int>(parse_double("--degree", p.get("--degree"))) : 1;
  const std::string time_integration = p.get("--time-integration", "fixed_step");
  if (time_integration != "fixed_step" && time_integration != "ida")
    throw UsageError("--time-integration must be fixed_step or ida");
  if (time_integration == "ida" && against != "reference")
    throw UsageError("--time-integration ida needs --against reference");

  tm::RunOptions opt;
  opt.tmlab_root = tmlab_root();
  opt.results_root = p.get("--results", (fs::path(tmlab_root()) / "results").string());
  opt.command_line = split_words(command_line);
  opt.plots = false;
  opt.log = &std::cerr;
  CaseConfig tm_cfg = cfg;
  tm_cfg.model = "tensor_mass";
  tm_cfg.effective["model"] = "tensor_mass";
  std::cerr << "tmlab compare: tensor-mass run\n";
  const tm::RunResult a = tm::run_case(tm_cfg, opt);
  tm::RunResult b;
  if (against == "reference") {
    std::cerr << "tmlab compare: deal.II reference run (P" << degree << ")\n";
    b = run_model(cfg, opt, "reference", degree, time_integration);
  } else {
    CaseConfig o = cfg;
    o.name = cfg.name + "-tl_oracle";
    o.model = "tl_oracle";
    o.effective["model"] = "tl_oracle";
    o.effective["name"] = o.name;
    std::cerr << "tmlab compare: total-Lagrangian oracle run\n";
    b = tm::run_case(o, opt);
  }
  ComparisonSeries series;
  nlohmann::json cmp = compare_results(a.dir, b.dir, &series);
  cmp["case"] = cfg.name;
  cmp["a"] = a.dir;
  cmp["b"] = b.dir;
  cmp["against"] = against;
  const fs::path dir = a.dir;
  {
    std::ofstream(dir / "compare.json") << cmp.dump(2) << "\n";
    H5File h5 = H5File::create((dir / "compare.h5").string());
    h5.write("/series/time", series.time, {series.time.size()});
    h5.write("/series/step_time", series.step_time, {series.step_time.size()});
    h5.write("/series/rel_diff_displacement", series.rel_displacement, {series.rel_displacement.size()});
    h5.write("/series/rel_diff_reaction", series.rel_reaction, {series.rel_reaction.size()});
    h5.write("/series/rel_diff_energy", series.rel_energy, {series.rel_energy.size()});
    h5.close();
  }
  // Plot: the per-step relative differences on a log scale (round-off zeros floored at 1e-17).
  std::string plot_note;
  if (!p.has("--no-plots")) {
    const fs::path pdir = dir / "compare";
    fs::create_directories(pdir);
    auto floored = [](std::vector<double> v) {
      for (double& x : v) x = std::max(x, 1e-17);
      return v;
    };
    H5File h5 = H5File::create((pdir / "timeseries.h5").string());
    h5.write("/series/time", series.time, {series.time.size()});
    h5.write("/series/step_time", series.step_time, {series.step_time.size()});
    h5.write("/series/rel_diff_displacement", floored(series.rel_displacement),
             {series.rel_displacement.size()});
    h5.write("/series/rel_diff_reaction", floored(series.rel_reaction), {series.rel_reaction.size()});
    h5.write("/series/rel_diff_energy", floored(series.rel_energy), {series.rel_energy.size()});
    h5.close();
    const nlohmann::json plots = nlohmann::json::array(
        {{{"file", "compare_displacement.png"},
          {"x", "time"},
          {"y", {"rel_diff_displacement"}},
          {"title", cfg.name + ": tensor-mass vs " + against + ", nodal displacements"},
          {"xlabel", "time [s]"},
          {"ylabel", "|u_a - u_b| / |u_b|"},
          {"logy", true}},
         {{"file", "compare_reaction_energy.png"},
          {"x", "step_time"},
          {"y", {"rel_diff_reaction", "rel_diff_energy"}},
          {"title", cfg.name + ": tensor-mass vs " + against + ", reactions and energy"},
          {"xlabel", "time [s]"},
          {"ylabel", "relative difference"},
          {"logy", true}}});
    std::ofstream(pdir / "plots.json") << plots.dump(2) << "\n";
    const ProcessStatus ps = run_python(fs::path(tmlab_root()) / "core" / "python" / "tmlab_plot.py",
                                        {pdir.string()}, ProcessOutput::discard());
    plot_note = ps.ok() ? ", compare/*.png" : " (plotting failed: " + ps.describe() + ")";
  }
  std::cout << "comparison of " << cfg.name << ": tensor-mass vs " << against << "\n"
            << "  quantity                          max over steps\n"
            << "  rel_diff_displacement             " << cmp["rel_diff_displacement"].get<double>() << "\n"
            << "  rel_diff_reaction                 " << cmp["rel_diff_reaction"].get<double>() << "\n"
            << "  rel_diff_energy                   " << cmp["rel_diff_energy"].get<double>() << "\n"
            << "written: " << (dir / "compare.json").string() << ", compare.h5" << plot_note << "\n";
  return 0;
}

int cmd_cases(const std::vector<std::string>& args) {
  if (!args.empty()) throw UsageError("cases takes no arguments");
  const fs::path dir = fs::path(tmlab_root()) / "cases";
  std::vector<fs::path> files;
  if (fs::exists(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::cout << "shipped cases (" << dir.string() << "); run one with 'tmlab run NAME':\n";
  for (const auto& f : files) {
    std::string desc;
    try {
      const auto j = ConfigReader::parse_file(f.string());
      desc = j.value("description", "");
    } catch (const Error& e) {
      desc = std::string("(unreadable: ") + e.what() + ")";
    }
    std::cout << "  " << std::left << std::setw(28) << f.stem().string() << desc << "\n";
  }
  return 0;
}

int cmd_mesh(const std::vector<std::string>& args) {
  if (args.empty()) throw UsageError("mesh needs a sub-command: info FILE | check FILE");
  const std::string sub = args[0];
  const Parsed p =
      parse(std::vector<std::string>(args.begin() + 1, args.end()), {"--scale", "--repair"}, {"--json"});
  if (p.positional.size() != 1) throw UsageError("mesh " + sub + " needs exactly one mesh file");
  Mesh mesh = read_mesh(p.positional[0]);
  if (p.has("--scale")) scale_mesh(mesh, parse_double("--scale", p.get("--scale")));
  if (sub == "info") {
    const MeshReport rep = analyse_mesh(mesh);
    if (p.has("--json"))
      std::cout << mesh_report_json(rep).dump(2) << "\n";
    else
      std::cout << format_mesh_report(rep);
    return 0;
  }
  if (sub == "check") {
    if (p.has("--repair")) {
      const int n = repair_orientation(mesh);
      write_gmsh22(mesh, p.get("--repair"));
      std::cout << "re-oriented " << n << " tets; wrote " << p.get("--repair") << "\n";
    }
    const MeshReport rep = analyse_mesh(mesh);
    std::cout << format_mesh_report(rep);
    if (!rep.inverted.empty() || !rep.degenerate.empty()) {
      std::cerr << "tmlab: error: " << p.positional[0] << ": " << rep.inverted.size() << " inverted and "
                << rep.degenerate.size() << " degenerate tets";
      if (!rep.inverted.empty()) std::cerr << " (first inverted: tet " << rep.inverted.front() << ")";
      if (!rep.degenerate.empty()) std::cerr << " (first degenerate: tet " << rep.degenerate.front() << ")";
      std::cerr << "\n";
      return 1;
    }
    std::cout << "check: OK (no inverted or degenerate tets)\n";
    return 0;
  }
  throw UsageError("unknown mesh sub-command '" + sub + "' (info or check)");
}

int cmd_paper(const std::vector<std::string>& args, const std::string& command_line) {
  const Parsed p = parse(args, {"--results", "--params"}, {"--no-plots"});
  if (p.positional.size() != 1) throw UsageError("paper needs one figure: fig5, fig6 or fig7");
  const std::string params_file =
      p.get("--params", (fs::path(tmlab_root()) / "cases" / "paper" / "xu2011_liver.json").string());
  const nlohmann::json params = ConfigReader::parse_file(params_file);
  const tm::PaperFigure fig = tm::paper_figure(p.positional[0], params, params_file);
  const fs::path dir =
      fs::path(p.get("--results", (fs::path(tmlab_root()) / "results").string())) / "paper" / fig.name;
  fs::create_directories(dir);
  nlohmann::json spec = {{"name", fig.name},     {"title", fig.title},    {"xlabel", fig.xlabel},
                         {"ylabel", fig.ylabel}, {"params", params_file}, {"runs", nlohmann::json::array()}};
  std::size_t k = 0;
  for (const auto& run : fig.runs) {
    ++k;
    std::cerr << "tmlab paper " << fig.name << ": run " << k << "/" << fig.runs.size() << " " << run.id
              << "\n";
    const CaseConfig cfg =
        parse_case(run.case_doc, params_file + " (" + fig.name + "/" + run.id + ")", {tmlab_root()});
    tm::RunOptions opt;
    opt.tmlab_root = tmlab_root();
    opt.results_root = dir.string();
    opt.command_line = split_words(command_line);
    opt.plots = false;
    const tm::RunResult r = tm::run_case(cfg, opt);
    spec["runs"].push_back({{"id", run.id},
                            {"label", run.label},
                            {"scheme", run.scheme},
                            {"dir", r.dir},
                            {"x", run.x},
                            {"y", run.y},
                            {"x_sign", run.x_sign},
                            {"y_sign", run.y_sign}});
  }
  std::ofstream(dir / "figure.json") << spec.dump(2) << "\n";
  if (p.has("--no-plots")) return 0;
  const fs::path script = fs::path(tmlab_root()) / "core" / "python" / "tmlab_paper_figure.py";
  const ProcessStatus ps = run_python(script, {dir.string()});
  if (!ps.ok()) throw Error("drawing " + fig.name + " failed (" + ps.describe() + ")");
  if (fig.name == "fig7") {
    std::ifstream in(dir / "fig7_energy.json");
    const auto e = nlohmann::json::parse(in);
    std::cout << "hysteresis: loop area = dissipated + stored at the end of the cycle\n";
    for (const auto& row : e)
      std::cout << "  " << std::left << std::setw(24) << row["run"].get<std::string>() << " loop "
                << row["loop_area_J"].get<double>() << " J, dissipated " << row["dissipation_J"].get<double>()
                << " J, stored " << row["stored_end_J"].get<double>() << " J, relative residual "
                << row["relative_residual"].get<double>() << "\n";
  }
  return 0;
}

int cmd_version() {
  std::cout << "tmlab " << build_info::git_sha << (build_info::git_dirty ? " (modified)" : "") << "\n"
            << "build " << build_info::build_type << ", " << build_info::compiler << "\n";
  return 0;
}

}  // namespace tmlab::cli
