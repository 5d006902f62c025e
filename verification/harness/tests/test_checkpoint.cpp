// Suite checkpoints: a CaseResult survives the round trip through JSON bit for bit (NaN and
// infinities included), and a checkpoint resumes only the suite it was written for.
#include "core/base/error.hpp"
#include "verification/harness/checkpoint.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

namespace tmlab::verify {
namespace {

namespace fs = std::filesystem;

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b));
}

CaseResult sample() {
  CaseResult r;
  r.name = "case-a";
  r.status = Status::Fail;
  r.error_message = "";
  r.seconds = 1.0 / 3.0;
  CheckOutcome o;
  o.name = "err";
  o.kind = "max";
  o.measured = 0.1 + 0.2;  // not representable exactly in decimal: must survive bit for bit
  o.limit = 1e-300;
  o.tolerance = std::numeric_limits<double>::infinity();
  o.rationale = "because";
  o.passed = false;
  r.outcomes = {o};
  r.measurements.set("nan", std::numeric_limits<double>::quiet_NaN());
  r.measurements.set("minus_inf", -std::numeric_limits<double>::infinity());
  r.measurements.set("tiny", std::numeric_limits<double>::denorm_min());
  r.measurements.series["conv"] = Series{"h [m]", "error", {0.1, 0.05}, {1e-3 / 7.0, 2.5e-4 / 7.0}};
  r.measurements.notes = {"a note"};
  r.measurements.data = {{"rows", {1, 2, 3}}};
  return r;
}

TEST(Checkpoint, CaseResultRoundTripsBitForBit) {
  const CaseResult a = sample();
  const CaseResult b = case_result_from_json(nlohmann::json::parse(case_result_to_json(a).dump()));
  EXPECT_EQ(b.name, a.name);
  EXPECT_EQ(b.status, a.status);
  EXPECT_TRUE(same_bits(b.seconds, a.seconds));
  ASSERT_EQ(b.outcomes.size(), 1u);
  EXPECT_TRUE(same_bits(b.outcomes[0].measured, a.outcomes[0].measured));
  EXPECT_TRUE(same_bits(b.outcomes[0].limit, a.outcomes[0].limit));
  EXPECT_TRUE(std::isinf(b.outcomes[0].tolerance));
  EXPECT_EQ(b.outcomes[0].passed, false);
  for (const auto& [k, v] : a.measurements.metrics)
    EXPECT_TRUE(same_bits(b.measurements.metrics.at(k), v)) << k;
  EXPECT_EQ(b.measurements.series.at("conv").y, a.measurements.series.at("conv").y);
  EXPECT_EQ(b.measurements.notes, a.measurements.notes);
  EXPECT_EQ(b.measurements.data, a.measurements.data);
}

TEST(Checkpoint, StoresFindsAndResumesOnlyTheSameSuite) {
  const fs::path root = fs::temp_directory_path() / ("tmlab_checkpoint_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root);
  const fs::path dir = root / "verification.checkpoint.h5";
  const nlohmann::json suite = {{"cases", {"case-a", "case-b"}}};
  EXPECT_THROW(SuiteCheckpoint(dir, suite, /*resume=*/true), Error);  // nothing to resume
  {
    SuiteCheckpoint cp(dir, suite, false);
    EXPECT_FALSE(cp.find("case-a").has_value());
    cp.store(sample());
    EXPECT_EQ(cp.stored(), 1u);
  }
  {
    const SuiteCheckpoint cp(dir, suite, true);
    ASSERT_TRUE(cp.find("case-a").has_value());
    EXPECT_TRUE(same_bits(cp.find("case-a")->outcomes[0].measured, 0.1 + 0.2));
    EXPECT_FALSE(cp.find("case-b").has_value());
  }
  try {
    SuiteCheckpoint(dir, nlohmann::json{{"cases", {"case-a"}}}, true);
    FAIL() << "a checkpoint of another suite was resumed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("different suite"), std::string::npos) << e.what();
  }
  {
    const SuiteCheckpoint fresh(dir, suite, false);  // without --resume: starts again
    EXPECT_EQ(fresh.stored(), 0u);
    EXPECT_FALSE(fs::exists(dir));
    fresh.remove();
  }
  EXPECT_FALSE(fs::exists(dir));

  // The JSON checkpoint directory of earlier versions: refused on --resume with a clear message,
  // removed by a fresh run.
  fs::create_directories(root / "verification.checkpoint");
  std::ofstream(root / "verification.checkpoint" / "suite.json") << suite.dump();
  try {
    SuiteCheckpoint(dir, suite, true);
    FAIL() << "an old JSON checkpoint was resumed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("JSON checkpoint of an earlier tmlab"), std::string::npos)
        << e.what();
  }
  { const SuiteCheckpoint fresh(dir, suite, false); }
  EXPECT_FALSE(fs::exists(root / "verification.checkpoint"));
  fs::remove_all(root);
}

}  // namespace
}  // namespace tmlab::verify
