// What every runner of a case takes and gives back (the tensor-mass runner, the deal.II reference):
// where results go and how verbose to be; the result directory and its summary.
#pragma once

#include "core/results/checkpoint.hpp"

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
  /// Continue an interrupted run from its checkpoint (the tensor-mass runner; issue 12).
  bool resume = false;
  /// When the tensor-mass runner writes checkpoints besides at a stop request (--checkpoint-every).
  CheckpointSchedule checkpoints;
};

struct RunResult {
  std::string dir;         ///< the complete result directory
  nlohmann::json summary;  ///< its summary.json
};

}  // namespace tmlab
