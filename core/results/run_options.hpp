// What every runner of a case takes and gives back (the tensor-mass runner, the deal.II reference):
// where results go and how verbose to be; the result directory and its summary.
#pragma once

#include <nlohmann/json.hpp>

#include <ostream>
#include <string>
#include <vector>

namespace tmlab {

struct RunOptions {
  std::string results_root = "results";  ///< results go to <results_root>/<case name>
  std::string tmlab_root = ".";          ///< for the plotting script
  std::vector<std::string> command_line;
  bool plots = true;
  std::ostream* log = nullptr;  ///< progress and a short report (nullptr: silent)
};

struct RunResult {
  std::string dir;         ///< the complete result directory
  nlohmann::json summary;  ///< its summary.json
};

}  // namespace tmlab
