#include "core/base/number.hpp"

#include "core/base/format.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <system_error>

namespace tmlab {

namespace {

bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

/// Consumes a run of digits from s[i]; returns how many.
std::size_t digits(std::string_view s, std::size_t& i) {
  const std::size_t from = i;
  while (i < s.size() && is_digit(s[i])) ++i;
  return i - from;
}

std::string shown(std::string_view s) { return "'" + printable(s, 40) + "'"; }

}  // namespace

bool parse_decimal(std::string_view s, double& out, std::string& why) {
  if (s.empty()) {
    why = "empty value (a number is needed)";
    return false;
  }
  std::string lower;
  for (char c : s.substr(0, 8)) lower += char(std::tolower(static_cast<unsigned char>(c)));
  const std::string_view body =
      (lower[0] == '+' || lower[0] == '-') ? std::string_view(lower).substr(1) : std::string_view(lower);
  if (body.rfind("nan", 0) == 0) {
    why = "NaN is not a value";
    return false;
  }
  if (body.rfind("inf", 0) == 0) {
    why = "an infinite value is not allowed";
    return false;
  }
  std::size_t i = (s[0] == '+' || s[0] == '-') ? 1 : 0;
  const std::size_t first = i;
  bool ok = digits(s, i) > 0;
  if (ok && i < s.size() && s[i] == '.') {
    ++i;
    ok = digits(s, i) > 0;
  }
  if (ok && i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    ok = digits(s, i) > 0;
  }
  if (!ok || i != s.size()) {
    why = shown(s) + " is not a number (decimal: [+-]digits[.digits][e[+-]digits])";
    return false;
  }
  // from_chars takes no leading '+'.
  const std::size_t from = s[0] == '+' ? first : 0;
  const auto r = std::from_chars(s.data() + from, s.data() + s.size(), out);
  if (r.ec == std::errc::result_out_of_range || (r.ec == std::errc() && !std::isfinite(out))) {
    why = shown(s) + " is out of the range of a double";
    return false;
  }
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) {
    why = shown(s) + " is not a number";
    return false;
  }
  return true;
}

bool parse_whole(std::string_view s, std::int64_t min, std::int64_t max, std::int64_t& out,
                 std::string& why) {
  std::size_t i = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
  const std::size_t n = digits(s, i);
  if (s.empty() || n == 0 || i != s.size()) {
    double d = 0.0;
    std::string ignored;
    why = parse_decimal(s, d, ignored) ? shown(s) + " is not a whole number"
                                       : shown(s) + " is not a whole number (digits only)";
    return false;
  }
  const std::size_t from = s[0] == '+' ? 1 : 0;
  std::int64_t v = 0;
  const auto r = std::from_chars(s.data() + from, s.data() + s.size(), v);
  if (r.ec == std::errc::result_out_of_range || v < min || v > max) {
    why = shown(s) + " is outside " + std::to_string(min) + " .. " + std::to_string(max);
    return false;
  }
  out = v;
  return true;
}

}  // namespace tmlab
