// The bench report on a hand-made bench document: the targets are the ratios of the right records
// (compute floor, fast / baseline, overheads, thread speed-up), missing records give "not
// measured", the largest mesh with a 1 ms contact step is interpolated (or extrapolated) from the
// contact ladder, and the Markdown has one row per kernel variant. The suite itself runs in
// test_cli_bench (tmlab bench --quick, schema only: timings are never asserted).
#include "bench/bench_report.hpp"
#include "bench/machine_limits.hpp"

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
       rec("tensor_mass", "xu2011", "cube_24k", 24576, 1, 82.0), rec("fast", "none", "cube_2k", 2352, 1, 8.0),
       rec("fast", "objective", "cube_2k", 2352, 1, 9.0), rec("fast", "none", "cube_240k", 235824, 1, 12.0),
       rec("fast", "none", "cube_240k", 235824, 2, 6.5)});
  b["records"].push_back({{"kind", "step"},
                          {"step", "explicit"},
                          {"kernel", "tensor_mass"},
                          {"history", "xu2011"},
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
  EXPECT_NEAR(by_name(t, "viscoelastic overhead, tensor_mass xu2011").at("value").get<double>(), 2.5, 1e-12);
  EXPECT_NEAR(by_name(t, "viscoelastic overhead, fast objective in cache").at("value").get<double>(), 12.5,
              1e-12);
  EXPECT_TRUE(by_name(t, "viscoelastic overhead, fast objective (cube_2m)").at("value").is_null());
  EXPECT_NEAR(by_name(t, "2 threads").at("value").get<double>(), 12.0 / 6.5, 1e-12);
  EXPECT_TRUE(by_name(t, "2 threads").at("met").get<bool>());
  EXPECT_DOUBLE_EQ(by_name(t, "liver explicit").at("value").get<double>(), 540.0);
  EXPECT_NEAR(by_name(t, "largest mesh").at("value").get<double>(), 1000.0 / (540.0 / 2704.0), 1e-9);
  EXPECT_DOUBLE_EQ(by_name(t, "cost linear").at("value").get<double>(), 1.5);
}

json contact(const std::string& step, const std::string& linear, long tets, int threads, double us) {
  return {{"kind", "step"},
          {"step", step},
          {"linear", linear},
          {"kernel", "fast"},
          {"history", "objective"},
          {"law", "stvk"},
          {"mesh", "contact_" + std::to_string(tets)},
          {"tets", tets},
          {"threads", threads},
          {"us_per_step", us},
          {"energy_bookkeeping", false},
          {"contact", "sphere"},
          {"dt", step == "explicit_contact" ? 5e-5 : 1e-3},
          {"active_nodes", 9}};
}

json contact_doc() {
  json b = doc();
  for (const json& r : {contact("explicit_contact", "none", 10368, 2, 400.0),
                        contact("explicit_contact", "none", 48000, 2, 1400.0),
                        contact("explicit_contact", "none", 24576, 2, 800.0),  // out of order on purpose
                        contact("explicit_contact", "none", 10368, 1, 500.0),
                        contact("explicit_contact", "none", 24576, 1, 900.0),
                        contact("implicit_contact", "ldlt", 2352, 1, 30000.0),
                        contact("implicit_contact", "cholmod", 2352, 1, 36000.0),
                        contact("implicit_contact", "ldlt", 10368, 1, 400000.0),
                        contact("implicit_contact", "cholmod", 10368, 1, 200000.0)})
    b["records"].push_back(r);
  return b;
}

TEST(BenchReport, LargestMeshWithAOneMillisecondContactStepIsInterpolatedInTets) {
  const json t = bench_targets(contact_doc());
  // 2 threads: 1000 us lies between 24576 tets (800 us) and 48000 tets (1400 us).
  const json& two =
      by_name(t, "largest mesh with a 1 ms viscoelastic step with contact (explicit, fast objective, 2");
  EXPECT_NEAR(two.at("value").get<double>(), 24576.0 + 200.0 * (48000.0 - 24576.0) / 600.0, 1e-9);
  EXPECT_FALSE(two.at("met").get<bool>());
  // 1 thread: every mesh is below 1 ms: extrapolated with the largest one's per-tet cost.
  const json& one =
      by_name(t, "largest mesh with a 1 ms viscoelastic step with contact (explicit, fast objective, 1");
  EXPECT_NEAR(one.at("value").get<double>(), 24576.0 * 1000.0 / 900.0, 1e-9);
  EXPECT_NE(one.at("how").get<std::string>().find("extrapolated"), std::string::npos);
  // Implicit: the cheapest on the smallest mesh, and CHOLMOD / LDL^T on the largest with both.
  EXPECT_DOUBLE_EQ(by_name(t, "implicit step with contact, dt 1 ms").at("value").get<double>(), 30000.0);
  EXPECT_DOUBLE_EQ(by_name(t, "implicit step with contact, CHOLMOD").at("value").get<double>(), 0.5);
  // Without contact records the targets are "not measured".
  EXPECT_TRUE(by_name(bench_targets(doc()), "largest mesh with a 1 ms viscoelastic step with contact")
                  .at("value")
                  .is_null());
  // The contact records have their own table, not rows of the plain step table.
  const std::string md = bench_markdown(contact_doc());
  EXPECT_NE(md.find("| explicit_contact | fast | objective | none | 2 | - | 400 | 800 | 1.4e+03 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| implicit_contact | fast | objective | cholmod | 1 | 3.6e+04 | 2e+05 | - | - |"),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("| explicit_contact | fast | objective | 2 | off |"), std::string::npos) << md;
}

TEST(BenchReport, MarkdownHasOneRowPerVariant) {
  const std::string md = bench_markdown(doc());
  EXPECT_NE(md.find("| fast | none | stvk | 2 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| explicit | tensor_mass | xu2011 | 1 | on | - | - | - |"), std::string::npos) << md;
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
