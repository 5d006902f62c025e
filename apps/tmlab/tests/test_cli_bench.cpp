// `tmlab bench --quick` (issue 16): a complete result (summary.json, bench.json, bench.md) whose
// bench.json has the documented schema: the limits, and records with every field. Timings are never
// asserted (the machine is shared); only that they are positive and finite.
#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

namespace {

namespace fs = std::filesystem;
using tmlab::cli_test::Result;
using tmlab::cli_test::run;

TEST(CliBench, QuickWritesTheDocumentedSchema) {
  const fs::path dir = fs::temp_directory_path() / ("tmlab_cli_bench_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const Result r = run("bench --quick --no-plots --results '" + dir.string() + "'");
  ASSERT_EQ(r.status, 0) << r.output;
  const fs::path out = dir / "bench";
  ASSERT_TRUE(fs::exists(out / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "manifest.json"));
  EXPECT_TRUE(fs::exists(out / "bench.md"));
  const nlohmann::json b = nlohmann::json::parse(std::ifstream(out / "bench.json"));
  for (const char* k : {"peak_gflops_1t", "peak_gflops_2t", "triad_gbs_1t", "triad_gbs_2t"}) {
    ASSERT_TRUE(b.at("limits").contains(k)) << k;
    EXPECT_GT(b["limits"][k].get<double>(), 0.0) << k;
  }
  std::set<std::string> kernels, histories, laws, steps;
  for (const auto& rec : b.at("records")) {
    for (const char* k : {"kind", "kernel", "history", "law", "mesh", "tets", "threads"})
      ASSERT_TRUE(rec.contains(k)) << k << " in " << rec.dump();
    if (rec["kind"] == "force") {
      for (const char* k : {"ns_per_tet", "flops_per_tet", "bytes_per_tet", "memory_per_tet"}) {
        ASSERT_TRUE(rec.contains(k)) << k;
        const double v = rec[k].get<double>();
        EXPECT_TRUE(std::isfinite(v) && v > 0.0) << k << " " << rec.dump();
      }
      kernels.insert(rec["kernel"].get<std::string>());
      histories.insert(rec["history"].get<std::string>());
      laws.insert(rec["law"].get<std::string>());
    } else {
      ASSERT_EQ(rec["kind"], "step");
      ASSERT_TRUE(rec.contains("step") && rec.contains("us_per_step")) << rec.dump();
      EXPECT_GT(rec["us_per_step"].get<double>(), 0.0);
      steps.insert(rec["step"].get<std::string>());
    }
  }
  EXPECT_EQ(kernels, (std::set<std::string>{"baseline", "fast", "tensor_mass"}));
  EXPECT_EQ(histories, (std::set<std::string>{"none", "seed", "objective"}));
  EXPECT_EQ(laws, (std::set<std::string>{"stvk", "neo_hookean"}));
  EXPECT_EQ(steps, (std::set<std::string>{"explicit", "implicit", "static_newton"}));
  ASSERT_TRUE(b.contains("targets"));
  fs::remove_all(dir);
}

TEST(CliBench, UsageErrors) {
  EXPECT_EQ(run("bench --threads 0").status, 2);
  EXPECT_EQ(run("bench --quick --large").status, 2);
  EXPECT_EQ(run("bench extra").status, 2);
}

}  // namespace
