// run_with_protocol (core/results/run_protocol.hpp): manifest -> compute -> checkpoint removed ->
// summary.json last; a stop request leaves INTERRUPTED naming the checkpoint (which stays), any
// other error FAILED, and the exception reaches the caller either way. With UnitCheckpoint
// (unit_checkpoint.hpp), the hooks every unit-wise command uses.
#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/results/run_protocol.hpp"
#include "core/results/unit_checkpoint.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using tmlab::CheckpointData;
using tmlab::CheckpointSchedule;
using tmlab::Interrupted;
using tmlab::RunOutput;
using tmlab::UnitCheckpoint;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class RunProtocolTest : public tmlab::testing::TempDirTest {
 protected:
  tmlab::ManifestInput manifest() const {
    tmlab::ManifestInput mi;
    mi.command_line = {"tmlab", "test"};
    mi.config = {{"answer", 42}};
    return mi;
  }
  /// A checkpoint that writes after every unit; its snapshot holds the number of units so far.
  CheckpointSchedule every_unit() const {
    CheckpointSchedule s;
    s.every_steps = 1;
    s.every_seconds = 0.0;
    return s;
  }
};

TEST_F(RunProtocolTest, CompleteRunHasManifestSummaryAndNoCheckpoint) {
  const fs::path dir = dir_ / "run";
  long units = 0;
  UnitCheckpoint ck(dir / RunOutput::kStaging / "checkpoint.h5", "test", {{"k", 1}}, every_unit(), [&units] {
    CheckpointData d;
    d.put_int("units", units);
    return d;
  });
  std::vector<std::string> order;
  {
    RunOutput out(dir);
    tmlab::run_with_protocol(
        out, manifest(),
        [&] {
          order.push_back(fs::exists(out.file("manifest.json")) ? "manifest before compute" : "no manifest");
          ++units;
          ck.unit_finished("1 unit");
          order.push_back(fs::exists(ck.path()) ? "checkpoint written" : "no checkpoint");
          out.write_json("result.json", {{"x", 1.5}});
          return nlohmann::json{{"answer", 42}};
        },
        tmlab::protocol_checkpoint(ck));
    EXPECT_TRUE(out.finalized());
  }
  EXPECT_EQ(order, (std::vector<std::string>{"manifest before compute", "checkpoint written"}));
  EXPECT_TRUE(fs::exists(dir / "manifest.json"));
  EXPECT_TRUE(fs::exists(dir / "result.json"));
  ASSERT_TRUE(fs::exists(dir / "summary.json"));
  EXPECT_NE(slurp(dir / "summary.json").find("\"answer\": 42"), std::string::npos);
  EXPECT_NE(slurp(dir / "manifest.json").find("\"answer\": 42"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / RunOutput::kStaging));
  EXPECT_FALSE(fs::exists(dir / "checkpoint.h5")) << "a complete result holds no checkpoint";
  EXPECT_FALSE(fs::exists(dir / RunOutput::kFailed));
}

TEST_F(RunProtocolTest, InterruptedLeavesMarkerNamingTheCheckpoint) {
  const fs::path dir = dir_ / "run";
  long units = 0;
  UnitCheckpoint ck(dir / RunOutput::kStaging / "checkpoint.h5", "test", {{"k", 1}}, CheckpointSchedule{},
                    [&units] {
                      CheckpointData d;
                      d.put_int("units", units);
                      return d;
                    });
  std::string caught;
  {
    RunOutput out(dir);
    try {
      tmlab::run_with_protocol(
          out, manifest(),
          [&]() -> nlohmann::json {
            ++units;
            ck.unit_finished("2 finished units");  // not due yet (every 60 s): pending at the stop
            throw Interrupted(15, "stopped by SIGTERM");
          },
          tmlab::protocol_checkpoint(ck));
    } catch (const Interrupted& e) {
      caught = e.what();
      EXPECT_EQ(e.signal(), 15);
    }
    EXPECT_TRUE(out.interrupted());
  }
  EXPECT_NE(caught.find("checkpoint after 2 finished units"), std::string::npos) << caught;
  ASSERT_TRUE(fs::exists(dir / RunOutput::kInterrupted));
  EXPECT_NE(slurp(dir / RunOutput::kInterrupted).find("--resume"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  // The pending unit was written at the stop and reads back.
  EXPECT_EQ(ck.read().integer("units"), 1);
}

TEST_F(RunProtocolTest, ErrorLeavesFailedAndKeepsTheCheckpoint) {
  const fs::path dir = dir_ / "run";
  UnitCheckpoint ck(dir / RunOutput::kStaging / "checkpoint.h5", "test", {{"k", 1}}, every_unit(),
                    [] { return CheckpointData{}; });
  bool threw = false;
  {
    RunOutput out(dir);
    try {
      tmlab::run_with_protocol(
          out, manifest(),
          [&]() -> nlohmann::json {
            ck.unit_finished("1 unit");
            throw tmlab::Error("the model diverged");
          },
          tmlab::protocol_checkpoint(ck));
    } catch (const Interrupted&) {
      ADD_FAILURE() << "an error is not a stop request";
    } catch (const tmlab::Error& e) {
      threw = std::string(e.what()) == "the model diverged";
    }
    EXPECT_TRUE(out.failed());
  }
  EXPECT_TRUE(threw);
  ASSERT_TRUE(fs::exists(dir / RunOutput::kFailed));
  EXPECT_NE(slurp(dir / RunOutput::kFailed).find("the model diverged"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  EXPECT_TRUE(fs::exists(ck.path())) << "only a complete result drops its checkpoint";
}

TEST_F(RunProtocolTest, WithoutCheckpointAStopIsPassedOnUnchanged) {
  const fs::path dir = dir_ / "run";
  std::string caught;
  {
    RunOutput out(dir);
    try {
      tmlab::run_with_protocol(out, manifest(), []() -> nlohmann::json { throw Interrupted(2, "stopped"); });
    } catch (const Interrupted& e) {
      caught = e.what();
    }
    EXPECT_TRUE(out.interrupted());
  }
  EXPECT_EQ(caught, "stopped");
}

TEST_F(RunProtocolTest, RefusesToResumeACompleteResult) {
  std::ofstream(dir_ / "summary.json") << "{}";
  try {
    tmlab::refuse_resume_of_complete(dir_, "fit");
    FAIL() << "no error";
  } catch (const tmlab::Error& e) {
    EXPECT_NE(std::string(e.what()).find("nothing to resume"), std::string::npos);
  }
  EXPECT_NO_THROW(tmlab::refuse_resume_of_complete(dir_ / "elsewhere", "fit"));
  std::ofstream(dir_ / "data.csv") << "a";
  EXPECT_EQ(tmlab::file_hash(dir_ / "data.csv"), "af63dc4c8601ec8c");  // FNV-1a-64 of "a"
}

}  // namespace
