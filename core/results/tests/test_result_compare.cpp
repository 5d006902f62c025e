// compare_results: relative differences of displacements, reactions and energy between two result
// directories written through the recorder, and the errors for results that cannot be compared.
#include "core/results/result_compare.hpp"

#include "core/base/error.hpp"
#include "core/results/recorder.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace tmlab {
namespace {

namespace fs = std::filesystem;

/// What a fake run records per step: the displacement of its two nodes, one reaction per
/// condition, the elastic energy.
struct FakeStep {
  std::vector<double> u;                         // 6 values
  std::vector<std::array<double, 3>> reactions;  // one per condition
  double energy = 0.0;
};
/// Per step, one ContactValues per rigid body (empty: a run without contact).
using FakeContact = std::vector<std::vector<series_names::ContactValues>>;

class ResultCompareTest : public tmlab::testing::TempDirTest {
 protected:
  const std::filesystem::path& root_ = dir_;  // where each test puts its files

  /// A complete result directory (summary.json, displacement.h5, timeseries.h5) of the steps.
  fs::path write_run(const std::string& name, const std::vector<std::string>& conditions,
                     const std::vector<FakeStep>& steps, const FakeContact& contact = {}) {
    const fs::path dir = root_ / name;
    fs::create_directories(dir);
    Recorder rec(conditions, {}, {});
    rec.open_displacements(dir / "displacement.h5");
    for (std::size_t k = 0; k < steps.size(); ++k) {
      Recorder::StepValues v;
      v.time = static_cast<double>(k);
      v.elastic_energy = steps[k].energy;
      v.reactions = steps[k].reactions;
      if (!contact.empty()) v.contact = contact[k];
      rec.record(v);
      rec.add_field_frame(v.time, steps[k].u);
    }
    rec.close_displacements("");
    rec.write_timeseries(dir / "timeseries.h5", {{"case", name}});
    std::ofstream(dir / "summary.json") << "{}";
    return dir;
  }
};

std::vector<FakeStep> base_steps() {
  return {{{0, 0, 0, 0, 0, 0}, {{0, 0, 0}, {0, 0, 0}}, 0.0},
          {{0, 0, 3, 0, 0, 4}, {{0, 0, 10}, {0, 0, -10}}, 2.0},
          {{0, 0, 6, 0, 0, 8}, {{0, 0, 20}, {0, 0, -20}}, 8.0}};
}

TEST_F(ResultCompareTest, IdenticalRunsDifferByNothing) {
  const auto a = write_run("a", {"base", "top"}, base_steps());
  const auto b = write_run("b", {"base", "top"}, base_steps());
  ComparisonSeries s;
  const nlohmann::json c = compare_results(a, b, &s);
  EXPECT_EQ(c["rel_diff_displacement"].get<double>(), 0.0);
  EXPECT_EQ(c["rel_diff_reaction"].get<double>(), 0.0);
  EXPECT_EQ(c["rel_diff_energy"].get<double>(), 0.0);
  EXPECT_EQ(c["frames"].get<int>(), 3);
  EXPECT_EQ(c["nodes"].get<int>(), 2);
  EXPECT_EQ(c["steps"].get<int>(), 3);
  EXPECT_EQ(s.time, (std::vector<double>{0.0, 1.0, 2.0}));
  EXPECT_EQ(s.rel_displacement.size(), 3u);
}

TEST_F(ResultCompareTest, DifferencesAreRelativeToRunB) {
  auto steps_a = base_steps();
  steps_a[1].u = {0, 0, 3, 0, 0, 4.5};    // |u_b| = 5, |u_a - u_b| = 0.5
  steps_a[0].u = {0, 0, 0.25, 0, 0, 0};   // |u_b| = 0: the absolute difference
  steps_a[2].reactions[1] = {0, 0, -18};  // 2 N off on a scale of the largest |R_b| = 20 N
  steps_a[2].energy = 9.0;                // 1 J off on max |W_b| = 8 J
  const auto a = write_run("a", {"base", "top"}, steps_a);
  const auto b = write_run("b", {"base", "top"}, base_steps());
  ComparisonSeries s;
  const nlohmann::json c = compare_results(a, b, &s);
  EXPECT_DOUBLE_EQ(s.rel_displacement[0], 0.25);
  EXPECT_DOUBLE_EQ(s.rel_displacement[1], 0.1);
  EXPECT_DOUBLE_EQ(s.rel_displacement[2], 0.0);
  EXPECT_DOUBLE_EQ(c["rel_diff_displacement"].get<double>(), 0.25);
  EXPECT_EQ(s.rel_reaction, (std::vector<double>{0.0, 0.0, 0.1}));
  EXPECT_DOUBLE_EQ(c["rel_diff_reaction"].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(c["reactions"]["top"]["rel_diff"].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(c["reactions"]["base"]["rel_diff"].get<double>(), 0.0);
  EXPECT_EQ(c["reactions"]["top"]["final_a_N"], nlohmann::json({0.0, 0.0, -18.0}));
  EXPECT_EQ(c["reactions"]["top"]["final_b_N"], nlohmann::json({0.0, 0.0, -20.0}));
  EXPECT_DOUBLE_EQ(c["rel_diff_energy"].get<double>(), 0.125);
  EXPECT_DOUBLE_EQ(s.rel_energy[2], 0.125);
}

TEST_F(ResultCompareTest, ARunWithoutSummaryIsNotComplete) {
  const auto a = write_run("a", {"base"}, {{{0, 0, 0, 0, 0, 0}, {{0, 0, 0}}, 0.0}});
  const auto b = write_run("b", {"base"}, {{{0, 0, 0, 0, 0, 0}, {{0, 0, 0}}, 0.0}});
  fs::remove(a / "summary.json");
  try {
    compare_results(a, b);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a complete result"), std::string::npos) << e.what();
  }
}

TEST_F(ResultCompareTest, DifferentMeshesStepsOrConditionsAreNotComparable) {
  const FakeStep one{{0, 0, 0, 0, 0, 0}, {{0, 0, 0}}, 0.0};
  const auto b = write_run("b", {"base"}, {one, one});
  // Three nodes instead of two.
  const FakeStep three{{0, 0, 0, 0, 0, 0, 0, 0, 0}, {{0, 0, 0}}, 0.0};
  const auto a_mesh = write_run("a_mesh", {"base"}, {three, three});
  EXPECT_THROW(compare_results(a_mesh, b), Error);
  // Same frames, written with a different number of steps in timeseries.h5.
  const auto a_steps = write_run("a_steps", {"base"}, {one, one});
  {
    SeriesTable t;
    t.add("time", "s", 0.0);
    write_series_file(a_steps / "timeseries.h5", t);
  }
  EXPECT_THROW(compare_results(a_steps, b), Error);
  // A condition of b that a does not have.
  const auto a_cond = write_run("a_cond", {"other"}, {one, one});
  try {
    compare_results(a_cond, b);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/series/reaction_base_x"), std::string::npos) << e.what();
  }
}

/// For base_steps(): a sphere pressing with force (0, 0, 5 k) N, area k m^2 and 3 k active nodes at step k.
FakeContact contact_steps() {
  FakeContact steps;
  for (std::size_t k = 0; k < 3; ++k) {
    series_names::ContactValues c;
    c.body = "indenter";
    c.force = {0.0, 0.0, 5.0 * k};
    c.area = 1.0 * k;
    c.active_nodes = 3.0 * k;
    steps.push_back({c});
  }
  return steps;
}

TEST_F(ResultCompareTest, ContactForceAreaAndActiveNodesAreCompared) {
  const auto b = write_run("b", {"bottom", "top"}, base_steps(), contact_steps());
  const auto same = compare_results(write_run("a0", {"bottom", "top"}, base_steps(), contact_steps()), b);
  EXPECT_EQ(same.at("rel_diff_contact_force").get<double>(), 0.0);
  EXPECT_EQ(same.at("rel_diff_contact_area").get<double>(), 0.0);
  EXPECT_EQ(same.at("max_diff_active_nodes").get<double>(), 0.0);

  FakeContact steps = contact_steps();
  steps[1][0].force = {0.3, 0.0, 5.4};  // |dF| = 0.5 against max |F_b| = 10
  steps[2][0].area = 2.5;               // |dA| = 0.5 against max A_b = 2
  steps[2][0].active_nodes = 7.0;       // 1 node more
  ComparisonSeries cs;
  const auto cmp = compare_results(write_run("a", {"bottom", "top"}, base_steps(), steps), b, &cs);
  EXPECT_NEAR(cmp.at("rel_diff_contact_force").get<double>(), 0.05, 1e-15);
  EXPECT_NEAR(cmp.at("rel_diff_contact_area").get<double>(), 0.25, 1e-15);
  EXPECT_EQ(cmp.at("max_diff_active_nodes").get<double>(), 1.0);
  EXPECT_NEAR(cmp.at("contact").at("indenter").at("final_area_a_m2").get<double>(), 2.5, 0.0);
  ASSERT_EQ(cs.rel_contact_force.size(), 3u);
  EXPECT_NEAR(cs.rel_contact_force[1], 0.05, 1e-15);
  EXPECT_EQ(cs.rel_contact_area[1], 0.0);

  // Without contact in either run there are no contact keys; in one run only, an error.
  EXPECT_FALSE(compare_results(write_run("n1", {"bottom", "top"}, base_steps()),
                               write_run("n2", {"bottom", "top"}, base_steps()))
                   .contains("rel_diff_contact_force"));
  EXPECT_THROW(compare_results(write_run("n3", {"bottom", "top"}, base_steps()), b), Error);
  EXPECT_THROW(compare_results(b, write_run("n4", {"bottom", "top"}, base_steps())), Error);
}

}  // namespace
}  // namespace tmlab
