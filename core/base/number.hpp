// One strict number grammar for everything a user types: option values on the command line, the
// fields of a measured-data CSV, the parameters of a model SPEC. Decimal only:
//
//   [+-]digits[.digits][(e|E)[+-]digits]
//
// so "1.5", "-2e-3", "+7" are numbers and ".5", "7.", " 1", "0x1p-1", "1e", "nan", "inf" are not
// (std::stod would take most of those). Values must be finite.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace tmlab {

/// Parses `s` under the grammar above. On failure returns false and says why in `why` (the text
/// shown at most 40 characters, control characters escaped).
bool parse_decimal(std::string_view s, double& out, std::string& why);

/// A whole number written as [+-]digits, within [min, max]. On failure returns false and says why in `why`.
bool parse_whole(std::string_view s, std::int64_t min, std::int64_t max, std::int64_t& out, std::string& why);

}  // namespace tmlab
