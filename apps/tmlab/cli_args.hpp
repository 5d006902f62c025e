// Value helpers shared by the tmlab sub-commands (cli_args.cpp); the options themselves are read
// through each command's option table (command_specs.hpp, options/option_table.hpp).
#pragma once

#include "apps/tmlab/options/parsed_options.hpp"
#include "core/results/checkpoint.hpp"

#include <string>
#include <utility>
#include <vector>

namespace tmlab::cli {

/// Whitespace-separated words (the command line as a list, for manifests).
std::vector<std::string> split_words(const std::string& s);

/// --mesh CELLS,LAYERS of an FE-rig forward model (CELLS 2-400, LAYERS 1-400); UsageError otherwise.
std::pair<int, int> parse_cells_layers(const std::string& value);

/// --checkpoint-every of a command that finishes in units (default: every 60 s of wall time, and
/// always at a stop request); UsageError naming the accepted forms.
CheckpointSchedule checkpoint_schedule(const ParsedOptions& p);

/// --results of the command, or <tmlab>/results.
std::string results_root(const ParsedOptions& p);

}  // namespace tmlab::cli
