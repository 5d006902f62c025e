// What `tmlab discover` writes and says (issue 15; docs/discover.md): index.html (the page a reader
// opens first, from report.json), discover.h5 (read by python/tmlab_discover_plot.py), the
// benchmark's confusion matrix (text and CSV), the reports on standard output, and the options
// fingerprint --resume must match. The loop itself is discover.hpp, the benchmark benchmark.hpp.
#pragma once

#include "calibration/discover/benchmark.hpp"
#include "calibration/discover/discover.hpp"
#include "calibration/discover/fe_refit.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace tmlab::discover {

/// index.html from report.json (`report`, with its "fe_rig" block when there is one): what was
/// found, the error before and after, the figures when `plots`, each step with its evidence, the
/// diagnostics, the parameters, the library.
std::string report_html(const nlohmann::json& report, bool plots);
/// report_html into `path` (tmlab::Error naming it when it cannot be written).
void write_report_html(const std::filesystem::path& path, const nlohmann::json& report, bool plots);

/// discover.h5: per test (/tests/NNN, attribute id) the data, the baseline's and the final model's
/// forces, and each FE refit's (fe_rig_<which>_N).
void write_discover_h5(const std::filesystem::path& path, const Report& r,
                       const std::vector<FeRefit>& fe_refits);

/// The error before and after, each accepted effect and the FE refits.
void print_discover_report(std::ostream& os, const Report& r, const std::vector<FeRefit>& fe_refits);

/// The confusion matrix as text: a title line, then CSV (rows: truth; columns: the effects found
/// that have a count).
std::string benchmark_text(const BenchmarkResult& b);
/// The CSV part of benchmark_text into `path` (tmlab::Error naming it when it cannot be written).
void write_confusion_csv(const std::filesystem::path& path, const BenchmarkResult& b);
/// The confusion matrix and the benchmark's scores (library, noise-only, outside sets, error reduction).
void print_benchmark_report(std::ostream& os, const BenchmarkResult& b);

/// Every option of the loop that changes its result, as the engine holds them: part of what
/// --resume must match and of the manifest (tmlab discover adds its command-line options, the FE
/// rig's and the data's hashes).
nlohmann::json options_fingerprint(const Options& o);

/// summary.json's own block of a discovery (`plots`: "ok", "failed (why)", "skipped (--no-plots)").
nlohmann::json summary_json(const Report& r, const std::string& plots);
/// summary.json's own block of a benchmark.
nlohmann::json summary_json(const BenchmarkResult& b);

/// The plots of a discovery (calibration/discover/python/tmlab_discover_plot.py under `tmlab_root`,
/// from report.json and discover.h5 in `dir`): "ok" or "failed (why)".
std::string write_discover_plots(const std::filesystem::path& dir, const std::filesystem::path& tmlab_root);

}  // namespace tmlab::discover
