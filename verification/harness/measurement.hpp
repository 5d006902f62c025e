// What a check function measures: named scalar metrics and named series (x, error) for
// convergence studies, plus free-form notes and data for the report. No pass/fail here: the
// case's verify.json judges the measurements (evaluate.hpp).
#pragma once

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

namespace tmlab::verify {

struct Series {
  std::string x_label = "h";      ///< axis label, e.g. "h [m]" or "dt [s]"
  std::string y_label = "error";  ///< axis label
  std::vector<double> x, y;
};

struct Measurements {
  std::map<std::string, double> metrics;
  std::map<std::string, Series> series;
  std::vector<std::string> notes;                  ///< one line each, shown in the report
  nlohmann::json data = nlohmann::json::object();  ///< extra values kept in verification.json

  void set(const std::string& name, double value) { metrics[name] = value; }
};

}  // namespace tmlab::verify
