// A number for a result's JSON: JSON has no infinity or NaN, so those are written as null (read
// as "not available"), never as a string or a huge stand-in. One copy for every writer of
// fit.json, report.json, hereditary.json and the verification report.
#pragma once

#include <nlohmann/json.hpp>

#include <cmath>

namespace tmlab {

/// v as a JSON number, or null when v is infinite or NaN.
inline nlohmann::json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

}  // namespace tmlab
