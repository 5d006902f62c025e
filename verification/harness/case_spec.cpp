#include "verification/harness/case_spec.hpp"

#include "core/base/error.hpp"
#include "core/config/config_reader.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace fs = std::filesystem;

namespace tmlab::verify {

bool VerificationCase::has_label(const std::string& label) const {
  return std::find(labels.begin(), labels.end(), label) != labels.end();
}

namespace {

std::string require_text(ConfigReader& r, const std::string& key) {
  const auto s = r.require<std::string>(key);
  if (s.empty()) throw r.error(key, "must not be empty");
  return s;
}

/// A label or a case name: lower case letters, digits, '-', '_' and '.', so it is safe in ctest
/// names, file names and command lines.
bool is_identifier(const std::string& s) {
  if (s.empty()) return false;
  return std::all_of(s.begin(), s.end(), [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '-' || ch == '_' || ch == '.';
  });
}

MetricCheck read_check(ConfigReader r) {
  MetricCheck c;
  c.metric = require_text(r, "metric");
  const bool has_max = r.has("max"), has_min = r.has("min");
  if (has_max == has_min) throw r.error("max", "give exactly one of 'max' or 'min'");
  c.bound = has_max ? MetricCheck::Bound::Max : MetricCheck::Bound::Min;
  c.limit = r.require<double>(has_max ? "max" : "min");
  if (!std::isfinite(c.limit)) throw r.error(has_max ? "max" : "min", "must be finite");
  c.rationale = require_text(r, "rationale");
  r.finish();
  return c;
}

ConvergenceCheck read_convergence(ConfigReader r) {
  ConvergenceCheck c;
  c.series = require_text(r, "series");
  c.expected_order = r.positive("expected_order");
  c.order_tolerance = r.positive("order_tolerance");
  c.fit_points = r.get<int>("fit_points", 0);
  if (c.fit_points == 1 || c.fit_points < 0) throw r.error("fit_points", "must be 0 (all points) or >= 2");
  c.finest_max = r.positive("finest_max");
  c.rationale = require_text(r, "rationale");
  r.finish();
  return c;
}

}  // namespace

VerificationCase load_case(const fs::path& dir) {
  VerificationCase c;
  c.dir = dir;
  c.name = dir.filename().string();
  const fs::path spec = dir / "verify.json";
  if (!fs::exists(spec)) throw Error(spec.string() + ": missing (every case directory needs verify.json)");
  if (!is_identifier(c.name))
    throw Error(dir.string() + ": case name must use only a-z, 0-9, '-', '_' and '.'");
  const nlohmann::json j = ConfigReader::parse_file(spec.string());
  if (!j.is_object()) throw Error(spec.string() + ": must hold a JSON object");
  ConfigReader r(j, spec.string());
  c.title = require_text(r, "title");
  c.what = require_text(r, "what");
  c.reference = require_text(r, "reference");
  c.kind = require_text(r, "kind");
  c.suite = r.get<std::string>("suite", "fast");
  if (c.suite != "fast" && c.suite != "full")
    throw r.error("suite", "must be \"fast\" or \"full\" (got \"" + c.suite + "\")");
  c.labels = r.get<std::vector<std::string>>("labels", {});
  for (const auto& l : c.labels)
    if (!is_identifier(l))
      throw r.error("labels", "label \"" + l + "\" must use only a-z, 0-9, '-', '_' and '.'");
  if (r.has("parameters")) {
    c.parameters = r.raw("parameters");
    if (!c.parameters.is_object()) throw r.error("parameters", "must be an object");
  }
  if (r.has("checks")) {
    const auto& arr = r.raw("checks");
    if (!arr.is_array()) throw r.error("checks", "must be an array");
    for (std::size_t i = 0; i < arr.size(); ++i)
      c.checks.push_back(
          read_check(ConfigReader(arr[i], spec.string(), "checks[" + std::to_string(i) + "]")));
  }
  if (r.has("convergence")) {
    const auto& arr = r.raw("convergence");
    if (!arr.is_array()) throw r.error("convergence", "must be an array");
    for (std::size_t i = 0; i < arr.size(); ++i)
      c.convergence.push_back(
          read_convergence(ConfigReader(arr[i], spec.string(), "convergence[" + std::to_string(i) + "]")));
  }
  c.report = r.get<std::vector<std::string>>("report", {});
  r.finish();
  if (c.checks.empty() && c.convergence.empty())
    throw Error(spec.string() + ": a case needs at least one entry in 'checks' or 'convergence'");
  if (!fs::exists(dir / "README.md"))
    throw Error((dir / "README.md").string() + ": missing (every case needs a README)");
  return c;
}

std::vector<VerificationCase> load_catalogue(const fs::path& root) {
  if (!fs::is_directory(root)) throw Error(root.string() + ": verification case directory not found");
  std::vector<fs::path> dirs;
  for (const auto& e : fs::directory_iterator(root))
    if (e.is_directory()) dirs.push_back(e.path());
  std::sort(dirs.begin(), dirs.end());
  std::vector<VerificationCase> out;
  out.reserve(dirs.size());
  for (const auto& d : dirs) out.push_back(load_case(d));
  return out;
}

}  // namespace tmlab::verify
