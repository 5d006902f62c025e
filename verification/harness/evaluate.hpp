// Judging measurements against a case's tolerances, and the result of a case.
#pragma once

#include "verification/harness/case_spec.hpp"
#include "verification/harness/measurement.hpp"

#include <string>
#include <vector>

namespace tmlab::verify {

enum class Status { Pass, Fail, Error };
const char* to_string(Status s);

struct CheckOutcome {
  std::string name;  ///< metric or series name
  std::string kind;  ///< "max", "min", "order", "finest"
  double measured = 0.0;
  double limit = 0.0;      ///< tolerance (max/min/finest) or expected order (order)
  double tolerance = 0.0;  ///< order: |observed - expected| allowed; else = limit
  std::string rationale;
  bool passed = false;
  std::string describe() const;  ///< "force_rel_error = 3.2e-09 <= 1e-07"
};

struct CaseResult {
  std::string name;
  Status status = Status::Error;
  std::vector<CheckOutcome> outcomes;
  Measurements measurements;
  std::string error_message;  ///< Status::Error: what went wrong
  double seconds = 0.0;
  /// The case's headline check, used for the one-line summary, the results table and the
  /// `error` / `tolerance` of verification.json: the first failed check if any failed; otherwise
  /// the finest-error check of the first convergence study if the case has one (the error the
  /// study ends at); otherwise the first check. nullptr if there are no outcomes.
  const CheckOutcome* primary() const;
};

/// Applies every check and convergence check of `c` to `m`. A metric or series that the check
/// function did not produce is a failed check with a message (never a silent pass).
CaseResult evaluate(const VerificationCase& c, Measurements m);

}  // namespace tmlab::verify
