// `tmlab realtime` as a user meets it (issue 17): --record writes timing.json with every thread's
// and every coupling's fields, forces.csv, PNG frames and summary.json last; bad cases and options
// are refused naming the problem. No timing assertion (the machine may be busy).
#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace {

namespace fs = std::filesystem;

using tmlab::cli_test::Result;
using tmlab::testing::read_file;
using tmlab::testing::write_file;

class CliRealtime : public tmlab::cli_test::CliTest {};

TEST_F(CliRealtime, RecordWritesTheTimingReport) {
  const Result r =
      tmlab({"realtime", "liver-poke", "--record", "--duration", "0.5", "--results", dir_.string()});
  ASSERT_EQ(r.status, 0) << r.output;
  const fs::path out = dir_ / "realtime";
  ASSERT_TRUE(fs::exists(out / "summary.json")) << r.output;
  const nlohmann::json t = nlohmann::json::parse(read_file(out / "timing.json"));
  for (const char* thread : {"haptic", "control", "visual"})
    for (const char* key : {"target_hz", "rate_hz", "p50_us", "p99_us", "p999_us", "missed"})
      EXPECT_TRUE(t["threads"][thread].contains(key)) << thread << "." << key;
  EXPECT_EQ(t["threads"]["haptic"]["target_hz"], 1000.0);
  EXPECT_EQ(t["threads"]["visual"]["target_hz"], 40.0);
  for (const char* scheme : {"extrapolation", "local_model"}) {
    EXPECT_TRUE(t["couplings"][scheme]["haptic_force_error_rel"].is_number()) << scheme;
    EXPECT_TRUE(t["couplings"][scheme]["coupling_energy_J"].is_number()) << scheme;
  }
  EXPECT_GT(t["frames"].get<int>(), 0);
  EXPECT_TRUE(fs::exists(out / "frames" / "frame_0000.png"));
  EXPECT_TRUE(fs::exists(out / "forces.csv"));
  EXPECT_TRUE(fs::exists(out / "manifest.json"));
  // 0.5 s of the 1.6 s poke: the study's path is open, and the run says its energy is no passivity measure.
  EXPECT_EQ(t["study"]["path_closed"], false);
  EXPECT_NE(r.output.find("covers 0.5 s of the 1.6 s trajectory, an open path"), std::string::npos)
      << r.output;
}

TEST_F(CliRealtime, WholePokeIsAClosedPath) {
  const Result r = tmlab(
      {"realtime", "liver-poke", "--record", "--duration", "1.6", "--no-frames", "--results", dir_.string()});
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json t = nlohmann::json::parse(read_file(dir_ / "realtime" / "timing.json"));
  EXPECT_EQ(t["study"]["path_closed"], true);
  EXPECT_EQ(t["frames"], 0);
  EXPECT_EQ(r.output.find("passivity measure"), std::string::npos) << r.output;
  // The deterministic study over the whole poke meets the bounds of docs/realtime.md (test 2's).
  for (const char* scheme : {"extrapolation", "local_model"})
    EXPECT_LE(t["couplings"][scheme]["coupling_energy_J"].get<double>(), 0.0) << scheme;
}

TEST_F(CliRealtime, BadInputIsRefused) {
  Result r = tmlab({"realtime", "no-such-case"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("no case file 'no-such-case'"), std::string::npos) << r.output;
  r = tmlab({"realtime", "liver-poke", "--duration", "-1"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--duration"), std::string::npos) << r.output;
  r = tmlab({"realtime", "liver-poke", "--coupling", "magic"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("haptic coupling 'magic' is unknown"), std::string::npos) << r.output;
  // A case with a misspelt key and one with a trajectory CSV with a bad line.
  const std::string src = read_file(fs::path(TMLAB_SOURCE_DIR) / "cases" / "realtime" / "liver-poke.json");
  std::string bad = src;
  bad.replace(bad.find("\"png_every\""), 11, "\"png_evry\"");
  write_file(dir_ / "bad.json", bad);
  r = tmlab({"realtime", (dir_ / "bad.json").string()});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("png_evry"), std::string::npos) << r.output;
  std::string csv = src;
  const auto a = csv.find("\"trajectory\": {");
  const auto b = csv.find('}', a);
  csv.replace(a, b - a + 1, "\"trajectory\": {\"type\": \"csv\", \"file\": \"probe.csv\"}");
  write_file(dir_ / "csv.json", csv);
  write_file(dir_ / "probe.csv", "t,x,y,z\n0,0,0,1.6\n0.1,0,oops,1.6\n");
  r = tmlab({"realtime", (dir_ / "csv.json").string()});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("probe.csv:3: column 3 (y) is not a finite number: 'oops'"), std::string::npos)
      << r.output;
  // A path in millimetres (the mesh is in metres): refused at its first sample, not run without contact.
  write_file(dir_ / "probe.csv", "t,x,y,z\n# mm by mistake\n0,-40.4,-57.6,1636\n1,-40.4,-57.6,1626\n");
  r = tmlab({"realtime", (dir_ / "csv.json").string()});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(
      r.output.find("probe.csv:3: the probe centre (-40.4, -57.6, 1636) m lies outside the mesh's bounding "
                    "box grown by two probe radii"),
      std::string::npos)
      << r.output;
  // So is a probe surface point in millimetres, naming the key.
  std::string mm = src;
  const auto sp = mm.find("\"surface_point\": [");
  mm.replace(sp, mm.find(']', sp) - sp + 1, "\"surface_point\": [-40.4, -57.6, 1609.1]");
  write_file(dir_ / "mm.json", mm);
  r = tmlab({"realtime", (dir_ / "mm.json").string()});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("key 'probe.surface_point' lies outside the mesh's bounding box"),
            std::string::npos)
      << r.output;
}

}  // namespace
