// The option tables of the model commands (demo, run, compare, cases, mesh, version, help) and the
// list of every command (command_specs.hpp).
#include "command_specs.hpp"

#include "core/base/format.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace tmlab::cli {

OptionSpec results_option() { return text("--results", "DIR", "results root (default: <tmlab>/results)"); }
OptionSpec no_plots_option() { return flag("--no-plots", "skip the PNG plots"); }
OptionSpec resume_option() {
  return flag("--resume", "continue an interrupted run from its checkpoint (finished units reused)");
}
OptionSpec checkpoint_option() {
  return text("--checkpoint-every", "N|Ts|Tmin|off",
              "checkpoint every N units (steps, fits) or T of wall time (default 60s)\n"
              "and always on SIGINT/SIGTERM");
}

CommandSpec demo_spec() {
  return {"demo",
          {},
          "the liver pressed by a probe, on embedded defaults",
          {results_option(), no_plots_option()}};
}

CommandSpec run_spec() {
  return {"run",
          {"NAME|PATH [options]"},
          "run a case (a name from 'tmlab cases' or a case file)",
          {choice("--model", {"tensor_mass", "tl_oracle", "hyperelastic_tl", "reference"},
                  "override the case's model"),
           choice("--element", {"p1", "p1_anp", "p2", "p2_mean_dilatation"},
                  "override the case's mesh.element (docs/elements.md)"),
           choice("--degree", {"1", "2"}, "reference element degree").def("1"),
           choice("--time-integration", {"fixed_step", "ida"},
                  "reference viscoelastic time integration (IDA: the DAE, serial)")
               .def("fixed_step"),
           results_option(), no_plots_option(), checkpoint_option(),
           flag("--resume", "continue an interrupted run from its checkpoint (bit-identical)")}};
}

CommandSpec compare_spec() {
  return {
      "compare",
      {"NAME|PATH [options]"},
      "run the case with tensormass and the reference (or the oracle:\n"
      "results/<case>-compare-tl_oracle/); write results/<case>-compare/\n"
      "(compare.json: max relative differences)",
      {choice("--against", {"reference", "tl_oracle"}, "the second model").def("reference").role(kManifest),
       choice("--degree", {"1", "2"}, "reference element degree").def("1").role(kManifest),
       choice("--time-integration", {"fixed_step", "ida"}, "reference viscoelastic time integration")
           .def("fixed_step")
           .role(kManifest),
       results_option(), no_plots_option()}};
}

CommandSpec cases_spec() { return {"cases", {}, "list the shipped case files", {}}; }

CommandSpec mesh_info_spec() {
  return {"mesh info",
          {"FILE [options]"},
          "counts, volume, bounding box, quality",
          {decimal("--scale", "F", Interval{}, "multiply the coordinates by F"), flag("--json", "as JSON")}};
}

CommandSpec mesh_quadratic_spec() {
  return {"mesh quadratic",
          {"FILE --out OUT.msh [options]"},
          "write the 10-node (P2) mesh of a linear tet mesh, Gmsh 2.2 type 11\n"
          "(midside nodes at the edge midpoints; for other tools: tmlab runs P2\n"
          "from the linear mesh with mesh.element, docs/elements.md)",
          {decimal("--scale", "F", Interval{}, "multiply the coordinates by F"),
           text("--out", "OUT.msh", "the quadratic mesh (never over FILE)"),
           flag("--overwrite", "replace an existing OUT.msh")}};
}

CommandSpec mesh_check_spec() {
  return {"mesh check",
          {"FILE [options]"},
          "exit 1 if any tet is inverted or degenerate",
          {decimal("--scale", "F", Interval{}, "multiply the coordinates by F"),
           text("--repair", "OUT.msh", "write a re-oriented copy (never over FILE)"),
           flag("--overwrite", "replace an existing OUT.msh")}};
}

CommandSpec version_spec() { return {"version", {}, "git SHA and build of this binary", {}}; }

CommandSpec help_spec() {
  return {
      "help", {"[COMMAND]"}, "this text; 'tmlab help COMMAND' or 'tmlab COMMAND --help': one command", {}};
}

std::vector<CommandSpec> command_specs() {
  return {demo_spec(),       run_spec(),           compare_spec(),        cases_spec(),
          mesh_info_spec(),  mesh_check_spec(),    mesh_quadratic_spec(), paper_spec(),
          hereditary_spec(), workprecision_spec(), depth_limit_spec(),    realtime_spec(),
          verify_spec(),     data_convert_spec(),  data_show_spec(),      rig_spec(),
          converge_spec(),   fit_spec(),           bench_spec(),          discover_spec(),
          version_spec(),    help_spec()};
}

std::vector<CommandSpec> specs_of(const std::string& command) {
  std::vector<CommandSpec> out;
  for (CommandSpec& s : command_specs())
    if (s.name == command || s.name.rfind(command + " ", 0) == 0) out.push_back(std::move(s));
  return out;
}

std::string usage_text() {
  std::string s = "usage: tmlab <command> [options]\n\ncommands:\n";
  for (const CommandSpec& c : command_specs()) s += command_help(c);
  return s + "\nThe ./tmlab script also offers: ./tmlab test [ctest args], ./tmlab build.\n";
}

namespace {

/// Levenshtein distance (single-character insertions, deletions and substitutions).
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string unknown_command_message(const std::string& word) {
  const std::string tail = "\n(see 'tmlab help' for the commands and their options)\n";
  if (word == "inversion")
    return "unknown command 'inversion': tmlab inversion is now tmlab depth-limit (the same options; "
           "results in <results>/depth-limit/; see 'tmlab help depth-limit')\n";
  std::string best;
  std::size_t best_distance = 3;  // suggest within two edits only
  for (const CommandSpec& c : command_specs()) {
    const std::string name = c.name.substr(0, c.name.find(' '));  // "mesh info" -> "mesh"
    const std::size_t d = edit_distance(word, name);
    if (d < best_distance) best = name, best_distance = d;
  }
  return "unknown command '" + printable(word, 60) + "'" +
         (best.empty() ? "" : " (did you mean '" + best + "'?)") + tail;
}

}  // namespace tmlab::cli
