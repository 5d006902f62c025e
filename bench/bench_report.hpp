// The report of tmlab bench: bench.json (the run_bench document plus the target ratios), bench.md
// (tables and targets) and the PNG plots (bench/python/tmlab_bench_plot.py: ns/tet
// against mesh size, speed-up against threads).
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <ostream>
#include <string>

namespace tmlab::tm {

/// The issue-16 targets evaluated on one run's records: [{name, value, limit, unit, met, note}].
/// A target whose records are missing (e.g. the 2.4M cube without --large) has value null.
nlohmann::json bench_targets(const nlohmann::json& bench);
/// Markdown tables (force kernels: ns/tet per mesh; steps: us/step per mesh) and the targets.
std::string bench_markdown(const nlohmann::json& bench);
/// Writes bench.json and bench.md into dir, and the plots when `plots` (run_python; a failing
/// plotter is reported on `log`, not fatal). Returns the summary block for summary.json.
nlohmann::json write_bench_report(nlohmann::json bench, const std::filesystem::path& dir, bool plots,
                                  const std::string& tmlab_root, std::ostream* log);

}  // namespace tmlab::tm
