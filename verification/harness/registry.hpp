// The check functions, by kind. A check function reads its case's parameters, measures, and
// returns Measurements; it throws tmlab::Error for bad parameters (naming verify.json and the key).
// Registration is explicit (verification/checks/builtin_checks.hpp), no static initialisers.
#pragma once

#include "verification/harness/case_spec.hpp"
#include "verification/harness/measurement.hpp"

#include <filesystem>
#include <functional>
#include <initializer_list>
#include <iosfwd>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace tmlab::verify {

/// What a check function gets besides its case.
struct CheckContext {
  const VerificationCase& vcase;
  std::filesystem::path source_root;  ///< the tmlab tree (meshes/, cases/)
  std::filesystem::path work_dir;     ///< scratch directory of this case (exists, empty at start)
  std::ostream& log;                  ///< progress lines of long checks
};

using CheckFunction = std::function<Measurements(const CheckContext&)>;

class CheckRegistry {
 public:
  /// Throws (an internal error) when `kind` is registered twice.
  void add(const std::string& kind, CheckFunction fn);
  /// add() for each (kind, function) of a module's checks.
  void add(std::initializer_list<std::pair<std::string, CheckFunction>> checks);
  bool has(const std::string& kind) const { return fns_.count(kind) > 0; }
  /// Throws tmlab::Error naming the case file when `kind` is unknown.
  const CheckFunction& get(const VerificationCase& c) const;
  std::vector<std::string> kinds() const;

 private:
  std::map<std::string, CheckFunction> fns_;
};

}  // namespace tmlab::verify
