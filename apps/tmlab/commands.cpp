#include "commands.hpp"

#include "demo_case.hpp"

#include "tmlab/build_info.hpp"
#include "tmlab/core/case_config.hpp"
#include "tmlab/core/config_reader.hpp"
#include "tmlab/core/error.hpp"
#include "tmlab/core/gmsh_reader.hpp"
#include "tmlab/core/mesh_generator.hpp"
#include "tmlab/core/mesh_ops.hpp"
#include "tmlab/core/mesh_quality.hpp"
#include "tmlab/tensormass/case_runner.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
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

/// Splits "--key value" options (listed in `with_value`) and flags from positional arguments.
struct Parsed {
  std::vector<std::string> positional;
  std::vector<std::pair<std::string, std::string>> options;
  std::string get(const std::string& key, const std::string& fallback = "") const {
    for (const auto& o : options)
      if (o.first == key) return o.second;
    return fallback;
  }
  bool has(const std::string& key) const {
    return std::any_of(options.begin(), options.end(), [&](const auto& o) { return o.first == key; });
  }
};

Parsed parse(const std::vector<std::string>& args, const std::vector<std::string>& with_value,
             const std::vector<std::string>& flags) {
  Parsed p;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.rfind("--", 0) == 0) {
      if (std::find(with_value.begin(), with_value.end(), a) != with_value.end()) {
        if (i + 1 >= args.size()) throw UsageError("option " + a + " needs a value");
        p.options.emplace_back(a, args[++i]);
      } else if (std::find(flags.begin(), flags.end(), a) != flags.end()) {
        p.options.emplace_back(a, "");
      } else {
        throw UsageError("unknown option " + a);
      }
    } else {
      p.positional.push_back(a);
    }
  }
  return p;
}

double parse_double(const std::string& key, const std::string& s) {
  try {
    std::size_t pos = 0;
    const double v = std::stod(s, &pos);
    if (pos != s.size()) throw std::invalid_argument(s);
    return v;
  } catch (const std::exception&) {
    throw UsageError(key + " needs a number (got '" + s + "')");
  }
}

std::vector<std::string> split_words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> w;
  for (std::string x; in >> x;) w.push_back(x);
  return w;
}

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
    std::cout << "reaction    " << it.key() << ": (" << v[0].get<double>() << ", " << v[1].get<double>() << ", "
              << v[2].get<double>() << ") N\n";
  }
  std::cout << "min J       " << s["min_volume_ratio"].get<double>() << " (smallest deformed/rest tet volume)\n"
            << "wall time   " << s["run_seconds"].get<double>() << " s\n"
            << "results     " << r.dir << "/ (summary.json, timeseries.h5, fields.xdmf, result.pvd, *.png)\n";
}

int run_config(const CaseConfig& cfg, const Parsed& p, const std::string& command_line) {
  tm::RunOptions opt;
  opt.tmlab_root = tmlab_root();
  opt.results_root = p.get("--results", (fs::path(tmlab_root()) / "results").string());
  opt.command_line = split_words(command_line);
  opt.plots = !p.has("--no-plots");
  opt.log = &std::cerr;
  std::cerr << "tmlab: running '" << cfg.name << "' (" << cfg.model << ")\n";
  const tm::RunResult r = tm::run_case(cfg, opt);
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
  Parsed p = parse(args, {"--results", "--model"}, {"--no-plots"});
  if (p.positional.size() != 1) throw UsageError("run needs exactly one case name or case file");
  std::string path = p.positional[0];
  if (!fs::exists(path)) {
    const fs::path named = fs::path(tmlab_root()) / "cases" / (path + ".json");
    if (!fs::exists(named)) throw Error(path + ": no such case file, and no shipped case of that name (see 'tmlab cases')");
    path = named.string();
  }
  CaseConfig cfg = load_case(path, tmlab_root());
  if (p.has("--model")) {
    const std::string m = p.get("--model");
    if (m != "tensor_mass" && m != "tl_oracle") throw UsageError("--model must be tensor_mass or tl_oracle");
    cfg.model = m;
    cfg.effective["model"] = m;
  }
  return run_config(cfg, p, command_line);
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
  const Parsed p = parse(std::vector<std::string>(args.begin() + 1, args.end()), {"--scale", "--repair"}, {"--json"});
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

int cmd_version() {
  std::cout << "tmlab " << build_info::git_sha << (build_info::git_dirty ? " (modified)" : "") << "\n"
            << "build " << build_info::build_type << ", " << build_info::compiler << "\n";
  return 0;
}

}  // namespace tmlab::cli
