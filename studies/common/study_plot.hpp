// The studies' plotting scripts (verification/studies/python/): one place that finds a script in the
// tmlab tree and runs it on a result directory with the plotting python (core/base/process.hpp).
#pragma once

#include "core/base/process.hpp"

#include <filesystem>
#include <string>

namespace tmlab::tm {

/// Runs `python verification/studies/python/<script> <dir>` (run_python: no shell). Returns how it
/// ended; never throws for a failing script.
ProcessStatus draw_study_plot(const std::string& tmlab_root, const std::string& script,
                              const std::filesystem::path& dir, const ProcessOutput& output = {});

}  // namespace tmlab::tm
