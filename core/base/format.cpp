#include "core/base/format.hpp"

#include <cstdio>

namespace tmlab {

namespace {
std::string print(const char* style, int digits, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, style, digits, v);
  return buf;
}
}  // namespace

std::string significant(double v, int digits) { return print("%.*g", digits, v); }
std::string scientific(double v, int digits) { return print("%.*e", digits, v); }
std::string fixed_point(double v, int digits) { return print("%.*f", digits, v); }

std::string choice_list(const std::vector<std::string>& names, const std::string& quote) {
  std::string out;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (k > 0) out += k + 1 == names.size() ? " or " : ", ";
    out += quote + names[k] + quote;
  }
  return out;
}

std::string printable(std::string_view s, std::size_t max_chars) {
  std::string out;
  const std::size_t n = s.size() < max_chars ? s.size() : max_chars;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned>(c));
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (n < s.size()) out += "...";
  return out;
}

}  // namespace tmlab
