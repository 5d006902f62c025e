// Checkpoint files: exact round trip, atomic replacement, refusal of another kind or configuration
// (naming the differing key), and the --checkpoint-every schedule.
#include "core/base/error.hpp"
#include "core/results/checkpoint.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace fs = std::filesystem;

namespace {

using tmlab::CheckpointData;
using tmlab::CheckpointSchedule;

class CheckpointTest : public tmlab::testing::TempDirTest {};

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), 8 * a.size()) == 0);
}

TEST_F(CheckpointTest, RoundTripIsExact) {
  CheckpointData d;
  const std::vector<double> u = {0.1,
                                 -0.0,
                                 1e-310,
                                 std::numeric_limits<double>::quiet_NaN(),
                                 std::numeric_limits<double>::infinity(),
                                 std::nextafter(1.0, 2.0)};
  d.put("state.u", u);
  d.put("empty", std::vector<double>{});
  d.put("ints", std::vector<std::int64_t>{-1, 0, std::numeric_limits<std::int64_t>::max()});
  d.put_scalar("t", 0.30000000000000004);
  d.put_int("step", 17);
  const std::string text = std::string("{\"a\": 1}\n\0binary", 16) + "x";  // odd length, NUL inside
  d.put_text("note", text);
  const nlohmann::json config = {{"solver", {{"dt", 1e-3}, {"steps", 10}}}, {"name", "cube"}};
  const fs::path f = dir_ / "checkpoint.h5";
  tmlab::write_checkpoint(f, "run", config, d);
  EXPECT_FALSE(fs::exists(dir_ / "checkpoint.h5.tmp"));

  const CheckpointData r = tmlab::read_checkpoint(f, "run", config);
  EXPECT_TRUE(same_bits(r.doubles("state.u"), u));
  EXPECT_TRUE(r.doubles("empty").empty());
  EXPECT_EQ(r.ints("ints"), d.ints("ints"));
  EXPECT_EQ(r.scalar("t"), 0.30000000000000004);
  EXPECT_EQ(r.integer("step"), 17);
  EXPECT_EQ(r.text("note"), text);
  EXPECT_TRUE(r.has("note"));
  EXPECT_FALSE(r.has("v"));
  try {
    (void)r.doubles("v");
    FAIL() << "a missing entry must throw";
  } catch (const tmlab::Error& e) {
    EXPECT_NE(std::string(e.what()).find("'v'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(f.string()), std::string::npos) << e.what();
  }

  // A second write replaces the first.
  d.put_int("step", 18);
  tmlab::write_checkpoint(f, "run", config, d);
  EXPECT_EQ(tmlab::read_checkpoint(f, "run", config).integer("step"), 18);
}

TEST_F(CheckpointTest, AnotherConfigurationOrKindIsRefusedNamingTheDifference) {
  const fs::path f = dir_ / "c.h5";
  const nlohmann::json config = {{"solver", {{"dt", 1e-3}, {"steps", 10}}}, {"name", "cube"}};
  tmlab::write_checkpoint(f, "run", config, {});
  nlohmann::json other = config;
  other["solver"]["dt"] = 2e-3;
  try {
    tmlab::read_checkpoint(f, "run", other);
    FAIL() << "another configuration must be refused";
  } catch (const tmlab::Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("solver.dt: the checkpoint has 0.001, this run 0.002"), std::string::npos) << m;
    EXPECT_NE(m.find("without --resume"), std::string::npos) << m;
  }
  EXPECT_THROW(tmlab::read_checkpoint(f, "hereditary", config), tmlab::Error);
  try {
    tmlab::read_checkpoint(dir_ / "none.h5", "run", config);
    FAIL();
  } catch (const tmlab::Error& e) {
    EXPECT_NE(std::string(e.what()).find("no checkpoint"), std::string::npos) << e.what();
  }
  // Not HDF5 at all.
  tmlab::testing::write_file(dir_ / "junk.h5", "not hdf5");
  EXPECT_THROW(tmlab::read_checkpoint(dir_ / "junk.h5", "run", config), tmlab::Error);
  EXPECT_THROW(CheckpointData().put("a/b", std::vector<double>{}), tmlab::Error);
}

TEST(CheckpointMismatch, NamesKeysAndArrayEntries) {
  EXPECT_EQ(tmlab::fingerprint_mismatch({{"a", 1}}, {{"a", 1}}), "");
  const std::string m = tmlab::fingerprint_mismatch({{"cases", {"x", "y"}}}, {{"cases", {"x", "z"}}});
  EXPECT_EQ(m, "cases[1]: the checkpoint has \"y\", this run \"z\"");
  EXPECT_NE(
      tmlab::fingerprint_mismatch({{"a", 1}}, {{"a", 1}, {"b", 2}}).find("b: the checkpoint has nothing"),
      std::string::npos);
}

TEST(CheckpointScheduleTest, ParsesStepsTimesAndOff) {
  EXPECT_EQ(CheckpointSchedule::parse("25").every_steps, 25);
  EXPECT_EQ(CheckpointSchedule::parse("25").every_seconds, 0.0);
  EXPECT_EQ(CheckpointSchedule::parse("30s").every_seconds, 30.0);
  EXPECT_EQ(CheckpointSchedule::parse("2min").every_seconds, 120.0);
  EXPECT_EQ(CheckpointSchedule::parse("1.5min").every_seconds, 90.0);
  EXPECT_EQ(CheckpointSchedule::parse("0.5s").every_seconds, 0.5);
  EXPECT_EQ(CheckpointSchedule::parse("off").describe(), "only on a stop request");
  EXPECT_EQ(CheckpointSchedule::parse("5").describe(), "every 5 steps");
  for (const char* bad :
       {"", "0", "-3", "2.5", "10h", "s", "nan", "0x10", " 5", "5 ", ".5s", "1e3", "2.5", "+", "s", "min"})
    EXPECT_THROW(CheckpointSchedule::parse(bad), tmlab::Error) << bad;
  const tmlab::CheckpointClock by_steps(CheckpointSchedule::parse("5"));
  EXPECT_TRUE(by_steps.due(10));
  EXPECT_FALSE(by_steps.due(11));
  const tmlab::CheckpointClock off(CheckpointSchedule::parse("off"));
  EXPECT_FALSE(off.due(10));
}

}  // namespace
