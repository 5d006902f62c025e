// `tmlab bench --quick` (issue 16): a complete result (summary.json, bench.json, bench.md) whose
// bench.json has the documented schema: the limits, and records with every field (the contact
// ladder's step records with the sphere in contact). Timings are never
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
  // --no-plots: the results line does not promise PNGs.
  EXPECT_NE(r.output.find("no plots: --no-plots"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("*.png"), std::string::npos) << r.output;
  const nlohmann::json b = nlohmann::json::parse(std::ifstream(out / "bench.json"));
  for (const char* k : {"peak_gflops_1t", "peak_gflops_2t", "triad_gbs_1t", "triad_gbs_2t"}) {
    ASSERT_TRUE(b.at("limits").contains(k)) << k;
    EXPECT_GT(b["limits"][k].get<double>(), 0.0) << k;
  }
  std::set<std::string> kernels, histories, laws, steps;
  int implicit_contact = 0;
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
      if (rec.contains("contact")) {
        // The contact ladder: the sphere is in contact during the measured steps.
        for (const char* k : {"dt", "active_nodes", "linear"})
          ASSERT_TRUE(rec.contains(k)) << k << " in " << rec.dump();
        EXPECT_GT(rec["dt"].get<double>(), 0.0);
        if (rec["contact"] == "none") {  // the same explicit step without the body
          EXPECT_EQ(rec["step"], "explicit") << rec.dump();
          continue;
        }
        EXPECT_EQ(rec["contact"], "sphere");
        EXPECT_GT(rec["active_nodes"].get<int>(), 0) << rec.dump();
        if (rec["step"] == "explicit_contact") {
          EXPECT_GT(rec["dt_critical"].get<double>(), 0.0);
        }
        if (rec["step"] == "implicit_contact") {
          ++implicit_contact;
          EXPECT_TRUE(rec["linear"] == "ldlt" || rec["linear"] == "cholmod") << rec.dump();
        }
      }
    }
  }
  EXPECT_EQ(implicit_contact, 2);  // ldlt and cholmod
  EXPECT_EQ(kernels, (std::set<std::string>{"baseline", "fast", "tensor_mass"}));
  EXPECT_EQ(histories, (std::set<std::string>{"none", "xu2011", "objective"}));
  EXPECT_EQ(laws, (std::set<std::string>{"stvk", "neo_hookean"}));
  EXPECT_EQ(steps, (std::set<std::string>{"explicit", "implicit", "static_newton", "explicit_contact",
                                          "implicit_contact"}));
  ASSERT_TRUE(b.contains("targets"));
  bool contact_target = false;
  for (const auto& t : b["targets"])
    if (t["name"].get<std::string>().find("with contact (explicit") != std::string::npos) {
      contact_target = true;
      EXPECT_GT(t["value"].get<double>(), 0.0) << t.dump();  // a number of tets, never asserted against 40k
    }
  EXPECT_TRUE(contact_target);
  fs::remove_all(dir);
}

TEST(CliBench, MeshesSelectsTheMeasuredMeshes) {
  const fs::path dir = fs::temp_directory_path() / ("tmlab_cli_bench_sel_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const Result r = run("bench --quick --no-plots --meshes cube_2k --results '" + dir.string() + "'");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json b = nlohmann::json::parse(std::ifstream(dir / "bench" / "bench.json"));
  ASSERT_FALSE(b.at("records").empty());
  for (const auto& rec : b["records"]) EXPECT_EQ(rec["mesh"], "cube_2k") << rec.dump();
  EXPECT_EQ(b["options"]["meshes"], nlohmann::json::array({"cube_2k"}));
  fs::remove_all(dir);
}

TEST(CliBench, UsageErrors) {
  EXPECT_EQ(run("bench --threads 0").status, 2);
  EXPECT_EQ(run("bench --quick --large").status, 2);
  EXPECT_EQ(run("bench extra").status, 2);
  EXPECT_EQ(run("bench --meshes cube_9k").status, 2);
  EXPECT_EQ(run("bench --meshes cube_2m").status, 2);  // needs --large
  EXPECT_EQ(run("bench --quick --meshes cube_24k").status, 2);
}

}  // namespace
