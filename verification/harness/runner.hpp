// Selecting and running verification cases, with progress.
#pragma once

#include "verification/harness/checkpoint.hpp"
#include "verification/harness/evaluate.hpp"
#include "verification/harness/registry.hpp"

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace tmlab::verify {

struct Selection {
  bool full = false;                ///< include suite "full"
  std::vector<std::string> names;   ///< --case (any suite); empty: all of the suite(s)
  std::vector<std::string> labels;  ///< --label: keep cases having any of these
};

/// The cases to run, in catalogue order. Throws tmlab::Error for an unknown --case name (listing
/// the known ones) or a label no case has.
std::vector<VerificationCase> select(const std::vector<VerificationCase>& catalogue, const Selection& s);

struct RunSettings {
  std::filesystem::path source_root;
  std::filesystem::path work_root;  ///< scratch: <work_root>/<case>/
};

/// Runs each case (exceptions become Status::Error, except tmlab::Interrupted, which stops the suite),
/// printing "[k/n] name ... PASS (1.2 s)" to `log`. With a checkpoint, a case whose result it holds
/// is not run again (its stored result is used), and each finished case's result is stored.
std::vector<CaseResult> run_cases(const std::vector<VerificationCase>& cases, const CheckRegistry& registry,
                                  const RunSettings& settings, std::ostream& log,
                                  SuiteCheckpoint* checkpoint = nullptr);

}  // namespace tmlab::verify
