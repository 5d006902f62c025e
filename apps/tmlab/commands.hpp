// The tmlab sub-commands, one function each (commands.cpp).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace tmlab::cli {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The tmlab source tree (cases/, meshes/, results/): $TMLAB_ROOT, else the tree this binary was built from.
std::string tmlab_root();

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

}  // namespace tmlab::cli
