// tmlab::Error: the one exception type for bad user input (files, parameters, meshes, unstable steps).
// Its message always names where the problem is (file and line, config key, element index) so the
// CLI can print it and exit non-zero. Internal invariants use assert(), not this type.
#pragma once

#include <stdexcept>
#include <string>

namespace tmlab {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/// "file:line: reason" (line omitted when 0), the format used for every input error.
inline Error input_error(const std::string& file, long line, const std::string& reason) {
  std::string where = file;
  if (line > 0) where += ":" + std::to_string(line);
  return Error(where + ": " + reason);
}

}  // namespace tmlab
