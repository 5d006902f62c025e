// `tmlab discover` as a user meets it (issue 15): the phantom converted and studied end to end
// (report.json with the keys the issue names, index.html, the PNGs, discover.h5, the manifest,
// summary.json last, progress on standard error), and bad options refused.
#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace {

namespace fs = std::filesystem;

using tmlab::cli_test::Result;
using tmlab::testing::read_file;

const fs::path kPhantomA1 = tmlab::cli_test::phantom_a1();

class CliDiscover : public tmlab::cli_test::CliTest {
 protected:
  fs::path convert() const {
    const Result c = tmlab({"data", "convert", kPhantomA1.string(), "--out", (dir_ / "data").string()});
    EXPECT_EQ(c.status, 0) << c.output;
    return dir_ / "data" / "EF10_0T_A1.csv";
  }
};

TEST_F(CliDiscover, StudiesThePhantom) {
  const fs::path csv = convert();
  const fs::path out = dir_ / "disc";
  const Result r = tmlab({"discover", csv.string(), "--out", out.string(), "--max-samples", "150", "--rounds",
                          "1", "--starts", "4"});
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("baseline stvk+prony:2"), std::string::npos) << r.output;  // progress
  ASSERT_TRUE(fs::exists(out / "summary.json"));
  const nlohmann::json j = nlohmann::json::parse(read_file(out / "report.json"));
  for (const char* k : {"dataset", "baseline", "steps", "selected_effects", "final", "unexplained_structure",
                        "unexplained_signature", "forward_model"})
    EXPECT_TRUE(j.contains(k)) << k;
  for (const char* k : {"model", "rms_N", "rel_rms"}) {
    EXPECT_TRUE(j["baseline"].contains(k)) << k;
    EXPECT_TRUE(j["final"].contains(k)) << k;
  }
  EXPECT_EQ(j["dataset"], "EF10_0T_A1");
  EXPECT_EQ(j["baseline"]["model"], "stvk+prony:2");
  ASSERT_FALSE(j["steps"].empty());
  for (const auto& s : j["steps"])
    for (const char* k : {"effect", "rms_N", "held_out_rms_N", "criterion", "accepted"})
      EXPECT_TRUE(s.contains(k)) << k;
  // St VK cannot follow 67 % compression: a hyperelastic law is what the first round adds.
  ASSERT_EQ(j["selected_effects"].size(), 1u) << j["selected_effects"];
  EXPECT_NE(j["selected_effects"][0].get<std::string>().find("_hyperelastic"), std::string::npos);
  EXPECT_LT(j["final"]["rms_N"].get<double>(), 0.25 * j["baseline"]["rms_N"].get<double>());
  EXPECT_TRUE(fs::exists(out / "index.html"));
  EXPECT_TRUE(fs::exists(out / "discover.h5"));
  EXPECT_TRUE(fs::exists(out / "manifest.json"));
  for (const char* png : {"discover_fits.png", "discover_residuals.png", "discover_residual_vs_strain.png"}) {
    ASSERT_TRUE(fs::exists(out / png)) << png << "\n" << r.output;
    EXPECT_EQ(read_file(out / png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  }
}

TEST_F(CliDiscover, BadOptionsAreRefused) {
  const fs::path csv = convert();
  Result r = tmlab({"discover"});
  EXPECT_EQ(r.status, 2) << r.output;
  r = tmlab({"discover", csv.string(), "--effects", "gremlins"});
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("unknown effect 'gremlins'"), std::string::npos) << r.output;
  r = tmlab({"discover", csv.string(), "--quick"});
  EXPECT_EQ(r.status, 2) << r.output;
  r = tmlab({"discover", csv.string(), "--poisson", "0.6"});
  EXPECT_EQ(r.status, 2) << r.output;
}

}  // namespace
