// The run's checkpoint (issue 12, core/results/checkpoint.hpp): what a stepping loop needs to
// continue with --resume and end with a result identical bit for bit to an uninterrupted run.
#pragma once

#include "core/results/checkpoint.hpp"
#include "core/results/run_options.hpp"
#include "runner/contact_checkpoint.hpp"
#include "runner/loop_state.hpp"
#include "runner/problem.hpp"
#include "runner/step_recorder.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

namespace tmlab::tm::runner {

/// The run's checkpoint, <result dir>/.incomplete/checkpoint.h5: written at step boundaries when
/// the schedule says so and when a stop was requested; read back by --resume, which restores the
/// state so that the finished result is identical bit for bit to an uninterrupted run.
class RunCheckpoint {
 public:
  /// The checkpoint of the run whose result directory is `dir`. With opt.resume the checkpoint is
  /// read and checked against the case here (a refusal throws tmlab::Error before the result
  /// directory is touched); opt.checkpoints says when after_step writes one.
  RunCheckpoint(const Problem& p, const std::filesystem::path& dir, const RunOptions& opt);
  bool resuming() const { return resume_.has_value(); }

  /// After the loop's integrator is initialised: restores the saved state (model, integrator,
  /// loop, recorder and field files) and returns the last completed step (0 when not resuming).
  int restore(StepRecorder& rec, const LoopState& loop, const ContactLoop* contact = nullptr);

  /// At a step boundary, after the step is recorded: writes the checkpoint when it is due or a
  /// stop was requested (SIGINT/SIGTERM; the loop's safe point throws right after).
  void after_step(int step, const StepRecorder& rec, const LoopState& loop,
                  const ContactLoop* contact = nullptr);

  /// For the INTERRUPTED marker: where the checkpoint is and how to continue.
  std::string where() const;
  /// The run is complete: its result directory holds no checkpoint.
  void remove() const;

 private:
  const Problem& p_;
  std::filesystem::path path_;
  nlohmann::json fingerprint_;
  CheckpointClock clock_;
  std::ostream* log_;
  std::optional<CheckpointData> resume_;
  int last_step_ = -1;
};

}  // namespace tmlab::tm::runner
