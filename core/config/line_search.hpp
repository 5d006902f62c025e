// The Newton line search, one vocabulary for the case file, both models' solvers and the summary
// (docs/theory/newton.md).
#pragma once

#include <optional>
#include <string>

namespace tmlab {

/// energy: Armijo on the potential where one exists, else full steps (the default); residual:
/// sufficient decrease of |R|; none: full Newton steps.
enum class LineSearch { Energy, Residual, None };

inline std::string to_string(LineSearch ls) {
  switch (ls) {
    case LineSearch::Energy:
      return "energy";
    case LineSearch::Residual:
      return "residual";
    case LineSearch::None:
      break;
  }
  return "none";
}

/// The line search a name denotes ("energy", "residual", "none"), or nothing.
inline std::optional<LineSearch> line_search_from_string(const std::string& name) {
  for (LineSearch ls : {LineSearch::Energy, LineSearch::Residual, LineSearch::None})
    if (to_string(ls) == name) return ls;
  return std::nullopt;
}

}  // namespace tmlab
