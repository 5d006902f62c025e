// Runs one case file with the tensor-mass model (or its total-Lagrangian oracle) and writes
// results/<case>/: timeseries.h5 (quantities per step), fields.h5 + fields.xdmf and vtu/*.vtu +
// result.pvd (fields for ParaView), PNG plots, manifest.json, and summary.json last.
#pragma once

#include "core/config/case_config.hpp"
#include "core/results/run_options.hpp"
#include "tensormass/solvers/newton.hpp"

#include <nlohmann/json.hpp>

#include <ostream>
#include <string>
#include <vector>

namespace tmlab::tm {

using tmlab::RunOptions;  // core/results/run_options.hpp: shared with the deal.II reference
using tmlab::RunResult;

/// Runs the case. Bad input (mesh, parameters, empty selections), an inverted element, an unstable
/// explicit step or a failed Newton solve throw tmlab::Error; the result directory then holds a
/// FAILED marker and no summary.json.
RunResult run_case(const CaseConfig& config, const RunOptions& options);

/// The Newton settings of a case file's solver section (solver.newton, docs/case-files.md).
NewtonOptions newton_options(const SolverSpec& solver);

}  // namespace tmlab::tm
