// Tests of the test rigs: validation of the specification, the generated meshes, and the platen
// rigs run through the fast model against the homogeneous closed form (St VK, uniaxial stress or
// strain: linear tets represent the homogeneous state exactly, so the agreement is to round-off).
#include "calibration/rigs/rig.hpp"

#include "core/base/error.hpp"
#include "core/config/case_config.hpp"
#include "core/mesh/mesh_quality.hpp"
#include "core/mesh/sample_meshes.hpp"
#include "runner/case_runner.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

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
    RigWriteOptions w;
    w.overwrite = true;  // one folder for the rigs a test compares
    const fs::path case_file = write_rig(spec, dir_ / "rig", w);
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

/// The message of validate(s) ("" when it accepts the rig).
std::string refusal(const RigSpec& s) {
  try {
    validate(s);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// The indenter's centre (--at): off the top face, too close to its edge, or not a number, the
// message names --at; an indenter wider than the face names its radius (issue 26).
TEST(RigValidation, IndenterPositionNamesAt) {
  RigSpec s;
  s.cx = s.cy = 0.5;  // metres: far off the 40 mm block
  std::string e = refusal(s);
  EXPECT_NE(e.find("--at (the indenter centre cx, cy): (500 mm, 500 mm) lies outside the top face, x in "
                   "+-20 mm and y in +-20 mm"),
            std::string::npos)
      << e;
  s.cx = 0.018;  // on the face, but the 5 mm indenter reaches over its edge
  s.cy = 0.0;
  e = refusal(s);
  EXPECT_NE(
      e.find("--at (the indenter centre cx, cy): (18 mm, 0 mm) is too close to the edge of the top face "
             "for the indenter radius 5 mm"),
      std::string::npos)
      << e;
  EXPECT_EQ(e.find("indenter_radius"), std::string::npos) << e;
  s.cx = std::nan("");
  EXPECT_NE(refusal(s).find("--at (the indenter centre cx, cy): must be two finite numbers"),
            std::string::npos);
  s = RigSpec{};
  s.indenter_radius = 0.03;
  EXPECT_NE(refusal(s).find("indenter_radius: the indenter (radius 30 mm) is wider than the top face"),
            std::string::npos);
  s = RigSpec{};
  s.cx = 0.01;
  EXPECT_EQ(refusal(s), "");
}

// A mesh too large to build is refused from its size before meshing (not std::bad_alloc), with
// the size, the memory, the limit and how to go lower.
TEST(RigValidation, MeshTooLargeIsRefusedFromItsSize) {
  RigSpec s;
  s.cells = s.layers = 400;
  const std::string e = refusal(s);
  EXPECT_NE(
      e.find("rig 'rig': cells, layers: cells 400 and layers 400 give a block of 400 x 400 x 400 cells"),
      std::string::npos)
      << e;
  EXPECT_NE(e.find(": 64,481,201 nodes and 384,000,000 tets (about "), std::string::npos) << e;
  EXPECT_NE(e.find("GB of memory to generate"), std::string::npos) << e;
  EXPECT_NE(e.find("the limit is 2,000,000 tets"), std::string::npos) << e;
  EXPECT_NE(e.find("give fewer cells or layers"), std::string::npos) << e;
  s.test = RigTest::UnconfinedCompression;
  s.shape = SampleShape::Cylinder;
  EXPECT_NE(refusal(s).find("a cylinder of 200 rings (cells / 2) and 400 layers"), std::string::npos);
  s.cells = 40;  // 20 rings, 400 layers: 2,880,000 tets
  EXPECT_NE(refusal(s).find("2,880,000 tets"), std::string::npos);
  s.layers = 100;  // 720,000 tets
  EXPECT_EQ(refusal(s), "");
  // A sample so slender its cell count is astronomical still gets its size, not an overflow (the
  // explicit form, whose size is checked before the indenter).
  s = RigSpec{};
  s.cells = 16;
  s.layers = 8;
  s.size_x = 1e10;
  s.size_y = 1e-10;
  EXPECT_NE(refusal(s).find("tets (about "), std::string::npos) << refusal(s);
}

// The contact rule (docs/rigs.md): uniform cells of exactly a_max / contact_cells within
// contact_zone a_max of the indenter's axis and of the top face, a_max = sqrt(R d_max) for a sphere
// and the radius for a flat punch; growth beyond, bounded by `growth`.
TEST(RigMesh, ContactRuleSetsTheCellSizeUnderTheIndenter) {
  for (const IndenterShape shape : {IndenterShape::Sphere, IndenterShape::FlatPunch}) {
    RigSpec s;
    s.indenter = shape;
    s.cx = 0.004;  // off centre: the zone follows the indenter
    s.contact_cells = 5;
    const double a = shape == IndenterShape::Sphere ? std::sqrt(0.005 * 0.002) : 0.005;
    EXPECT_DOUBLE_EQ(rig_contact_radius(s), a);
    const double h = a / 5.0, zone = std::ceil(1.5 * 5) * h;  // 8 whole cells reach past 1.5 a_max
    EXPECT_GE(zone, 1.5 * a);
    const BoxGrid g = rig_grid(s);
    const double focus[3] = {s.cx, s.cy, s.height};
    for (int k = 0; k < 3; ++k) {
      const std::vector<double>& c = g[static_cast<std::size_t>(k)];
      EXPECT_NE(std::find(c.begin(), c.end(), focus[k]), c.end()) << "axis " << k;
      int fine = 0;
      for (std::size_t i = 1; i < c.size(); ++i) {
        const double w = c[i] - c[i - 1];
        if (std::max(std::abs(c[i] - focus[k]), std::abs(c[i - 1] - focus[k])) <= zone * (1 + 1e-12)) {
          EXPECT_NEAR(w, h, 1e-12 * h) << "axis " << k << " cell " << i;
          ++fine;
        }
        EXPECT_GE(w, h * (1 - 1e-12));
        if (i + 1 < c.size()) {
          EXPECT_LE((c[i + 1] - c[i]) / w, s.growth * (1 + 1e-12));
        }
        if (i + 1 < c.size()) {
          EXPECT_LE(w / (c[i + 1] - c[i]), s.growth * (1 + 1e-12));
        }
      }
      // The zone is covered: 8 cells (ceil(1.5 * 5)) on each side of the focus (one side in depth).
      EXPECT_GE(fine, k == 2 ? 8 : 16) << "axis " << k;
    }
    const Mesh m = rig_mesh(s);
    EXPECT_EQ(m.points.size(), g[0].size() * g[1].size() * g[2].size());
    EXPECT_TRUE(analyse_mesh(m).inverted.empty());
  }
}

// refined(spec, r): every spacing divided by r. A whole ratio keeps every node (nested meshes) and
// multiplies every axis's cell count by r; in the fine zone the spacing is a_max / (r contact_cells).
TEST(RigMesh, RefinedScalesEverySpacing) {
  RigSpec s;
  const RigSpec s2 = refined(s, 2.0);
  EXPECT_EQ(s2.refinement, 2.0);
  EXPECT_EQ(refined(s2, 1.5).refinement, 3.0);
  const BoxGrid g1 = rig_grid(s), g2 = rig_grid(s2);
  const double h = rig_contact_radius(s) / s.contact_cells;
  for (std::size_t k = 0; k < 3; ++k) {
    ASSERT_EQ(g2[k].size() - 1, 2 * (g1[k].size() - 1)) << k;
    for (std::size_t i = 0; i < g1[k].size(); ++i)
      EXPECT_NEAR(g2[k][2 * i], g1[k][i], 1e-15) << k << " " << i;
    for (std::size_t i = 1; i < g2[k].size(); ++i) {
      const double parent = g1[k][(i + 1) / 2] - g1[k][(i - 1) / 2];
      const double child = g2[k][i] - g2[k][i - 1];
      EXPECT_GT(2.0 * child / parent, 1.0 / s.growth);
      EXPECT_LT(2.0 * child / parent, s.growth);
      if (std::abs(parent - h) < 1e-12 * h) {
        EXPECT_NEAR(child, h / 2.0, 1e-12 * h);
      }
    }
  }
  // The explicit form: cells and layers times the ratio.
  RigSpec e;
  e.cells = 8;
  e.layers = 4;
  const BoxGrid ge = rig_grid(refined(e, 1.5));
  EXPECT_EQ(ge[0].size(), 13u);
  EXPECT_EQ(ge[2].size(), 7u);
  EXPECT_THROW(refined(s, 0.0), Error);
}

// The explicit form (cells > 0) is the earlier mesh, to the bit.
TEST(RigMesh, ExplicitFormIsTheEarlierMesh) {
  RigSpec s;
  s.cells = 16;
  s.layers = 8;
  s.grading = 2.0;
  BlockSpec b;
  b.nx = b.ny = 16;
  b.nz = 8;
  b.grading = 2.0;
  const Mesh m = rig_mesh(s), ref = make_block_mesh(b);
  EXPECT_EQ(m.points, ref.points);
  EXPECT_EQ(m.tets, ref.tets);
  s = RigSpec{};
  s.test = RigTest::UnconfinedCompression;
  s.shape = SampleShape::Cylinder;
  s.height = 0.03;
  s.cells = 8;
  s.layers = 10;
  CylinderSpec c;
  c.radius = 0.025;
  c.height = 0.03;
  c.rings = 4;
  c.layers = 10;
  EXPECT_EQ(rig_mesh(s).points, make_cylinder_mesh(c).points);
}

// Platen rigs: uniform cells of L / rim_cells (L = min(radius, height / 2)) at the rim and at both
// platens, growing towards the axis and the mid-height.
TEST(RigMesh, PlatenRuleRefinesTheRimAndThePlatens) {
  RigSpec s;
  s.test = RigTest::UnconfinedCompression;
  s.shape = SampleShape::Cylinder;
  s.platens = Support::Bonded;
  s.height = 0.03;
  s.history = DisplacementHistory::ramp_hold(0.003, 1.0, 0.0);
  const double h = 0.015 / kDefaultRimCells;
  const BoxGrid g = rig_grid(s);
  const std::vector<double>& r = g[0];
  const std::vector<double>& z = g[2];
  EXPECT_EQ(r.front(), 0.0);
  EXPECT_EQ(r.back(), s.radius);
  EXPECT_NEAR(r.back() - r[r.size() - 2], h, 1e-12 * h);
  EXPECT_NEAR(z[1] - z[0], h, 1e-12 * h);
  EXPECT_NEAR(z.back() - z[z.size() - 2], h, 1e-12 * h);
  EXPECT_GT(r[1] - r[0], h);                            // coarser at the axis
  EXPECT_GT(z[z.size() / 2] - z[z.size() / 2 - 1], h);  // and at mid-height
  const Mesh m = rig_mesh(s);
  EXPECT_TRUE(analyse_mesh(m).inverted.empty());
  CylinderSpec c;
  c.radius = s.radius;
  c.height = s.height;
  c.rings = static_cast<int>(r.size()) - 1;
  double volume = 0.0;
  for (Index e = 0; e < m.num_tets(); ++e) volume += tet_signed_volume(m, e);
  EXPECT_NEAR(volume, cylinder_mesh_volume(c), 1e-12);
  // A block between bonded platens: the four sides too.
  s.shape = SampleShape::Block;
  const BoxGrid b = rig_grid(s);
  EXPECT_NEAR(b[0][1] - b[0][0], h, 1e-12 * h);
  EXPECT_NEAR(b[1].back() - b[1][b[1].size() - 2], h, 1e-12 * h);
}

TEST(RigValidation, ContactRuleFieldsAreNamed) {
  const auto refused = [](const std::function<void(RigSpec&)>& change, const std::string& what) {
    RigSpec s;
    change(s);
    const std::string e = refusal(s);
    EXPECT_NE(e.find(what), std::string::npos) << "expected '" << what << "' in: " << e;
  };
  refused([](RigSpec& s) { s.contact_cells = 0; }, "rig 'rig': contact_cells: must be in [1, 200] (got 0)");
  refused([](RigSpec& s) { s.contact_cells = -3; }, "contact_cells: must be in [1, 200]");
  refused([](RigSpec& s) { s.rim_cells = 0; }, "rim_cells: must be in [1, 200]");
  refused([](RigSpec& s) { s.growth = 0.9; }, "growth: must be in [1, 2]");
  refused([](RigSpec& s) { s.growth = std::nan(""); }, "growth: must be in [1, 2]");
  refused([](RigSpec& s) { s.contact_zone = 0.1; }, "contact_zone: must be in [0.5, 10]");
  refused([](RigSpec& s) { s.refinement = 0.0; }, "refinement: must be in (0, 16]");
  refused([](RigSpec& s) { s.refinement = std::nan(""); }, "refinement: must be in (0, 16]");
  refused([](RigSpec& s) { s.layers = 8; }, "layers: goes with cells");
  refused([](RigSpec& s) { s.cells = 8; }, "layers: must be in [1, 400]");
  // A huge mesh from the rule, refused from its size.
  refused(
      [](RigSpec& s) { s.contact_cells = 200; },
      "rig 'rig': contact_cells, contact_zone, growth, refinement: contact_cells 200 (h = 0.01581 mm across "
      "a_max = 3.162 mm) give a block of ");
  refused([](RigSpec& s) { s.contact_cells = 200; }, "the limit is 2,000,000 tets");
  refused([](RigSpec& s) { s.contact_cells = 200; },
          "give fewer contact_cells, a larger growth or a smaller refinement");
  refused([](RigSpec& s) { s.refinement = 16.0; }, "at refinement 16 give a block of");
  refused(
      [](RigSpec& s) {
        s.test = RigTest::UnconfinedCompression;
        s.shape = SampleShape::Cylinder;
        s.rim_cells = 200;
      },
      "rig 'rig': rim_cells, growth, refinement: rim_cells 200");
  RigSpec ok;
  ok.indenter_contact = Support::Bonded;
  EXPECT_EQ(refusal(ok), "");
  EXPECT_EQ(rig_case(ok, "r.msh")["contact"]["bodies"][0]["mode"], "bonded");
  EXPECT_EQ(rig_case(RigSpec{}, "r.msh")["contact"]["bodies"][0]["mode"], "frictionless");
}

TEST(RigValidation, LoadStepsHaveAnUpperBound) {
  RigSpec s;
  s.steps_per_sample = 100000000;
  EXPECT_NE(refusal(s).find("steps_per_segment: must be in [1, 1,000,000]"), std::string::npos) << refusal(s);
  s.steps_per_sample = 100000;  // across each of 11 one-second segments: 1.1 million steps
  s.history = DisplacementHistory::ramp_hold(0.002, 1.0, 10.0);
  EXPECT_NE(refusal(s).find("make 1,100,000 load steps; the limit is 1,000,000"), std::string::npos)
      << refusal(s);
  s.steps_per_sample = 90000;
  EXPECT_EQ(refusal(s), "");
  EXPECT_EQ(rig_load_steps(s), 990000.0);
}

// The material and model as `tmlab run` would read them: refused at rig time, naming the key.
TEST(RigValidation, MaterialIsCheckedAsRunChecksIt) {
  RigSpec s;
  s.material = {{"E", -1.0}, {"nu", 0.45}, {"density", 1000.0}};
  EXPECT_NE(refusal(s).find("key 'material.E'"), std::string::npos) << refusal(s);
  s.material = {{"E", 3000.0}, {"nu", 0.45}, {"density", 1000.0}, {"colour", "red"}};
  EXPECT_NE(refusal(s).find("colour"), std::string::npos) << refusal(s);
  s.material = {{"law", "ogden"}, {"mu", {1000.0}}, {"alpha", {0.0}}, {"kappa", 1e5}, {"density", 1000.0}};
  s.model = "hyperelastic_tl";
  EXPECT_NE(refusal(s).find("key 'material.alpha'"), std::string::npos) << refusal(s);
  s.material["alpha"] = {2.0};
  EXPECT_EQ(refusal(s), "");
  s.model = "tensor_mass";  // St VK only: run would refuse the Ogden law
  EXPECT_NE(refusal(s).find("model: 'tensor_mass' runs St Venant-Kirchhoff only; material.law 'ogden'"),
            std::string::npos)
      << refusal(s);
  s.model = "reference";
  EXPECT_NE(refusal(s).find("model: must be 'tensor_mass', 'tl_oracle' or 'hyperelastic_tl'"),
            std::string::npos);
  s = RigSpec{};
  s.name = ".hidden";
  EXPECT_NE(refusal(s).find("name: "), std::string::npos);
}

// write_rig checks everything before it writes: a refused rig leaves no folder and no file; files
// already there are refused (named) unless overwrite; an input is never written over.
TEST_F(RigTest_, WriteRigRefusesBeforeWritingAndNeverReplacesSilently) {
  RigSpec s;
  s.name = "r";
  s.cells = 4;
  s.layers = 2;
  using Break = std::function<void(RigSpec&)>;
  const std::vector<Break> breaks = {
      [](RigSpec& r) { r.cells = r.layers = 400; }, [](RigSpec& r) { r.steps_per_sample = 2000000; },
      [](RigSpec& r) { r.cx = std::nan(""); }, [](RigSpec& r) { r.material["E"] = -1.0; }};
  for (const Break& broken : breaks) {
    RigSpec b = s;
    broken(b);
    EXPECT_THROW(write_rig(b, dir_ / "out"), Error);
    EXPECT_FALSE(fs::exists(dir_ / "out"));
  }
  const fs::path case_file = write_rig(s, dir_ / "out");
  EXPECT_EQ(case_file, dir_ / "out" / "r.json");
  const auto mtime = fs::last_write_time(case_file);
  try {
    write_rig(s, dir_ / "out");
    FAIL() << "an existing rig was replaced without overwrite";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((dir_ / "out" / "r.msh").string() + " already exists"),
              std::string::npos)
        << e.what();
  }
  // Only the case file there (a user's own r.json): refused too, naming it, and left alone.
  fs::remove(dir_ / "out" / "r.msh");
  { std::ofstream(dir_ / "out" / "r.json") << "mine"; }
  EXPECT_THROW(write_rig(s, dir_ / "out"), Error);
  EXPECT_FALSE(fs::exists(dir_ / "out" / "r.msh"));
  RigWriteOptions w;
  w.overwrite = true;
  EXPECT_NO_THROW(write_rig(s, dir_ / "out", w));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "r.msh"));
  EXPECT_GE(fs::last_write_time(case_file), mtime);
  // An input is never written over, even with overwrite.
  w.inputs = {dir_ / "out" / "r.json"};
  try {
    write_rig(s, dir_ / "out", w);
    FAIL() << "an input was written over";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is the input"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tmlab::rigs
