// The help text of a command, generated from its option table (option_table.hpp): every option is
// listed by construction.
#pragma once

#include "apps/tmlab/options/option_table.hpp"

#include <string>

namespace tmlab::cli {

/// The help block of one command: its synopsis, summary and every option with its value, range and
/// default, in the layout of `tmlab help`.
std::string command_help(const CommandSpec& spec);

}  // namespace tmlab::cli
