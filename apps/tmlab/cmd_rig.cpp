// tmlab rig: a mechanical test as a generated mesh and an ordinary case file (calibration/rigs);
// with --data, the test of a tmlab-measured/1 data set, driven by its measured displacement column
// (calibration/rigs/rig_from_data.hpp).
#include "commands.hpp"

#include "cli_args.hpp"
#include "command_specs.hpp"

#include "calibration/data/measured_data.hpp"
#include "calibration/rigs/rig.hpp"
#include "calibration/rigs/rig_from_data.hpp"
#include "core/base/error.hpp"
#include "core/results/run_output.hpp"

#include <cmath>
#include <iostream>

namespace tmlab::cli {

namespace {

// The mesh resolution and the load steps, the same for every rig (the library's limits).
void apply_resolution(const ParsedOptions& p, int& cells, int& layers, double& grading, int& steps) {
  p.assign_if_given("--cells", cells);
  p.assign_if_given("--layers", layers);
  p.assign_if_given("--grading", grading);
  p.assign_if_given("--steps-per-segment", steps);
}

rigs::RigTest rig_test(const std::string& name) {
  if (name == "unconfined") return rigs::RigTest::UnconfinedCompression;
  if (name == "confined") return rigs::RigTest::ConfinedCompression;
  if (name == "tension") return rigs::RigTest::UniaxialTension;
  try {
    return rigs::parse_rig_test(name, "rig test");
  } catch (const Error& e) {
    throw UsageError(std::string(e.what()) + "; short forms: unconfined, confined, tension");
  }
}

// The sample, fixture and mesh options.
void apply_geometry(const ParsedOptions& p, rigs::RigSpec& s) {
  if (p.given("--shape")) s.shape = rigs::parse_sample_shape(p.text("--shape"), "--shape");
  if (p.given("--size")) {
    const auto v = p.numbers("--size");
    s.size_x = v[0];
    s.size_y = v[1];
    s.height = v[2];
  }
  p.assign_if_given("--radius", s.radius);
  p.assign_if_given("--height", s.height);
  if (p.given("--indenter")) s.indenter = rigs::parse_indenter_shape(p.text("--indenter"), "--indenter");
  p.assign_if_given("--indenter-radius", s.indenter_radius);
  if (p.given("--at")) {
    const auto v = p.numbers("--at");
    s.cx = v[0];
    s.cy = v[1];
  }
  if (p.given("--bottom")) s.bottom = rigs::parse_support(p.text("--bottom"), "--bottom");
  if (p.given("--platens")) s.platens = rigs::parse_support(p.text("--platens"), "--platens");
  apply_resolution(p, s.cells, s.layers, s.grading, s.steps_per_sample);
}

// The material section and the model.
void apply_material(const ParsedOptions& p, rigs::RigSpec& s) {
  if (p.given("--model")) s.model = p.text("--model");
  if (p.given("--element")) {
    s.element = p.text("--element");
    // The elements other than p1 run on the F-based kernel only: its model unless one is named.
    if (s.element != "p1" && !p.given("--model")) s.model = "hyperelastic_tl";
  }
  if (p.given("--material")) {
    try {
      s.material = nlohmann::json::parse(p.text("--material"));
    } catch (const nlohmann::json::exception& e) {
      throw UsageError(std::string("--material is not valid JSON: ") + e.what());
    }
    if (!s.material.is_object())
      throw UsageError("--material must be a JSON object (the case file's material section)");
  }
  for (const char* key : {"E", "nu", "density"}) {
    const std::string opt = std::string("--") + key;
    if (p.given(opt)) s.material[key] = p.decimal(opt);
  }
}

// The displacement history.
void apply_loading(const ParsedOptions& p, rigs::RigSpec& s) {
  const bool tension = s.test == rigs::RigTest::UniaxialTension;
  double depth = 0.1 * s.height, ramp = 1.0, hold = 0.0;
  p.assign_if_given("--depth", depth);
  p.assign_if_given("--ramp", ramp);
  p.assign_if_given("--hold", hold);
  const double signed_depth = tension ? -std::abs(depth) : depth;
  if (p.given("--cycles")) {
    s.history = rigs::DisplacementHistory::cycles(signed_depth, ramp, static_cast<int>(p.whole("--cycles")));
  } else {
    s.history = rigs::DisplacementHistory::ramp_hold(signed_depth, ramp, hold);
  }
}

// --data NAME.csv [--test ID]: the rig of a measured test (rig_from_data): the test, indenter,
// sample and supports from NAME.json, the history from the test's time_s and displacement_m
// columns. Only the mesh resolution, the material and the model are options.
rigs::RigSpec data_rig(const ParsedOptions& p) {
  if (!p.positional.empty())
    throw UsageError(
        "rig --data takes the test from the data set (its key 'test'); give no test name (got '" +
        p.positional[0] + "')");
  for (const char* opt : {"--shape", "--size", "--radius", "--height", "--indenter", "--indenter-radius",
                          "--at", "--bottom", "--platens", "--depth", "--ramp", "--hold", "--cycles"})
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
  rigs::RigFromDataMesh mesh;
  int steps = 1;  // one load step across the shortest sampling interval
  apply_resolution(p, mesh.cells, mesh.layers, mesh.grading, steps);
  rigs::RigSpec s = rigs::rig_from_data(data, k, mesh);
  s.steps_per_sample = steps;
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
  rigs::RigSpec s;
  s.test = rig_test(p.positional[0]);
  s.name = p.given("--name") ? p.text("--name") : rigs::rig_test_name(s.test);
  if (s.test != rigs::RigTest::Indentation) {
    // Platen tests default to the phantom geometry (a 50 mm x 30 mm cylinder); tension is gripped.
    s.shape = rigs::SampleShape::Cylinder;
    s.height = 0.03;
    s.cells = 8;
    s.layers = 10;
    if (s.test == rigs::RigTest::UniaxialTension) s.platens = rigs::Support::Bonded;
  }
  apply_geometry(p, s);
  apply_loading(p, s);
  apply_material(p, s);
  const auto case_file = rigs::write_rig(s, p.text("--out"), w);
  std::cout << "rig: " << rigs::rig_test_name(s.test) << " written to " << case_file.string() << " (mesh "
            << (case_file.parent_path() / (s.name + ".msh")).string() << ")\nrun it with: tmlab run "
            << case_file.string() << "\n";
  return 0;
}

}  // namespace tmlab::cli
