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

}  // namespace tmlab
