// RunCheckpoint: written at a step boundary when due or when a stop is pending, never otherwise;
// --resume restores the loop (time, state, Newton log and counters), the model and the recorder
// exactly; a checkpoint of another case is refused; where() says how to continue.
#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/results/run_output.hpp"
#include "runner/run_checkpoint.hpp"
#include "runner/tests/runner_test_case.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>

namespace tmlab::tm::runner {
namespace {

namespace fs = std::filesystem;

class RunCheckpointTest : public RunnerTestCase {
 protected:
  void TearDown() override {
    set_pending_interrupt(0);
    RunnerTestCase::TearDown();
  }
  fs::path result() const { return dir_ / "results" / "uniaxial"; }
  fs::path file() const { return result() / RunOutput::kStaging / "checkpoint.h5"; }
  static RunOptions options(long every_steps, bool resume) {
    RunOptions o;
    o.checkpoints.every_steps = every_steps;
    o.checkpoints.every_seconds = 0.0;
    o.resume = resume;
    return o;
  }
};

TEST_F(RunCheckpointTest, WrittenWhenDueAndRestoredExactly) {
  const CaseConfig cfg = config(uniaxial(0.001));
  const Problem p(cfg);
  RunOutput out(result());
  StepRecorder rec(p, out);
  State s{VecX::Random(p.system.num_dofs()), VecX::Random(p.system.num_dofs())};
  double t = 0.3;
  NewtonLog newton;
  NewtonResult nr;
  nr.history = {1.0, 1e-3};
  newton.add(nr, 2, 1, 2, false);
  long total_newton = 7, total_cutbacks = 1;
  const LoopState loop{s, t, &newton, &total_newton, &total_cutbacks, nullptr, nullptr};
  rec.record(0, 0.0, VecX::Zero(p.system.num_dofs()), VecX::Zero(p.system.num_dofs()), 0, true);

  RunCheckpoint ck(p, result(), options(2, false));
  EXPECT_FALSE(ck.resuming());
  EXPECT_EQ(ck.restore(rec, loop), 0);  // not resuming: nothing to restore
  EXPECT_NE(ck.where().find("no checkpoint was written"), std::string::npos);
  ck.after_step(1, rec, loop);  // not due
  EXPECT_FALSE(fs::exists(file()));
  ck.after_step(2, rec, loop);
  ASSERT_TRUE(fs::exists(file()));
  EXPECT_NE(ck.where().find("checkpoint after step 2 in " + file().string()), std::string::npos)
      << ck.where();
  EXPECT_NE(ck.where().find("--resume"), std::string::npos);

  RunCheckpoint resumed(p, result(), options(0, true));
  ASSERT_TRUE(resumed.resuming());
  RunOutput out2(dir_ / "results" / "other");
  StepRecorder rec2(p, out2);
  State s2{VecX::Zero(p.system.num_dofs()), VecX::Zero(p.system.num_dofs())};
  double t2 = 0.0;
  NewtonLog newton2;
  long total_newton2 = 0, total_cutbacks2 = 0;
  const LoopState loop2{s2, t2, &newton2, &total_newton2, &total_cutbacks2, nullptr, nullptr};
  EXPECT_EQ(resumed.restore(rec2, loop2), 2);
  EXPECT_EQ(t2, t);
  EXPECT_EQ(s2.u, s.u);
  EXPECT_EQ(s2.v, s.v);
  EXPECT_EQ(total_newton2, 7);
  EXPECT_EQ(total_cutbacks2, 1);
  EXPECT_EQ(newton2.json(cfg.solver), newton.json(cfg.solver));
  EXPECT_EQ(rec2.recorder().field_frames(), 1);
  resumed.remove();
  EXPECT_FALSE(fs::exists(file()));
}

TEST_F(RunCheckpointTest, APendingStopWritesOneOffSchedule) {
  const CaseConfig cfg = config(uniaxial(0.001));
  const Problem p(cfg);
  RunOutput out(result());
  StepRecorder rec(p, out);
  State s{VecX::Zero(p.system.num_dofs()), VecX::Zero(p.system.num_dofs())};
  double t = 0.0;
  const LoopState loop{s, t, nullptr, nullptr, nullptr, nullptr, nullptr};
  RunCheckpoint ck(p, result(), options(0, false));  // --checkpoint-every off
  ck.after_step(1, rec, loop);
  EXPECT_FALSE(fs::exists(file()));
  set_pending_interrupt(SIGINT);
  ck.after_step(2, rec, loop);
  EXPECT_TRUE(fs::exists(file()));
}

TEST_F(RunCheckpointTest, ACheckpointOfAnotherCaseIsRefused) {
  const CaseConfig cfg = config(uniaxial(0.001));
  const Problem p(cfg);
  {
    RunOutput out(result());
    StepRecorder rec(p, out);
    State s{VecX::Zero(p.system.num_dofs()), VecX::Zero(p.system.num_dofs())};
    double t = 0.0;
    RunCheckpoint ck(p, result(), options(1, false));
    ck.after_step(1, rec, {s, t, nullptr, nullptr, nullptr, nullptr, nullptr});
    ASSERT_TRUE(fs::exists(file()));
  }
  const CaseConfig other = config(uniaxial(0.002));
  const Problem q(other);
  try {
    RunCheckpoint ck(q, result(), options(0, true));
    FAIL() << "a checkpoint of another case was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the checkpoint is of another configuration"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tmlab::tm::runner
