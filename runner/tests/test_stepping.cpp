// step(): each solver advanced from rest with t = 0 recorded first, its summary block, the fields
// at the steps output.every asks for, and a contact case stepped with its bodies.
#include "core/results/run_output.hpp"
#include "core/results/series_names.hpp"
#include "runner/stepping.hpp"
#include "runner/tests/runner_test_case.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm::runner {
namespace {

using json = nlohmann::json;

class SteppingTest : public RunnerTestCase {
 protected:
  /// Steps the case `j`; `rec_steps` gets the number of recorded steps, `frames` the field frames.
  json run(const json& j, std::size_t& rec_steps, int& frames) {
    const CaseConfig cfg = config(j);
    const Problem p(cfg);
    RunOutput out(dir_ / "results" / cfg.name);
    StepRecorder rec(p, out);
    RunOptions opt;
    opt.checkpoints.every_seconds = 0.0;
    RunCheckpoint ck(p, out.dir(), opt);
    const json info = step(p, rec, nullptr, ck);
    rec_steps = rec.recorder().table().series().front().values.size();
    frames = rec.recorder().field_frames();
    last_probe_x_ = rec.recorder().table().series().empty() ? 0.0 : probe_x(rec);
    return info;
  }
  static double probe_x(const StepRecorder& rec) {
    for (const auto& s : rec.recorder().table().series())
      if (s.name == "probe_corner_x") return s.values.back();
    return 0.0;
  }
  double last_probe_x_ = 0.0;
};

TEST_F(SteppingTest, StaticLoadSteps) {
  json j = uniaxial(0.001);
  j["output"]["every"] = 3;
  std::size_t n = 0;
  int frames = 0;
  const json info = run(j, n, frames);
  EXPECT_EQ(info["type"], "static");
  EXPECT_EQ(info["load_steps"], 4);
  EXPECT_GE(info["newton_iterations"].get<long>(), 4);
  EXPECT_EQ(info["newton"]["per_step"]["iterations"].size(), 4u);
  EXPECT_EQ(n, 5u);      // t = 0 and 4 steps
  EXPECT_EQ(frames, 3);  // t = 0, step 3 and the last step
  EXPECT_NEAR(last_probe_x_, 0.001, 1e-12);
}

TEST_F(SteppingTest, ExplicitAndImplicitDynamics) {
  json j = uniaxial(1e-5);
  j["solver"] = json::parse(R"({"type": "explicit", "dt": 1e-5, "t_end": 1e-3})");
  std::size_t n = 0;
  int frames = 0;
  json info = run(j, n, frames);
  EXPECT_EQ(info["type"], "explicit");
  EXPECT_EQ(info["steps"], 100);
  EXPECT_GT(info["dt_critical_estimate"].get<double>(), 1e-5);
  EXPECT_EQ(n, 101u);
  j["name"] = "implicit";
  j["solver"] = json::parse(R"({"type": "implicit", "dt": 1e-4, "t_end": 1e-3})");
  info = run(j, n, frames);
  EXPECT_EQ(info["type"], "implicit");
  EXPECT_EQ(info["steps"], 10);
  EXPECT_EQ(n, 11u);
}

TEST_F(SteppingTest, ContactCasesStepWithTheirBodies) {
  std::size_t n = 0;
  int frames = 0;
  const json info = run(platen(0.0005), n, frames);
  EXPECT_EQ(info["type"], "static");
  ASSERT_TRUE(info.contains("contact"));
  EXPECT_EQ(info["contact"]["scheme"], "augmented_lagrangian_static");
  EXPECT_EQ(info["contact"]["bodies"][0]["name"], "top");
  EXPECT_GT(info["contact"]["bodies"][0]["final_force_N"][2].get<double>(), 0.0);
  EXPECT_EQ(n, 3u);
}

TEST(Stepping, FieldStepsAndTheExplicitSummary) {
  CaseConfig cfg;
  cfg.solver.steps = 10;
  cfg.output.every = 4;
  for (int k : {0, 4, 8, 10}) EXPECT_TRUE(field_step(cfg, k)) << k;
  for (int k : {1, 5, 9}) EXPECT_FALSE(field_step(cfg, k)) << k;
  StabilityEstimate st;
  st.dt_critical = 2e-5;
  cfg.solver.dt = 1e-5;
  const json j = explicit_summary(cfg, st);
  EXPECT_EQ(j["scheme"], "central_difference");
  EXPECT_EQ(j["dt"], 1e-5);
  EXPECT_EQ(j["dt_critical_estimate"], 2e-5);
}

}  // namespace
}  // namespace tmlab::tm::runner
