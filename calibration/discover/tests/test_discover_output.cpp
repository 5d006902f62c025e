// What a discovery and its benchmark write (calibration/discover/discover_output.hpp): the page
// (escaped text, figures only when there are plots), the confusion matrix text and CSV (only the
// columns with a count), the options fingerprint, and the benchmark's set filter (benchmark.hpp).
#include "calibration/discover/discover_output.hpp"

#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace {

namespace discover = tmlab::discover;
using nlohmann::json;

json model_block(const std::string& model) {
  return {{"model", model},
          {"rms_N", 0.5},
          {"rms_percent_of_peak", 1.25},
          {"max_abs_N", 1.5},
          {"bic", -100.0},
          {"free_parameters", 3},
          {"parameters", json::array({{{"name", "young"},
                                       {"value", 1234.5},
                                       {"unit", "Pa"},
                                       {"fixed", false},
                                       {"standard_error", 12.0},
                                       {"interval95", {1200.0, nullptr}}}})},
          {"residual",
           {{"structured", false},
            {"where", "nowhere"},
            {"diagnostics", json::array({{{"name", "runs"},
                                          {"statistic", 1.0},
                                          {"p_value", 0.5},
                                          {"threshold", 0.01},
                                          {"passed", true},
                                          {"decisive", false},
                                          {"note", ""}}})},
            {"by_phase", json::array()},
            {"by_cycle", json::array()},
            {"by_test", json::array()},
            {"by_strain", json::array()}}}};
}

json minimal_report() {
  return {{"dataset", "<script>alert(1)</script>"},
          {"baseline", model_block("stvk+prony:2")},
          {"final", model_block("stvk+prony:2 & more")},
          {"selected_effects", json::array({"contact_offset"})},
          {"removed_effects", json::array()},
          {"unexplained_structure", false},
          {"unexplained_signature", ""},
          {"stop_reason", "no gain"},
          {"selection_rule", "BIC"},
          {"held_out", "last cycle"},
          {"test_consistency_control", {{"applicable", false}}},
          {"notes", json::array()},
          {"forward_model", {{"name", "homogeneous_platen"}, {"exact_where", "everywhere"}}},
          {"peak_force_N", 10.0},
          {"samples", 150},
          {"tests", 1},
          {"decimation_stride", 1},
          {"steps", json::array()},
          {"library", json::array()},
          {"not_applicable", json::array()}};
}

TEST(DiscoverOutput, ReportHtmlEscapesAndShowsFiguresOnlyWithPlots) {
  const std::string with = discover::report_html(minimal_report(), true);
  EXPECT_EQ(with.find("<script>"), std::string::npos);
  EXPECT_NE(with.find("&lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(with.find("stvk+prony:2 &amp; more"), std::string::npos);
  EXPECT_NE(with.find("<code>contact_offset</code>"), std::string::npos);
  EXPECT_NE(with.find("discover_fits.png"), std::string::npos);
  EXPECT_NE(with.find("[1200, -]"), std::string::npos);  // a null interval end
  const std::string without = discover::report_html(minimal_report(), false);
  EXPECT_EQ(without.find(".png"), std::string::npos);
  EXPECT_EQ(without.find("FE rig"), std::string::npos);  // no fe_rig block
}

class DiscoverOutputFiles : public tmlab::testing::TempDirTest {};

TEST_F(DiscoverOutputFiles, ConfusionMatrixKeepsColumnsWithACount) {
  discover::BenchmarkResult b;
  b.rows = {"contact_offset", "noise_only"};
  b.columns = {"contact_offset", "force_drift", "nothing"};
  b.confusion = {{2, 0, 1}, {0, 0, 3}};
  const std::string text = discover::benchmark_text(b);
  EXPECT_EQ(text.substr(text.find('\n') + 1),
            "truth,contact_offset,nothing\ncontact_offset,2,1\nnoise_only,0,3\n");
  discover::write_confusion_csv(dir_ / "m.csv", b);
  std::ifstream in(dir_ / "m.csv");
  std::stringstream s;
  s << in.rdbuf();
  EXPECT_EQ(s.str(), "truth,contact_offset,nothing\ncontact_offset,2,1\nnoise_only,0,3\n");
  std::ostringstream os;
  discover::print_benchmark_report(os, b);
  EXPECT_EQ(os.str().substr(0, text.size()), text);
  EXPECT_NE(os.str().find("noise-only sets:"), std::string::npos);
}

TEST(DiscoverOutput, FingerprintFollowsEveryResultOption) {
  const discover::Options o;
  const json a = discover::options_fingerprint(o);
  discover::Options p = o;
  p.seed = o.seed + 1;
  EXPECT_NE(discover::options_fingerprint(p), a);
  p = o;
  p.effects = {"contact_offset"};
  EXPECT_NE(discover::options_fingerprint(p), a);
  p = o;
  p.test_control = !o.test_control;
  EXPECT_NE(discover::options_fingerprint(p), a);
  p = o;
  p.baseline_prony = o.baseline_prony + 1;
  EXPECT_EQ(discover::options_fingerprint(p)["baseline"],
            "stvk+prony:" + std::to_string(o.baseline_prony + 1));
}

TEST(DiscoverOutput, SelectSetsByRigAndTruth) {
  std::vector<discover::SyntheticSet> sets(3);
  sets[0].truth = "noise_only";
  sets[0].rig = discover::BenchmarkRig::unconfined;
  sets[1].truth = "contact_offset";
  sets[1].rig = discover::BenchmarkRig::unconfined;
  sets[2].truth = "noise_only";
  sets[2].rig = discover::BenchmarkRig::sphere;
  EXPECT_EQ(discover::select_sets(sets, "", "").size(), 3u);
  const auto noise = discover::select_sets(sets, "", "noise_only,force_drift");
  ASSERT_EQ(noise.size(), 2u);
  EXPECT_EQ(noise[1].rig, discover::BenchmarkRig::sphere);
  const auto sphere = discover::select_sets(sets, discover::to_string(discover::BenchmarkRig::sphere), "");
  ASSERT_EQ(sphere.size(), 1u);
  EXPECT_TRUE(discover::select_sets(sets, "", "noise").empty());  // whole names only
  EXPECT_TRUE(discover::select_sets(sets, "tension_rig", "").empty());
}

}  // namespace

namespace {

TEST(DiscoverOutput, SummaryOfTheBenchmark) {
  discover::BenchmarkResult b;
  b.diagonal_fraction = 0.75;
  EXPECT_EQ(discover::summary_json(b)["diagonal_fraction"], 0.75);
}

}  // namespace
