// Test helpers of the runner's pieces: a temporary directory holding a 1 cm cube mesh (3 x 3 x 3
// cells) and the case files the tests build their Problem from.
#pragma once

#include "core/config/case_config.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/testing/temp_dir.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace tmlab::tm::runner {

class RunnerTestCase : public testing::TempDirTest {
 protected:
  static constexpr double kL = 0.01;  ///< the cube's edge, m

  void SetUp() override {
    TempDirTest::SetUp();
    write_gmsh22(make_box_mesh(Vec3(0, 0, 0), Vec3(kL, kL, kL), 3, 3, 3), (dir_ / "cube.msh").string());
  }

  /// Uniaxial stretch by `d` of the cube with symmetry planes x = 0, y = 0, z = 0, static, 4 steps,
  /// a probe at the far corner.
  static nlohmann::json uniaxial(double d) {
    nlohmann::json j = nlohmann::json::parse(R"({
      "name": "uniaxial", "model": "tensor_mass",
      "mesh": {"file": "cube.msh"},
      "material": {"E": 10000, "nu": 0.3, "density": 1000},
      "boundary": [
        {"name": "x0", "nodes": {"plane": {"axis": "x", "value": 0}}, "components": "x"},
        {"name": "y0", "nodes": {"plane": {"axis": "y", "value": 0}}, "components": "y"},
        {"name": "z0", "nodes": {"plane": {"axis": "z", "value": 0}}, "components": "z"},
        {"name": "pull", "nodes": {"plane": {"axis": "x", "value": 0.01}}, "components": "x",
         "function": {"type": "ramp", "t0": 0, "t1": 1}}
      ],
      "solver": {"type": "static", "steps": 4},
      "output": {"probes": [{"name": "corner", "point": [0.01, 0.01, 0.01]}]}
    })");
    j["boundary"][3]["value"] = nlohmann::json::array({d, 0.0, 0.0});
    return j;
  }

  /// The cube on rollers pressed by a frictionless plane moving down by `d` (static, 2 steps).
  static nlohmann::json platen(double d) {
    nlohmann::json j = nlohmann::json::parse(R"({
      "name": "platen", "mesh": {"file": "cube.msh"},
      "material": {"E": 10000, "nu": 0.3, "density": 1000},
      "boundary": [
        {"name": "x0", "nodes": {"plane": {"axis": "x", "value": 0}}, "components": "x"},
        {"name": "y0", "nodes": {"plane": {"axis": "y", "value": 0}}, "components": "y"},
        {"name": "z0", "nodes": {"plane": {"axis": "z", "value": 0}}, "components": "z"}
      ],
      "contact": {"bodies": [{"name": "top", "type": "plane", "point": [0, 0, 0.01], "normal": [0, 0, -1],
                              "function": {"type": "ramp", "t0": 0, "t1": 1}}]},
      "solver": {"type": "static", "steps": 2}
    })");
    j["contact"]["bodies"][0]["displacement"] = nlohmann::json::array({0.0, 0.0, -d});
    return j;
  }

  /// The case of `j` as `run` reads it (mesh path relative to the test's directory).
  CaseConfig config(const nlohmann::json& j) const {
    return parse_case(j, (dir_ / "case.json").string(), {dir_.string()});
  }
};

}  // namespace tmlab::tm::runner
