// Argument parsing shared by the tmlab sub-commands (cli_args.cpp).
#pragma once

#include "core/results/checkpoint.hpp"

#include <string>
#include <utility>
#include <vector>

namespace tmlab::cli {

/// Splits "--key value" options (listed in `with_value`) and flags from positional arguments.
struct Parsed {
  std::vector<std::string> positional;
  std::vector<std::pair<std::string, std::string>> options;
  /// The value of an option given at most once; UsageError when it is given more than once (a
  /// repeatable option is read with all()).
  std::string get(const std::string& key, const std::string& fallback = "") const;
  bool has(const std::string& key) const;
  /// Every value given for a repeatable option, in order.
  std::vector<std::string> all(const std::string& key) const;
};

/// Throws UsageError for an unknown option or an option missing its value.
Parsed parse(const std::vector<std::string>& args, const std::vector<std::string>& with_value,
             const std::vector<std::string>& flags);

/// A number for option `key` under tmlab's one number grammar (core/base/number.hpp: decimal,
/// finite; no hex, no blanks, no ".5"); UsageError naming the key otherwise.
double parse_double(const std::string& key, const std::string& s);
/// A whole number for option `key` within [min, max]; UsageError naming the key and the range.
long long parse_whole(const std::string& key, const std::string& s, long long min, long long max);

/// The non-empty items of a comma-separated option value ("a,b,,c" -> a, b, c).
std::vector<std::string> split_list(const std::string& s);

/// Whitespace-separated words (the command line as a list, for manifests).
std::vector<std::string> split_words(const std::string& s);

/// --mesh CELLS,LAYERS of an FE-rig forward model (CELLS 2-400, LAYERS 1-400); UsageError otherwise.
std::pair<int, int> parse_cells_layers(const std::string& value);

/// --checkpoint-every of a command that finishes in units (default: every 60 s of wall time, and
/// always at a stop request); UsageError naming the accepted forms.
CheckpointSchedule checkpoint_schedule(const Parsed& p);

}  // namespace tmlab::cli
