// Number formatting for messages, logs and reports: one implementation of each style.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace tmlab {

/// printf "%.<digits>g": significant digits, no trailing zeros ("0.499", "1e-09").
std::string significant(double v, int digits = 3);
/// printf "%.<digits>e": scientific ("3.200e-09").
std::string scientific(double v, int digits = 3);
/// printf "%.<digits>f": fixed decimals ("1.97").
std::string fixed_point(double v, int digits = 2);

/// The accepted values of a choice for a message: "'a', 'b' or 'c'" (each name between `quote`).
std::string choice_list(const std::vector<std::string>& names, const std::string& quote = "'");

/// Text from a user's file or command line made safe to print in a message: control characters
/// (NUL, ESC and the rest below 0x20, and 0x7f) become \xNN escapes, so a message is neither cut at a
/// NUL nor able to drive the terminal; at most `max_chars` characters of `s` are shown, then "...".
std::string printable(std::string_view s, std::size_t max_chars = 200);

}  // namespace tmlab
