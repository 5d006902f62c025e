// The recorder: series names and order, the smallest volume ratio over the steps, the displacement
// frames, timeseries.h5, the standard plots and the summary blocks both runners write.
#include "core/results/recorder.hpp"

#include "core/base/error.hpp"
#include "core/results/series_names.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace tmlab {
namespace {

namespace fs = std::filesystem;

class RecorderTest : public tmlab::testing::TempDirTest {
 protected:
  const std::filesystem::path& root_ = dir_;  // where each test puts its files
};

/// Two steps of a run with one condition ("base") and one probe ("tip" at node 7).
Recorder two_steps(bool with_extras) {
  Recorder rec({"base"}, {"tip"}, {7});
  for (int k = 0; k < 2; ++k) {
    Recorder::StepValues v;
    v.time = 0.5 * k;
    v.max_displacement = 0.1 * k;
    v.elastic_energy = 2.0 * k;
    if (with_extras) v.extras = {{series_names::kExternalWork, "J", 3.0 * k}};
    v.kinetic_energy = 0.25 * k;
    v.min_volume_ratio = k == 0 ? 1.0 : 0.75;
    v.newton_iterations = 4 * k;
    v.reactions = {{3.0 * k, 0.0, 4.0 * k}};
    v.probes = {{1.0 * k, 2.0 * k, 2.0 * k}};
    rec.record(v);
  }
  return rec;
}

std::vector<std::string> names(const SeriesTable& t) {
  std::vector<std::string> out;
  for (const auto& s : t.series()) out.push_back(s.name);
  return out;
}

TEST_F(RecorderTest, SeriesComeInTheProtocolsOrderWithExtrasAfterTheElasticEnergy) {
  const Recorder rec = two_steps(true);
  EXPECT_EQ(
      names(rec.table()),
      (std::vector<std::string>{"time", "max_displacement", "elastic_energy", "external_work",
                                "kinetic_energy", "min_volume_ratio", "newton_iterations", "reaction_base_x",
                                "reaction_base_y", "reaction_base_z", "reaction_base_norm", "probe_tip_x",
                                "probe_tip_y", "probe_tip_z", "probe_tip_norm"}));
  EXPECT_EQ(rec.table().series()[0].values, (std::vector<double>{0.0, 0.5}));
  EXPECT_EQ(rec.table().series()[0].unit, "s");
  EXPECT_DOUBLE_EQ(rec.table().last("reaction_base_norm"), 5.0);
  EXPECT_DOUBLE_EQ(rec.table().last("probe_tip_norm"), 3.0);
  EXPECT_DOUBLE_EQ(rec.table().last("newton_iterations"), 4.0);
  EXPECT_DOUBLE_EQ(rec.min_volume_ratio(), 0.75);
}

TEST_F(RecorderTest, AStepWithoutAReactionPerConditionOrAProbeWithoutANodeIsAnError) {
  Recorder rec({"base", "top"}, {}, {});
  Recorder::StepValues v;
  v.reactions = {{0.0, 0.0, 0.0}};
  EXPECT_THROW(rec.record(v), std::out_of_range);
  EXPECT_THROW(Recorder({}, {"tip"}, {}), Error);
}

TEST_F(RecorderTest, SummaryBlocksHoldTheLastValuesAndTheSmallestVolumeRatio) {
  Recorder rec = two_steps(false);
  rec.add_field_frame(0.0, {0.0, 0.0, 0.0});  // no displacement file open: only counted
  const nlohmann::json s = rec.summary_blocks();
  EXPECT_DOUBLE_EQ(s["final_time"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(s["max_displacement_m"].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(s["elastic_energy_J"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(s["min_volume_ratio"].get<double>(), 0.75);
  EXPECT_EQ(s["field_frames"].get<int>(), 1);
  EXPECT_EQ(s["final_reactions_N"]["base"], nlohmann::json({3.0, 0.0, 4.0}));
  EXPECT_EQ(s["probes"]["tip"]["node"].get<int>(), 7);
  EXPECT_EQ(s["probes"]["tip"]["displacement_m"], nlohmann::json({1.0, 2.0, 2.0}));
}

TEST_F(RecorderTest, TimeseriesFileHoldsEverySeriesWithItsUnitAndTheRootAttributes) {
  const Recorder rec = two_steps(true);
  const fs::path path = root_ / "timeseries.h5";
  rec.write_timeseries(path, {{"case", "cube"}, {"model", "reference"}});
  const H5File h5 = H5File::open_read(path.string());
  EXPECT_EQ(h5.list("/series").size(), rec.table().series().size());
  for (const auto& s : rec.table().series()) {
    EXPECT_EQ(h5.read_double("/series/" + s.name), s.values) << s.name;
    EXPECT_EQ(h5.string_attribute("/series/" + s.name, "unit"), s.unit) << s.name;
  }
  EXPECT_EQ(h5.string_attribute("/", "case"), "cube");
  EXPECT_EQ(h5.string_attribute("/", "model"), "reference");
}

TEST_F(RecorderTest, SeriesWithoutAUnitGetNoUnitAttribute) {
  SeriesTable t;
  t.add("rel_diff", "", 1e-3);
  const fs::path path = root_ / "compare.h5";
  write_series_file(path, t);
  const H5File h5 = H5File::open_read(path.string());
  EXPECT_EQ(h5.read_double("/series/rel_diff"), std::vector<double>{1e-3});
  EXPECT_FALSE(h5.has_attribute("/series/rel_diff", "unit"));
}

TEST_F(RecorderTest, DisplacementFramesAreRowsWithTheirTimesAndLayout) {
  Recorder rec({}, {}, {});
  const fs::path path = root_ / "displacement.h5";
  rec.open_displacements(path);
  rec.add_field_frame(0.0, {0.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  rec.add_field_frame(1.0, {1.0, 2.0, 3.0, 4.0, 5.0, 6.0});
  rec.close_displacements("vertex values");
  EXPECT_EQ(rec.field_frames(), 2);
  const H5File h5 = H5File::open_read(path.string());
  H5File::Dims dims;
  const auto u = h5.read_double("/u", &dims);
  EXPECT_EQ(dims, (H5File::Dims{2, 6}));
  EXPECT_EQ(u[6 + 5], 6.0);
  EXPECT_EQ(h5.read_double("/time"), (std::vector<double>{0.0, 1.0}));
  EXPECT_EQ(h5.string_attribute("/u", "unit"), "m");
  EXPECT_EQ(h5.string_attribute("/u", "layout"),
            "rows: field frames; columns: 3*node + component (tmlab node order; vertex values)");
}

TEST_F(RecorderTest, PlotsNameOnlySeriesTheTableHolds) {
  const nlohmann::json plots = two_steps(true).plots("cube");
  ASSERT_EQ(plots.size(), 4u);
  EXPECT_EQ(plots[0]["file"], "displacement.png");
  EXPECT_EQ(plots[0]["y"], nlohmann::json::array({"max_displacement"}));
  EXPECT_EQ(plots[0]["title"], "cube: largest displacement");
  EXPECT_EQ(plots[1]["y"], nlohmann::json::array({"reaction_base_norm"}));
  // No spring/branch/dissipated series in this run: the energy plot leaves them out.
  EXPECT_EQ(plots[2]["y"], nlohmann::json::array({"elastic_energy", "kinetic_energy", "external_work"}));
  EXPECT_EQ(plots[3]["y"], nlohmann::json::array({"probe_tip_norm"}));
  const auto held = names(two_steps(true).table());
  for (const auto& p : plots) {
    EXPECT_EQ(p["x"], "time");
    for (const auto& y : p["y"])
      EXPECT_NE(std::find(held.begin(), held.end(), y.get<std::string>()), held.end()) << y;
  }
  const nlohmann::json bare = Recorder({}, {}, {}).plots("x");
  ASSERT_EQ(bare.size(), 2u);  // displacement and energy only
  EXPECT_EQ(bare[1]["file"], "energy.png");
}

}  // namespace
}  // namespace tmlab
