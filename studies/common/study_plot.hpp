// The studies' plotting scripts (studies/<study>/python/): one place that finds a script in the tmlab
// tree and runs it on a result directory with the plotting python (core/base/process.hpp).
#pragma once

#include "core/base/process.hpp"

#include <filesystem>
#include <string>

namespace tmlab::tm {

/// Runs `python studies/<study>/python/<script> <dir>` (run_python: no shell); `study` is the study's
/// folder (paper, hereditary, workprecision, depth_limit). Returns how it ended; never throws for a
/// failing script.
ProcessStatus draw_study_plot(const std::string& tmlab_root, const std::string& study,
                              const std::string& script, const std::filesystem::path& dir,
                              const ProcessOutput& output = {});

}  // namespace tmlab::tm
