// meshtool: thin command-line driver over tmlab::core's mesh functions.
//   meshtool info IN [--json]
//   meshtool convert IN OUT.msh [--scale F | --scale-to-extent L] [--translate X Y Z] [--repair]
//   meshtool box OUT.msh NX NY NZ [--lo X Y Z] [--hi X Y Z]
//   meshtool cook OUT.msh CELLS [--layers N]   (Cook's membrane, core/mesh/cook_membrane.hpp)
// Output files are Gmsh 2.2 ASCII. Errors print "meshtool: <message>" and exit with status 1.
#include "core/base/error.hpp"
#include "core/io/output_file.hpp"
#include "core/mesh/cook_membrane.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace {

const char* kUsage =
    "usage:\n"
    "  meshtool info IN [--json]\n"
    "  meshtool convert IN OUT.msh [--scale F | --scale-to-extent L] [--translate X Y Z] [--repair]\n"
    "  meshtool box OUT.msh NX NY NZ [--lo X Y Z] [--hi X Y Z]\n"
    "  meshtool cook OUT.msh CELLS [--layers N]\n";

double parse_double(const std::string& s, const std::string& what) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size() || s.empty()) throw tmlab::Error(what + ": '" + s + "' is not a number");
  return v;
}

int parse_int(const std::string& s, const std::string& what) {
  std::size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size() || s.empty()) throw tmlab::Error(what + ": '" + s + "' is not an integer");
  return v;
}

/// Consumes three numbers after option args[i].
tmlab::Vec3 take_vec3(const std::vector<std::string>& args, std::size_t& i) {
  if (i + 3 >= args.size()) throw tmlab::Error(args[i] + " needs three numbers");
  tmlab::Vec3 v(parse_double(args[i + 1], args[i]), parse_double(args[i + 2], args[i]),
                parse_double(args[i + 3], args[i]));
  i += 3;
  return v;
}

int cmd_info(const std::vector<std::string>& args) {
  if (args.empty() || args.size() > 2 || (args.size() == 2 && args[1] != "--json"))
    throw tmlab::Error(kUsage);
  const tmlab::MeshReport report = tmlab::analyse_mesh(tmlab::read_mesh(args[0]));
  if (args.size() == 2) {
    std::cout << tmlab::mesh_report_json(report).dump(2) << "\n";
  } else {
    std::cout << tmlab::format_mesh_report(report);
  }
  return 0;
}

int cmd_convert(const std::vector<std::string>& args) {
  if (args.size() < 2) throw tmlab::Error(kUsage);
  tmlab::check_output_files({args[1]}, {args[0]}, /*overwrite=*/true);  // never over the input
  tmlab::GmshReadInfo info;
  tmlab::Mesh mesh = tmlab::read_gmsh(args[0], &info);
  std::cout << "read " << args[0] << " (Gmsh format " << info.format_version << "), skipped "
            << info.skipped_total() << " line/quad elements\n";
  for (std::size_t i = 2; i < args.size(); ++i) {
    if (args[i] == "--scale" && i + 1 < args.size()) {
      const double f = parse_double(args[++i], "--scale");
      tmlab::scale_mesh(mesh, f);
      std::cout << "scaled by " << f << "\n";
    } else if (args[i] == "--scale-to-extent" && i + 1 < args.size()) {
      const double target = parse_double(args[++i], "--scale-to-extent");
      const tmlab::MeshReport r = tmlab::analyse_mesh(mesh);
      const double extent = (r.bbox_max - r.bbox_min).maxCoeff();
      if (!(extent > 0.0)) throw tmlab::Error("--scale-to-extent: mesh has zero extent");
      tmlab::scale_mesh(mesh, target / extent);
      std::printf("scaled by %.17g (largest extent %.17g -> %.17g)\n", target / extent, extent, target);
    } else if (args[i] == "--translate") {
      const tmlab::Vec3 t = take_vec3(args, i);
      tmlab::translate_mesh(mesh, t);
      std::cout << "translated by (" << t.transpose() << ")\n";
    } else if (args[i] == "--repair") {
      std::cout << "repaired orientation of " << tmlab::repair_orientation(mesh) << " tets\n";
    } else {
      throw tmlab::Error("unknown or incomplete option '" + args[i] + "'\n" + kUsage);
    }
  }
  tmlab::write_gmsh22(mesh, args[1]);
  mesh.source = args[1];
  std::cout << "wrote " << args[1] << "\n" << tmlab::format_mesh_report(tmlab::analyse_mesh(mesh));
  return 0;
}

int cmd_box(const std::vector<std::string>& args) {
  if (args.size() < 4) throw tmlab::Error(kUsage);
  tmlab::Vec3 lo = tmlab::Vec3::Zero();
  tmlab::Vec3 hi = tmlab::Vec3::Ones();
  for (std::size_t i = 4; i < args.size(); ++i) {
    if (args[i] == "--lo") {
      lo = take_vec3(args, i);
    } else if (args[i] == "--hi") {
      hi = take_vec3(args, i);
    } else {
      throw tmlab::Error("unknown option '" + args[i] + "'\n" + kUsage);
    }
  }
  const tmlab::Mesh mesh = tmlab::make_box_mesh(lo, hi, parse_int(args[1], "NX"), parse_int(args[2], "NY"),
                                                parse_int(args[3], "NZ"));
  tmlab::write_gmsh22(mesh, args[0]);
  std::cout << "wrote " << args[0] << ": " << mesh.num_points() << " points, " << mesh.num_tets()
            << " tets\n";
  return 0;
}

int cmd_cook(const std::vector<std::string>& args) {
  if (args.size() < 2) throw tmlab::Error(kUsage);
  tmlab::CookMembraneSpec spec;
  spec.cells = parse_int(args[1], "CELLS");
  for (std::size_t i = 2; i < args.size(); ++i) {
    if (args[i] == "--layers" && i + 1 < args.size()) {
      spec.layers = parse_int(args[++i], "--layers");
    } else {
      throw tmlab::Error("unknown option '" + args[i] + "'\n" + kUsage);
    }
  }
  const tmlab::Mesh mesh = tmlab::make_cook_membrane_mesh(spec);
  tmlab::write_gmsh22(mesh, args[0]);
  std::cout << "wrote " << args[0] << ": " << mesh.num_points() << " points, " << mesh.num_tets()
            << " tets\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> all(argv + 1, argv + argc);
  if (all.empty() || all[0] == "-h" || all[0] == "--help") {
    std::cout << kUsage;
    return all.empty() ? 1 : 0;
  }
  const std::vector<std::string> args(all.begin() + 1, all.end());
  try {
    if (all[0] == "info") return cmd_info(args);
    if (all[0] == "convert") return cmd_convert(args);
    if (all[0] == "box") return cmd_box(args);
    if (all[0] == "cook") return cmd_cook(args);
    throw tmlab::Error("unknown command '" + all[0] + "'\n" + kUsage);
  } catch (const tmlab::Error& e) {
    std::cerr << "meshtool: " << e.what() << "\n";
    return 1;
  }
}
