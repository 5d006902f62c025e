// The tmlab sub-commands, one function each (commands.cpp).
#pragma once

#include "apps/tmlab/options/parsed_options.hpp"
#include "core/config/case_config.hpp"
#include "runner/case_runner.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace tmlab::cli {

/// The tmlab source tree (cases/, meshes/, results/): $TMLAB_ROOT, else the tree this binary was built from.
std::string tmlab_root();

/// A case argument: an existing file, else the shipped case cases/<arg>.json (tmlab::Error if neither).
std::string resolve_case(const std::string& arg);
/// Runs `cfg` with `model` (tensor_mass, tl_oracle or reference; degree and time integration for
/// the reference).
tmlab::RunResult run_model(const CaseConfig& cfg, const tmlab::RunOptions& opt, const std::string& model,
                           int degree, const std::string& time_integration = "fixed_step");

int cmd_demo(const std::vector<std::string>& args, const std::string& command_line);
int cmd_run(const std::vector<std::string>& args, const std::string& command_line);
int cmd_cases(const std::vector<std::string>& args);
int cmd_mesh(const std::vector<std::string>& args);
int cmd_paper(const std::vector<std::string>& args, const std::string& command_line);
int cmd_compare(const std::vector<std::string>& args, const std::string& command_line);
int cmd_version();
// Studies and verification, each in its own source file (cmd_<name>.cpp).
int cmd_hereditary(const std::vector<std::string>& args, const std::string& command_line);
int cmd_workprecision(const std::vector<std::string>& args, const std::string& command_line);
int cmd_verify(const std::vector<std::string>& args, const std::string& command_line);
// Measured-data work: the test rigs (cmd_rig.cpp).
int cmd_rig(const std::vector<std::string>& args);
// A mesh-convergence study of a rig or a case (cmd_converge.cpp, docs/convergence.md).
int cmd_converge(const std::vector<std::string>& args, const std::string& command_line);
// Measured data sets (cmd_data.cpp, docs/measured-data.md).
int cmd_data(const std::vector<std::string>& args);
// Inverse identification (cmd_fit.cpp, docs/identification.md).
int cmd_fit(const std::vector<std::string>& args, const std::string& command_line);
// Kernel and step benchmarks with the machine's limits (cmd_bench.cpp, docs/performance.md).
int cmd_bench(const std::vector<std::string>& args, const std::string& command_line);
// The real-time haptic / control / visual loop (cmd_realtime.cpp, docs/realtime.md).
int cmd_realtime(const std::vector<std::string>& args, const std::string& command_line);
// Model discovery (cmd_discover.cpp, docs/discover.md).
int cmd_discover(const std::vector<std::string>& args, const std::string& command_line);
// The depth at which each law inverts a tet under a sphere (cmd_depth_limit.cpp, docs/contact.md).
int cmd_depth_limit(const std::vector<std::string>& args, const std::string& command_line);

}  // namespace tmlab::cli
