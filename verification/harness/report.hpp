// The verification report: verification.json (machines), report.md and a self-contained
// report.html (people; plots inline), convergence plots (PNG, log-log with fitted slopes) and the
// results table that docs/verification.md embeds.
#pragma once

#include "verification/harness/evaluate.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace tmlab::verify {

struct ReportInput {
  std::vector<VerificationCase> cases;  ///< same order as results
  std::vector<CaseResult> results;
  std::string command_line;
  bool plots = true;                  ///< draw the plots (run_python: the plotting python)
  std::filesystem::path plot_script;  ///< verification/harness/python/plot_convergence.py
};

/// One entry per case: name, status, error, tolerance, observed_order / expected_order where a
/// convergence check applies, and the full list of checks.
nlohmann::json verification_json(const ReportInput& in);

/// The results table (markdown): case, status, primary measured value, tolerance, order.
std::string results_table(const ReportInput& in);

/// Writes plots/<case>.png for cases with series (through the python script), report.md,
/// report.html and verification.json into `dir`. Returns the plot files written. A missing
/// plotting interpreter is reported in the report, not fatal.
std::vector<std::filesystem::path> write_report(const ReportInput& in, const std::filesystem::path& dir);

/// Replaces the text between "<!-- verification-results:begin -->" and
/// "<!-- verification-results:end -->" in `doc` with `table`. Throws tmlab::Error when the markers
/// are missing.
void update_doc_table(const std::filesystem::path& doc, const std::string& table);

}  // namespace tmlab::verify
