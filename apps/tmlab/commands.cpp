// Shared by the sub-commands: the tmlab tree, case-name resolution, tmlab version.
#include "commands.hpp"

#include "core/base/error.hpp"
#include "tmlab/build_info.hpp"

#include <cstdlib>
#include <filesystem>
#include <iostream>

#ifndef TMLAB_SOURCE_DIR
#define TMLAB_SOURCE_DIR "."
#endif

namespace tmlab::cli {

namespace fs = std::filesystem;

std::string tmlab_root() {
  if (const char* env = std::getenv("TMLAB_ROOT"); env && *env) return env;
  return TMLAB_SOURCE_DIR;
}

std::string resolve_case(const std::string& arg) {
  if (fs::exists(arg)) return arg;
  const fs::path named = fs::path(tmlab_root()) / "cases" / (arg + ".json");
  if (!fs::exists(named))
    throw Error(arg + ": no such case file, and no shipped case of that name (see 'tmlab cases')");
  return named.string();
}

int cmd_version() {
  std::cout << "tmlab " << build_info::git_sha << (build_info::git_dirty ? " (modified)" : "") << "\n"
            << "build " << build_info::build_type << ", " << build_info::compiler << "\n";
  return 0;
}

}  // namespace tmlab::cli
