// The checkpoint entries of a discovery and its benchmark (calibration/discover/discover_checkpoint.hpp):
// the fits of the loop (failed ones with their message) and the finished benchmark sets written to a
// checkpoint file and read back equal; a bad entry refused.
#include "calibration/discover/discover_checkpoint.hpp"

#include "core/base/error.hpp"
#include "core/results/checkpoint.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace {

namespace discover = tmlab::discover;
using tmlab::CheckpointData;

class DiscoverCheckpointTest : public tmlab::testing::TempDirTest {
 protected:
  CheckpointData through_file(const CheckpointData& d) const {
    const auto path = dir_ / "checkpoint.h5";
    tmlab::write_checkpoint(path, "discover", {{"k", 1}}, d);
    return tmlab::read_checkpoint(path, "discover", {{"k", 1}});
  }
};

TEST_F(DiscoverCheckpointTest, FitOutcomesRoundTrip) {
  std::vector<discover::FitOutcome> v(3);
  v[0].result.model_name = "homogeneous_platen";
  v[0].result.parameters = {{"young", "Pa", 1234.5, false, "log", 1.0 / 3.0, 1200.0, 1270.0, true}};
  v[0].result.prediction = {0.1, 0.2, std::numeric_limits<double>::infinity()};
  v[0].result.rms = 0.1 + 0.2;
  v[0].result.notes = {"a note"};
  v[1].failed = true;
  v[1].error = "no candidate start could be evaluated";
  v[2].result.model_name = "sphere";
  v[2].result.correlation = {{1.0, 0.5}, {0.5, 1.0}};
  CheckpointData d;
  discover::put_fit_outcomes(d, v);
  const std::vector<discover::FitOutcome> w = discover::get_fit_outcomes(through_file(d));
  ASSERT_EQ(w.size(), 3u);
  EXPECT_FALSE(w[0].failed);
  EXPECT_EQ(w[0].result.model_name, "homogeneous_platen");
  ASSERT_EQ(w[0].result.parameters.size(), 1u);
  EXPECT_EQ(w[0].result.parameters[0].standard_error, 1.0 / 3.0);
  EXPECT_EQ(w[0].result.prediction, v[0].result.prediction);
  EXPECT_EQ(w[0].result.rms, v[0].result.rms);
  EXPECT_EQ(w[0].result.notes, v[0].result.notes);
  EXPECT_TRUE(w[1].failed);
  EXPECT_EQ(w[1].error, v[1].error);
  EXPECT_EQ(w[2].result.correlation, v[2].result.correlation);
}

TEST_F(DiscoverCheckpointTest, BenchmarkEntriesRoundTrip) {
  std::vector<discover::BenchmarkEntry> v(2);
  v[0].name = "bench-contact_offset-1";
  v[0].truth = "contact_offset";
  v[0].rig = "unconfined_compression";
  v[0].kind = discover::Truth::library;
  v[0].found = {"contact_offset"};
  v[0].rms_before = 0.125;
  v[0].rms_after = 1.0 / 7.0;
  v[0].peak = 10.5;
  v[0].seconds = 3.25;
  v[0].correct = true;
  v[1].name = "bench-actuator_resonance-2";
  v[1].truth = "actuator_resonance";
  v[1].kind = discover::Truth::outside_library;
  v[1].unexplained = true;
  v[1].signature = "periodic residual";
  CheckpointData d;
  discover::put_benchmark_entries(d, v);
  const auto w = discover::get_benchmark_entries(through_file(d));
  ASSERT_EQ(w.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(w[i].name, v[i].name);
    EXPECT_EQ(w[i].truth, v[i].truth);
    EXPECT_EQ(w[i].rig, v[i].rig);
    EXPECT_EQ(w[i].kind, v[i].kind);
    EXPECT_EQ(w[i].found, v[i].found);
    EXPECT_EQ(w[i].unexplained, v[i].unexplained);
    EXPECT_EQ(w[i].signature, v[i].signature);
    EXPECT_EQ(w[i].correct, v[i].correct);
    EXPECT_EQ(w[i].rms_before, v[i].rms_before);
    EXPECT_EQ(w[i].rms_after, v[i].rms_after);
    EXPECT_EQ(w[i].peak, v[i].peak);
    EXPECT_EQ(w[i].seconds, v[i].seconds);
  }
  d.put_text("set.1.meta", R"({"name":"x","truth":"y","rig":"z","kind":7,"found":[],"unexplained":false,)"
                           R"("signature":"","correct":false})");
  EXPECT_THROW(discover::get_benchmark_entries(d), tmlab::Error);  // no Truth 7
}

}  // namespace
