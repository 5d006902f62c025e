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

}  // namespace tmlab
