// Checkpoints of a verification suite, so that an interrupted `tmlab verify` can continue with
// `--resume` and end with the same report as an uninterrupted run.
//
// The unit of work is a case: after each case the runner stores its complete CaseResult (status,
// every check outcome, every measurement, series, notes and data; doubles in a form that reads
// back bit for bit, non-finite values included) in one HDF5 checkpoint file (core/results/
// checkpoint.hpp: results/verification.checkpoint.h5), rewritten atomically after every case. Its
// fingerprint is the suite (the selected cases in order, and the options that change results);
// resuming with a different selection is refused, naming the difference. A case interrupted
// half-way is run again from its start on resume (check functions are deterministic for a given
// build and thread count, so the results are the same). The JSON checkpoint directory of earlier
// versions (results/verification.checkpoint/) is not read: --resume says so.
#pragma once

#include "verification/harness/evaluate.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tmlab::verify {

/// The CaseResult as JSON and back (exact for doubles, including NaN and infinities).
nlohmann::json case_result_to_json(const CaseResult& r);
CaseResult case_result_from_json(const nlohmann::json& j);

class SuiteCheckpoint {
 public:
  /// Opens (resume = true: must exist and describe the same `suite`) or starts afresh (resume =
  /// false: an existing checkpoint, and an old JSON one, are removed) the checkpoint file `file`.
  /// Throws tmlab::Error when resuming without a checkpoint, from an old JSON checkpoint, or with
  /// one of a different suite (naming the difference).
  SuiteCheckpoint(std::filesystem::path file, const nlohmann::json& suite, bool resume);

  /// The stored result of case `name`, if that case finished before.
  std::optional<CaseResult> find(const std::string& name) const;
  /// Stores the result of a finished case (atomically: a crash leaves the old state or the new).
  void store(const CaseResult& r);
  /// Removes the checkpoint (after the suite's report is complete).
  void remove() const;
  /// How many cases of the suite have a stored result.
  std::size_t stored() const;
  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
  nlohmann::json suite_;
  std::map<std::string, CaseResult> done_;
  std::vector<std::string> order_;  ///< the stored cases in the order they finished
};

}  // namespace tmlab::verify
