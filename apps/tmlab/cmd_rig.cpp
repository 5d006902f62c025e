// tmlab rig: a mechanical test as a generated mesh and an ordinary case file (calibration/rigs);
// with --data, the test of a tmlab-measured/1 data set, driven by its measured displacement column
// (calibration/rigs/rig_from_data.hpp).
#include "commands.hpp"

#include "cli_args.hpp"
#include "command_specs.hpp"
#include "rig_options.hpp"

#include "calibration/data/measured_data.hpp"
#include "calibration/rigs/rig.hpp"
#include "calibration/rigs/rig_from_data.hpp"
#include "core/base/error.hpp"
#include "core/results/run_output.hpp"

#include <cmath>
#include <iostream>

namespace tmlab::cli {

namespace {

// --data NAME.csv [--test ID]: the rig of a measured test (rig_from_data): the test, indenter,
// sample and supports from NAME.json, the history from the test's time_s and displacement_m
// columns. Only the mesh resolution, the material and the model are options.
rigs::RigSpec data_rig(const ParsedOptions& p) {
  if (!p.positional.empty())
    throw UsageError(
        "rig --data takes the test from the data set (its key 'test'); give no test name (got '" +
        p.positional[0] + "')");
  for (const char* opt :
       {"--shape", "--size", "--radius", "--height", "--indenter", "--indenter-radius", "--at", "--bottom",
        "--platens", "--indenter-contact", "--depth", "--ramp", "--hold", "--cycles"})
    if (p.given(opt))
      throw UsageError(std::string(opt) +
                       " does not go with --data: the data set gives the sample, the fixture "
                       "and the history");
  const std::string file = p.text("--data");
  const measured::DataSet data = measured::read_data_set(file);
  std::size_t k = 0;
  if (p.given("--test")) {
    const std::string id = p.text("--test");
    std::string ids;
    for (k = 0; k < data.tests.size() && data.tests[k].id != id; ++k)
      ids += (ids.empty() ? "" : ", ") + data.tests[k].id;
    if (k == data.tests.size()) throw Error(file + ": --test: no test '" + id + "' (the tests: " + ids + ")");
  } else if (data.tests.size() > 1) {
    std::string ids;
    for (const measured::Test& t : data.tests) ids += (ids.empty() ? "" : ", ") + t.id;
    throw UsageError("rig --data: " + file + " holds " + std::to_string(data.tests.size()) +
                     " tests; choose one with --test ID (" + ids + ")");
  }
  // The data rigs keep the explicit form (RigFromDataMesh) unless --contact-cells or --rim-cells.
  rigs::RigFromDataMesh mesh;
  const bool rule = !explicit_mesh_given(p) && (p.given("--contact-cells") || p.given("--rim-cells"));
  if (rule) mesh.contact_cells = rigs::kDefaultContactCells;
  rigs::RigSpec s = rigs::rig_from_data(data, k, mesh);
  s.steps_per_sample = 1;  // one load step across the shortest sampling interval
  apply_resolution(p, s, mesh.cells, mesh.layers);
  const std::string test_id = data.tests[k].id;
  std::string name = data.meta.name + (test_id.empty() || data.tests.size() == 1 ? "" : "-" + test_id);
  if (!result_name_problem(name).empty()) name = "data_rig";
  s.name = p.given("--name") ? p.text("--name") : name;
  apply_material(p, s);
  return s;
}

}  // namespace

int cmd_rig(const std::vector<std::string>& args) {
  const ParsedOptions p = parse(rig_spec(), args);
  rigs::RigWriteOptions w;
  w.overwrite = p.flag("--overwrite");
  if (p.given("--data")) {
    if (!p.given("--out")) throw UsageError("rig needs --out DIR (where NAME.json and NAME.msh go)");
    const rigs::RigSpec s = data_rig(p);
    // The data set's own files are never written over (NAME.json could be the rig's case file).
    w.inputs = {p.text("--data"), measured::metadata_path(p.text("--data"))};
    const auto case_file = rigs::write_rig(s, p.text("--out"), w);
    std::cout << "rig: " << rigs::rig_test_name(s.test) << " of " << p.text("--data") << " written to "
              << case_file.string() << " (mesh " << (case_file.parent_path() / (s.name + ".msh")).string()
              << "; " << s.history.t.size() << " history samples)\nrun it with: tmlab run "
              << case_file.string() << "\n";
    return 0;
  }
  if (p.given("--test")) throw UsageError("--test selects a test of a data set: it needs --data NAME.csv");
  if (p.positional.size() != 1) {
    throw UsageError("rig needs one test: indentation | unconfined | confined | tension (see tmlab help)");
  }
  if (!p.given("--out")) throw UsageError("rig needs --out DIR (where NAME.json and NAME.msh go)");
  const rigs::RigTest test = rig_test(p.positional[0]);
  const rigs::RigSpec s =
      rig_from_options(p, test, p.given("--name") ? p.text("--name") : rigs::rig_test_name(test));
  const auto case_file = rigs::write_rig(s, p.text("--out"), w);
  std::cout << "rig: " << rigs::rig_test_name(s.test) << " written to " << case_file.string() << " (mesh "
            << (case_file.parent_path() / (s.name + ".msh")).string() << ")\nrun it with: tmlab run "
            << case_file.string() << "\n";
  return 0;
}

}  // namespace tmlab::cli
