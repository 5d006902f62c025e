// `tmlab hereditary`'s result (docs/hereditary.md): the hereditary study (hereditary_study.hpp) run in
// its named steps (recursion sweeps, amplification factors, ramp-hold time histories, the kink on and
// off the step grid, haptic steps, the liver relaxation), each writing its part of hereditary.h5,
// hereditary.md (the tables) and summary.json, then the PNG plots (python/tmlab_hereditary_plot.py).
// The command (apps/tmlab/cmd_hereditary.cpp) parses the arguments and owns the result directory.
#pragma once

#include "core/results/checkpoint.hpp"
#include "studies/hereditary/hereditary_study.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace tmlab::tm {

struct HereditaryRunOptions {
  std::vector<DriverHistory> histories;  ///< the sweep's histories (study_histories)
  StudyOptions study;                    ///< study.quick: coarser sweeps, the short liver set
  bool liver = true;                     ///< run the liver relaxation
  /// The liver's history forms, each its own study: nodal_force (the seed's) and/or pk2.
  std::vector<std::string> liver_histories = {"nodal_force", "pk2"};
  std::string params_file;       ///< the paper parameter document (cases/paper/xu2011_liver.json)
  std::string tmlab_root = ".";  ///< meshes/, studies/<study>/python/
  std::string command_line;      ///< quoted in hereditary.md
  bool plots = true;
  std::function<void(const std::string&)> log;  ///< progress lines (may be empty)
  /// Checkpoints (issue 12; empty: none): after every sweep (history and scheme) and every liver
  /// study, the finished results are written to this file with `fingerprint` (the effective
  /// options), and SIGINT/SIGTERM stop the study there.
  std::filesystem::path checkpoint;
  nlohmann::json fingerprint = nlohmann::json::object();
  /// --resume: a checkpoint read back (read_checkpoint kind "hereditary"); its finished sweeps and
  /// liver studies are taken from it instead of run again.
  std::optional<CheckpointData> resume;
};

/// Runs the study and writes hereditary.h5, hereditary.md and (plots) the PNGs into `dir`; returns
/// the summary (for summary.json). Throws tmlab::Error for bad parameters or a failing plot script.
nlohmann::json write_hereditary_study(const HereditaryRunOptions& options, const std::filesystem::path& dir);

}  // namespace tmlab::tm
