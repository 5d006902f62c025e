// tmlab rig: a mechanical test as a generated mesh and an ordinary case file (calibration/rigs);
// with --data, the test of a tmlab-measured/1 data set, driven by its measured displacement column
// (calibration/rigs/rig_from_data.hpp).
#include "commands.hpp"

#include "cli_args.hpp"

#include "calibration/data/measured_data.hpp"
#include "calibration/rigs/rig.hpp"
#include "calibration/rigs/rig_from_data.hpp"
#include "core/base/error.hpp"
#include "core/results/run_output.hpp"

#include <cmath>
#include <iostream>

namespace tmlab::cli {

namespace {

// "a,b,c": exactly n numbers; UsageError naming the option otherwise (an empty item is no number).
std::vector<double> parse_list(const std::string& key, const std::string& s, std::size_t n) {
  std::vector<double> v;
  for (std::size_t from = 0;;) {
    const std::size_t comma = s.find(',', from);
    v.push_back(
        parse_double(key, s.substr(from, comma == std::string::npos ? std::string::npos : comma - from)));
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  if (v.size() != n) throw UsageError(key + " needs " + std::to_string(n) + " comma-separated numbers");
  return v;
}

// A whole-number option within [min, max] into `out` (unchanged when the option is absent).
void whole(const Parsed& p, const char* key, long long min, long long max, int& out) {
  if (p.has(key)) out = static_cast<int>(parse_whole(key, p.get(key), min, max));
}

// The mesh resolution and the load steps, the same for every rig (the library's limits).
void apply_resolution(const Parsed& p, int& cells, int& layers, double& grading, int& steps) {
  whole(p, "--cells", rigs::kMinCells, rigs::kMaxCells, cells);
  whole(p, "--layers", 1, rigs::kMaxLayers, layers);
  if (p.has("--grading")) grading = parse_double("--grading", p.get("--grading"));
  whole(p, "--steps-per-segment", 1, rigs::kMaxLoadSteps, steps);
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
void apply_geometry(const Parsed& p, rigs::RigSpec& s) {
  if (p.has("--shape")) s.shape = rigs::parse_sample_shape(p.get("--shape"), "--shape");
  if (p.has("--size")) {
    const auto v = parse_list("--size", p.get("--size"), 3);
    s.size_x = v[0];
    s.size_y = v[1];
    s.height = v[2];
  }
  if (p.has("--radius")) s.radius = parse_double("--radius", p.get("--radius"));
  if (p.has("--height")) s.height = parse_double("--height", p.get("--height"));
  if (p.has("--indenter")) s.indenter = rigs::parse_indenter_shape(p.get("--indenter"), "--indenter");
  if (p.has("--indenter-radius"))
    s.indenter_radius = parse_double("--indenter-radius", p.get("--indenter-radius"));
  if (p.has("--at")) {
    const auto v = parse_list("--at", p.get("--at"), 2);
    s.cx = v[0];
    s.cy = v[1];
  }
  if (p.has("--bottom")) s.bottom = rigs::parse_support(p.get("--bottom"), "--bottom");
  if (p.has("--platens")) s.platens = rigs::parse_support(p.get("--platens"), "--platens");
  apply_resolution(p, s.cells, s.layers, s.grading, s.steps_per_sample);
}

// The material section and the model.
void apply_material(const Parsed& p, rigs::RigSpec& s) {
  if (p.has("--model")) s.model = p.get("--model");
  if (p.has("--material")) {
    try {
      s.material = nlohmann::json::parse(p.get("--material"));
    } catch (const nlohmann::json::exception& e) {
      throw UsageError(std::string("--material is not valid JSON: ") + e.what());
    }
    if (!s.material.is_object())
      throw UsageError("--material must be a JSON object (the case file's material section)");
  }
  for (const char* key : {"E", "nu", "density"}) {
    const std::string opt = std::string("--") + key;
    if (p.has(opt)) s.material[key] = parse_double(opt, p.get(opt));
  }
}

// The displacement history.
void apply_loading(const Parsed& p, rigs::RigSpec& s) {
  const bool tension = s.test == rigs::RigTest::UniaxialTension;
  const double depth = p.has("--depth") ? parse_double("--depth", p.get("--depth")) : 0.1 * s.height;
  const double signed_depth = tension ? -std::abs(depth) : depth;
  const double ramp = p.has("--ramp") ? parse_double("--ramp", p.get("--ramp")) : 1.0;
  if (p.has("--cycles")) {
    int n = 1;
    whole(p, "--cycles", 1, 100000, n);
    s.history = rigs::DisplacementHistory::cycles(signed_depth, ramp, n);
  } else {
    const double hold = p.has("--hold") ? parse_double("--hold", p.get("--hold")) : 0.0;
    s.history = rigs::DisplacementHistory::ramp_hold(signed_depth, ramp, hold);
  }
}

// --data NAME.csv [--test ID]: the rig of a measured test (rig_from_data): the test, indenter,
// sample and supports from NAME.json, the history from the test's time_s and displacement_m
// columns. Only the mesh resolution, the material and the model are options.
rigs::RigSpec data_rig(const Parsed& p) {
  if (!p.positional.empty())
    throw UsageError(
        "rig --data takes the test from the data set (its key 'test'); give no test name (got '" +
        p.positional[0] + "')");
  for (const char* opt : {"--shape", "--size", "--radius", "--height", "--indenter", "--indenter-radius",
                          "--at", "--bottom", "--platens", "--depth", "--ramp", "--hold", "--cycles"})
    if (p.has(opt))
      throw UsageError(std::string(opt) +
                       " does not go with --data: the data set gives the sample, the fixture "
                       "and the history");
  const measured::DataSet data = measured::read_data_set(p.get("--data"));
  std::size_t k = 0;
  if (p.has("--test")) {
    const std::string id = p.get("--test");
    std::string ids;
    for (k = 0; k < data.tests.size() && data.tests[k].id != id; ++k)
      ids += (ids.empty() ? "" : ", ") + data.tests[k].id;
    if (k == data.tests.size())
      throw Error(p.get("--data") + ": --test: no test '" + id + "' (the tests: " + ids + ")");
  } else if (data.tests.size() > 1) {
    std::string ids;
    for (const measured::Test& t : data.tests) ids += (ids.empty() ? "" : ", ") + t.id;
    throw UsageError("rig --data: " + p.get("--data") + " holds " + std::to_string(data.tests.size()) +
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
  s.name = p.get("--name", name);
  apply_material(p, s);
  return s;
}

}  // namespace

int cmd_rig(const std::vector<std::string>& args) {
  const Parsed p = parse(args,
                         {"--out",
                          "--name",
                          "--shape",
                          "--size",
                          "--radius",
                          "--height",
                          "--indenter",
                          "--indenter-radius",
                          "--at",
                          "--bottom",
                          "--platens",
                          "--cells",
                          "--layers",
                          "--grading",
                          "--depth",
                          "--ramp",
                          "--hold",
                          "--cycles",
                          "--material",
                          "--E",
                          "--nu",
                          "--density",
                          "--steps-per-segment",
                          "--model",
                          "--data",
                          "--test"},
                         {"--overwrite"});
  rigs::RigWriteOptions w;
  w.overwrite = p.has("--overwrite");
  if (p.has("--data")) {
    if (!p.has("--out")) throw UsageError("rig needs --out DIR (where NAME.json and NAME.msh go)");
    const rigs::RigSpec s = data_rig(p);
    // The data set's own files are never written over (NAME.json could be the rig's case file).
    w.inputs = {p.get("--data"), measured::metadata_path(p.get("--data"))};
    const auto case_file = rigs::write_rig(s, p.get("--out"), w);
    std::cout << "rig: " << rigs::rig_test_name(s.test) << " of " << p.get("--data") << " written to "
              << case_file.string() << " (mesh " << (case_file.parent_path() / (s.name + ".msh")).string()
              << "; " << s.history.t.size() << " history samples)\nrun it with: tmlab run "
              << case_file.string() << "\n";
    return 0;
  }
  if (p.has("--test")) throw UsageError("--test selects a test of a data set: it needs --data NAME.csv");
  if (p.positional.size() != 1) {
    throw UsageError("rig needs one test: indentation | unconfined | confined | tension (see tmlab help)");
  }
  if (!p.has("--out")) throw UsageError("rig needs --out DIR (where NAME.json and NAME.msh go)");
  rigs::RigSpec s;
  s.test = rig_test(p.positional[0]);
  s.name = p.get("--name", rigs::rig_test_name(s.test));
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
  const auto case_file = rigs::write_rig(s, p.get("--out"), w);
  std::cout << "rig: " << rigs::rig_test_name(s.test) << " written to " << case_file.string() << " (mesh "
            << (case_file.parent_path() / (s.name + ".msh")).string() << ")\nrun it with: tmlab run "
            << case_file.string() << "\n";
  return 0;
}

}  // namespace tmlab::cli
