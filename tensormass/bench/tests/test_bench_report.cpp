// The bench report on a hand-made bench document: the targets are the ratios of the right records
// (compute floor, fast / baseline, overheads, thread speed-up), missing records give "not
// measured", and the Markdown has one row per kernel variant. The suite itself runs in
// test_cli_bench (tmlab bench --quick, schema only: timings are never asserted).
#include "tensormass/bench/bench_report.hpp"
#include "tensormass/bench/machine_limits.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm {
namespace {

using json = nlohmann::json;

json rec(const std::string& kernel, const std::string& history, const std::string& mesh, long tets,
         int threads, double ns) {
  return {{"kind", "force"},        {"kernel", kernel},       {"history", history},     {"law", "stvk"},
          {"mesh", mesh},           {"tets", tets},           {"threads", threads},     {"ns_per_tet", ns},
          {"flops_per_tet", 250.0}, {"bytes_per_tet", 116.0}, {"memory_per_tet", 200.0}};
}

json doc() {
  json b;
  b["limits"] = {
      {"peak_gflops_1t", 50.0}, {"peak_gflops_2t", 100.0}, {"triad_gbs_1t", 10.0}, {"triad_gbs_2t", 15.0}};
  b["meshes"] = json::array({{{"name", "cube_2k"}, {"tets", 2352}, {"nodes", 600}},
                             {{"name", "cube_24k"}, {"tets", 24576}, {"nodes", 4913}},
                             {{"name", "cube_240k"}, {"tets", 235824}, {"nodes", 42875}}});
  b["records"] = json::array(
      {rec("fast", "none", "cube_24k", 24576, 1, 10.0), rec("baseline", "none", "cube_24k", 24576, 1, 25.0),
       rec("tensor_mass", "none", "cube_24k", 24576, 1, 80.0),
       rec("tensor_mass", "seed", "cube_24k", 24576, 1, 82.0), rec("fast", "none", "cube_2k", 2352, 1, 8.0),
       rec("fast", "objective", "cube_2k", 2352, 1, 9.0), rec("fast", "none", "cube_240k", 235824, 1, 12.0),
       rec("fast", "none", "cube_240k", 235824, 2, 6.5)});
  b["records"].push_back({{"kind", "step"},
                          {"step", "explicit"},
                          {"kernel", "tensor_mass"},
                          {"history", "seed"},
                          {"law", "stvk"},
                          {"mesh", "liver"},
                          {"tets", 2704},
                          {"threads", 1},
                          {"us_per_step", 540.0},
                          {"energy_bookkeeping", true}});
  return b;
}

const json& by_name(const json& targets, const std::string& prefix) {
  for (const json& t : targets)
    if (t.at("name").get<std::string>().rfind(prefix, 0) == 0) return t;
  throw std::runtime_error("no target " + prefix);
}

TEST(BenchReport, TargetsAreTheRatiosOfTheRecords) {
  const json t = bench_targets(doc());
  EXPECT_DOUBLE_EQ(by_name(t, "fast kernel / compute floor").at("value").get<double>(),
                   10.0 / (250.0 / 50.0));
  EXPECT_DOUBLE_EQ(by_name(t, "fast / baseline").at("value").get<double>(), 0.4);
  EXPECT_FALSE(by_name(t, "fast / baseline").at("met").get<bool>());
  EXPECT_DOUBLE_EQ(by_name(t, "tensor_mass / baseline").at("value").get<double>(), 3.2);
  EXPECT_NEAR(by_name(t, "viscoelastic overhead, tensor_mass seed").at("value").get<double>(), 2.5, 1e-12);
  EXPECT_NEAR(by_name(t, "viscoelastic overhead, fast objective in cache").at("value").get<double>(), 12.5,
              1e-12);
  EXPECT_TRUE(by_name(t, "viscoelastic overhead, fast objective (cube_2m)").at("value").is_null());
  EXPECT_NEAR(by_name(t, "2 threads").at("value").get<double>(), 12.0 / 6.5, 1e-12);
  EXPECT_TRUE(by_name(t, "2 threads").at("met").get<bool>());
  EXPECT_DOUBLE_EQ(by_name(t, "liver explicit").at("value").get<double>(), 540.0);
  EXPECT_NEAR(by_name(t, "largest mesh").at("value").get<double>(), 1000.0 / (540.0 / 2704.0), 1e-9);
  EXPECT_DOUBLE_EQ(by_name(t, "cost linear").at("value").get<double>(), 1.5);
}

TEST(BenchReport, MarkdownHasOneRowPerVariant) {
  const std::string md = bench_markdown(doc());
  EXPECT_NE(md.find("| fast | none | stvk | 2 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| explicit | tensor_mass | seed | 1 | on | - | - | - |"), std::string::npos) << md;
  EXPECT_NE(md.find("not measured"), std::string::npos) << md;
}

TEST(BenchReport, MachineLimitsArePositive) {
  const MachineLimits m =
      measure_machine_limits(0.0, std::size_t(3) << 20);  // tiny: a smoke test, not a timing
  EXPECT_GT(m.peak_gflops_1t, 0.0);
  EXPECT_GT(m.peak_gflops_2t, 0.0);
  EXPECT_GT(m.triad_gbs_1t, 0.0);
  EXPECT_GT(m.triad_gbs_2t, 0.0);
}

}  // namespace
}  // namespace tmlab::tm
