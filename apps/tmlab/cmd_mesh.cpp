// tmlab mesh info|check and tmlab cases.
#include "commands.hpp"

#include "cli_args.hpp"
#include "command_specs.hpp"

#include "core/base/error.hpp"
#include "core/config/config_reader.hpp"
#include "core/io/output_file.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>

namespace tmlab::cli {

namespace fs = std::filesystem;

int cmd_cases(const std::vector<std::string>& args) {
  if (!parse(cases_spec(), args).positional.empty()) throw UsageError("cases takes no arguments");
  const fs::path dir = fs::path(tmlab_root()) / "cases";
  std::vector<fs::path> files;
  if (fs::exists(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::cout << "shipped cases (" << dir.string() << "); run one with 'tmlab run NAME':\n";
  std::size_t width = 0;  // the longest name, so every description starts in one column
  for (const auto& f : files) width = std::max(width, f.stem().string().size());
  for (const auto& f : files) {
    std::string desc;
    try {
      const auto j = ConfigReader::parse_file(f.string());
      desc = j.value("description", "");
    } catch (const Error& e) {
      desc = std::string("(unreadable: ") + e.what() + ")";
    }
    std::cout << "  " << std::left << std::setw(static_cast<int>(width + 2)) << f.stem().string() << desc
              << "\n";
  }
  return 0;
}

namespace {

/// tmlab mesh quadratic FILE --out OUT.msh: the 10-node mesh of a checked linear mesh.
int mesh_quadratic(const std::vector<std::string>& args) {
  const ParsedOptions p = parse(mesh_quadratic_spec(), args);
  if (p.positional.size() != 1) throw UsageError("mesh quadratic needs exactly one mesh file");
  if (!p.given("--out")) throw UsageError("mesh quadratic needs --out OUT.msh");
  const std::string out = p.text("--out");
  check_output_files({out}, {p.positional[0]}, p.flag("--overwrite"));
  Mesh mesh = read_mesh(p.positional[0]);
  if (p.given("--scale")) scale_mesh(mesh, p.decimal("--scale"));
  const MeshReport rep = analyse_mesh(mesh);
  if (mesh.num_tets() == 0 || !rep.inverted.empty() || !rep.degenerate.empty())
    throw Error(p.positional[0] + ": " + std::to_string(mesh.num_tets()) + " tets, " +
                std::to_string(rep.inverted.size()) + " inverted and " +
                std::to_string(rep.degenerate.size()) +
                " degenerate: repair it first ('tmlab mesh check FILE --repair OUT.msh')");
  const QuadraticMesh qm = make_quadratic(mesh);
  write_gmsh22_quadratic(mesh, qm, out);
  std::cout << "wrote " << out << ": " << qm.num_points() << " nodes (" << qm.num_vertices << " vertices, "
            << qm.num_edges() << " midside), " << qm.num_tets() << " 10-node tets\n";
  return 0;
}

}  // namespace

int cmd_mesh(const std::vector<std::string>& args) {
  if (args.empty()) throw UsageError("mesh needs a sub-command: info FILE | check FILE | quadratic FILE");
  const std::string sub = args[0];
  if (sub == "quadratic") return mesh_quadratic({args.begin() + 1, args.end()});
  if (sub != "info" && sub != "check")
    throw UsageError("unknown mesh sub-command '" + sub + "' (info, check or quadratic)");
  const ParsedOptions p =
      parse(sub == "info" ? mesh_info_spec() : mesh_check_spec(), {args.begin() + 1, args.end()});
  // Only `mesh check` declares --repair.
  const bool repair = sub == "check" && p.given("--repair");
  if (p.positional.size() != 1) throw UsageError("mesh " + sub + " needs exactly one mesh file");
  if (repair) check_output_files({p.text("--repair")}, {p.positional[0]}, p.flag("--overwrite"));
  Mesh mesh = read_mesh(p.positional[0]);
  if (p.given("--scale")) scale_mesh(mesh, p.decimal("--scale"));
  if (sub == "info") {
    const MeshReport rep = analyse_mesh(mesh);
    if (p.flag("--json"))
      std::cout << mesh_report_json(rep).dump(2) << "\n";
    else
      std::cout << format_mesh_report(rep);
    return 0;
  }
  // mesh check
  if (repair) {
    const int n = repair_orientation(mesh);
    write_gmsh22(mesh, p.text("--repair"));
    std::cout << "re-oriented " << n << " tets; wrote " << p.text("--repair") << "\n";
  }
  const MeshReport rep = analyse_mesh(mesh);
  std::cout << format_mesh_report(rep);
  if (mesh.num_points() == 0 || mesh.num_tets() == 0) {
    std::cerr << "tmlab: error: " << p.positional[0] << ": the mesh has " << mesh.num_points()
              << " nodes and " << mesh.num_tets()
              << " tetrahedra: nothing to simulate (a volume mesh of linear tets, Gmsh type 4, "
              << "is needed)\n";
    return 1;
  }
  if (!rep.inverted.empty() || !rep.degenerate.empty()) {
    std::cerr << "tmlab: error: " << p.positional[0] << ": " << rep.inverted.size() << " inverted and "
              << rep.degenerate.size() << " degenerate tets";
    if (!rep.inverted.empty())
      std::cerr << " (first inverted: " << mesh.tet_name(rep.inverted.front()) << ")";
    if (!rep.degenerate.empty())
      std::cerr << " (first degenerate: " << mesh.tet_name(rep.degenerate.front()) << ")";
    std::cerr << "\n";
    return 1;
  }
  std::cout << "check: OK (no inverted or degenerate tets)\n";
  return 0;
}

}  // namespace tmlab::cli
