// Tests of the test rigs: validation of the specification, the generated meshes, and the platen
// rigs run through the fast model against the homogeneous closed form (St VK, uniaxial stress or
// strain: linear tets represent the homogeneous state exactly, so the agreement is to round-off).
#include "calibration/rigs/rig.hpp"

#include "core/base/error.hpp"
#include "core/config/case_config.hpp"
#include "core/mesh/mesh_quality.hpp"
#include "core/mesh/sample_meshes.hpp"
#include "tensormass/runner/case_runner.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>

namespace tmlab::rigs {
namespace {

namespace fs = std::filesystem;

class RigTest_ : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tmlab_rig_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Writes the rig, reads the case back through the case-file parser and runs the fast model.
  nlohmann::json run(const RigSpec& spec) const {
    const fs::path case_file = write_rig(spec, dir_ / "rig");
    const CaseConfig c = load_case(case_file.string(), dir_.string());
    RunOptions o;
    o.results_root = (dir_ / "results").string();
    o.plots = false;
    return tm::run_case(c, o).summary;
  }
  fs::path dir_;
};

RigSpec cylinder_compression(RigTest test, Support platens, double d) {
  RigSpec s;
  s.name = "cyl";
  s.test = test;
  s.shape = SampleShape::Cylinder;
  s.radius = 0.025;
  s.height = 0.03;
  s.cells = 4;
  s.layers = 3;
  s.platens = platens;
  s.history = DisplacementHistory::ramp_hold(d, 1.0, 0.0);
  s.steps_per_sample = 4;
  s.material = {{"E", 10000.0}, {"nu", 0.3}, {"density", 1000.0}};
  return s;
}

double polygon_area(const RigSpec& s) {
  CylinderSpec c;
  c.radius = s.radius;
  c.height = s.height;
  c.rings = std::max(1, s.cells / 2);
  return cylinder_mesh_volume(c) / c.height;
}

TEST_F(RigTest_, UnconfinedFrictionlessMatchesUniaxialStress) {
  const double d = 0.003;  // 10 % compression
  const RigSpec s = cylinder_compression(RigTest::UnconfinedCompression, Support::Frictionless, d);
  const nlohmann::json summary = run(s);
  // St VK uniaxial stress: S_zz = E E_zz, force = -l S_zz A0 (positive in compression).
  const double l = 1.0 - d / s.height, ezz = 0.5 * (l * l - 1.0);
  const double force = -l * 10000.0 * ezz * polygon_area(s);
  const double fz = summary["final_reactions_N"]["top_platen"][2].get<double>();
  // The platen pushes the sample down: the reaction on the top face is the platen force, upward.
  EXPECT_NEAR(std::abs(fz), force, 1e-9 * force);
  EXPECT_GT(force, 0.0);
}

TEST_F(RigTest_, ConfinedMatchesUniaxialStrain) {
  const double d = 0.003;
  const RigSpec s = cylinder_compression(RigTest::ConfinedCompression, Support::Frictionless, d);
  const nlohmann::json summary = run(s);
  // Uniaxial strain: S_zz = (lambda + 2 mu) E_zz.
  const double E = 10000.0, nu = 0.3;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const double l = 1.0 - d / s.height, ezz = 0.5 * (l * l - 1.0);
  const double force = -l * (lambda + 2 * mu) * ezz * polygon_area(s);
  const double fz = summary["final_reactions_N"]["top_platen"][2].get<double>();
  EXPECT_NEAR(std::abs(fz), force, 1e-9 * force);
}

TEST_F(RigTest_, BondedPlatensBarrelAndStiffen) {
  // Bonded platens restrain the lateral expansion at the faces: the sample barrels and the force
  // exceeds the frictionless (homogeneous) one, which is the lower bound.
  const double d = 0.003;
  const nlohmann::json free =
      run(cylinder_compression(RigTest::UnconfinedCompression, Support::Frictionless, d));
  fs::remove_all(dir_ / "results");
  const nlohmann::json bonded = run(cylinder_compression(RigTest::UnconfinedCompression, Support::Bonded, d));
  const double f_free = std::abs(free["final_reactions_N"]["top_platen"][2].get<double>());
  const double f_bonded = std::abs(bonded["final_reactions_N"]["top_platen"][2].get<double>());
  EXPECT_GT(f_bonded, 1.001 * f_free);
}

TEST_F(RigTest_, IndentationCaseHasTheIndenterTouchingTheTop) {
  RigSpec s;
  s.name = "indent";
  s.history = DisplacementHistory::ramp_hold(0.002, 1.0, 10.0);
  const nlohmann::json c = rig_case(s, "indent.msh");
  ASSERT_TRUE(c.contains("contact"));
  const auto& body = c["contact"]["bodies"][0];
  EXPECT_EQ(body["type"], "sphere");
  EXPECT_DOUBLE_EQ(body["center"][2].get<double>() - body["radius"].get<double>(), s.height);
  EXPECT_EQ(c["solver"]["steps"].get<int>(), 110);  // 10 steps across the 1 s ramp, 11 s in all
  // The graded mesh has a node exactly under the indenter's first contact point.
  const Mesh m = rig_mesh(s);
  EXPECT_TRUE(analyse_mesh(m).inverted.empty());
  EXPECT_NE(std::find(m.points.begin(), m.points.end(), Vec3(0, 0, s.height)), m.points.end());
}

// The driving histories as the case file's time function: a ramp-and-hold and triangle cycles,
// tabulated as d(t) / peak, with the load steps landing on every kink.
TEST(RigHistory, RampHoldAndCyclesBecomeTheTimeFunction) {
  const DisplacementHistory rh = DisplacementHistory::ramp_hold(0.002, 1.0, 10.0);
  EXPECT_EQ(rh.t, (std::vector<double>{0.0, 1.0, 11.0}));
  EXPECT_EQ(rh.d, (std::vector<double>{0.0, 0.002, 0.002}));
  const DisplacementHistory cy = DisplacementHistory::cycles(0.003, 0.5, 2);
  EXPECT_EQ(cy.t, (std::vector<double>{0.0, 0.5, 1.0, 1.5, 2.0}));
  EXPECT_EQ(cy.d, (std::vector<double>{0.0, 0.003, 0.0, 0.003, 0.0}));
  EXPECT_DOUBLE_EQ(cy.peak(), 0.003);
  EXPECT_THROW(DisplacementHistory::cycles(0.003, 0.5, 0), Error);
  EXPECT_THROW(DisplacementHistory::ramp_hold(0.003, 0.0, 1.0), Error);

  RigSpec s;
  s.name = "cyc";
  s.test = RigTest::UnconfinedCompression;
  s.shape = SampleShape::Cylinder;
  s.history = cy;
  s.steps_per_sample = 4;
  const nlohmann::json c = rig_case(s, "cyc.msh");
  const nlohmann::json* top = nullptr;
  for (const auto& b : c["boundary"])
    if (b["name"] == "top_platen") top = &b;
  ASSERT_NE(top, nullptr);
  EXPECT_EQ((*top)["function"]["type"], "table");
  EXPECT_EQ((*top)["function"]["points"], nlohmann::json::parse("[[0,0],[0.5,1],[1,0],[1.5,1],[2,0]]"));
  EXPECT_DOUBLE_EQ((*top)["value"][2].get<double>(), -0.003);
  EXPECT_EQ(c["solver"]["steps"].get<int>(), 16);  // 4 steps per 0.5 s segment: kinks on step ends
  EXPECT_DOUBLE_EQ(c["solver"]["t_end"].get<double>(), 2.0);
}

TEST(RigValidation, RefusesImpossibleRigs) {
  RigSpec s;
  s.history = DisplacementHistory::ramp_hold(0.05, 1.0, 0.0);  // deeper than the 20 mm block
  EXPECT_THROW(validate(s), Error);
  s = RigSpec{};
  s.indenter_radius = 0.03;  // wider than the 40 mm block
  EXPECT_THROW(validate(s), Error);
  s = RigSpec{};
  s.test = RigTest::UniaxialTension;
  s.history = DisplacementHistory::ramp_hold(-0.002, 1.0, 0.0);
  s.platens = Support::Frictionless;
  EXPECT_THROW(validate(s), Error);
  s.platens = Support::Bonded;
  EXPECT_NO_THROW(validate(s));
  s.history = DisplacementHistory::ramp_hold(0.002, 1.0, 0.0);  // pushes in a tension test
  EXPECT_THROW(validate(s), Error);
  s = RigSpec{};
  s.name = "a b";
  EXPECT_THROW(validate(s), Error);
  EXPECT_THROW(parse_rig_test("shear", "test"), Error);
  EXPECT_EQ(parse_rig_test("confined_compression", "test"), RigTest::ConfinedCompression);
  try {
    s = RigSpec{};
    s.cells = 1;
    validate(s);
    FAIL() << "cells = 1 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cells"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tmlab::rigs
