#include "verification/harness/checkpoint.hpp"

#include "core/base/error.hpp"
#include "core/io/atomic_file.hpp"

#include <cmath>
#include <fstream>
#include <limits>

namespace tmlab::verify {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
/// JSON cannot hold NaN or infinities (nlohmann writes them as null): they become strings.
json number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}
double number(const json& j) {
  if (j.is_string()) {
    const std::string s = j.get<std::string>();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
    throw Error("checkpoint: '" + s + "' is not a number");
  }
  return j.get<double>();
}
json numbers(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(number(x));
  return a;
}
std::vector<double> numbers(const json& a) {
  std::vector<double> v;
  for (const auto& x : a) v.push_back(number(x));
  return v;
}
Status status_from(const std::string& s) {
  if (s == "pass") return Status::Pass;
  if (s == "fail") return Status::Fail;
  return Status::Error;
}
const char* status_name(Status s) {
  return s == Status::Pass ? "pass" : s == Status::Fail ? "fail" : "error";
}
}  // namespace

json case_result_to_json(const CaseResult& r) {
  json outcomes = json::array();
  for (const CheckOutcome& o : r.outcomes)
    outcomes.push_back({{"name", o.name},
                        {"kind", o.kind},
                        {"measured", number(o.measured)},
                        {"limit", number(o.limit)},
                        {"tolerance", number(o.tolerance)},
                        {"rationale", o.rationale},
                        {"passed", o.passed}});
  json metrics = json::object();
  for (const auto& [k, v] : r.measurements.metrics) metrics[k] = number(v);
  json series = json::object();
  for (const auto& [k, s] : r.measurements.series)
    series[k] = {{"x_label", s.x_label}, {"y_label", s.y_label}, {"x", numbers(s.x)}, {"y", numbers(s.y)}};
  return {{"name", r.name},
          {"status", status_name(r.status)},
          {"error_message", r.error_message},
          {"seconds", number(r.seconds)},
          {"outcomes", outcomes},
          {"measurements",
           {{"metrics", metrics},
            {"series", series},
            {"notes", r.measurements.notes},
            {"data", r.measurements.data}}}};
}

CaseResult case_result_from_json(const json& j) {
  CaseResult r;
  r.name = j.at("name").get<std::string>();
  r.status = status_from(j.at("status").get<std::string>());
  r.error_message = j.at("error_message").get<std::string>();
  r.seconds = number(j.at("seconds"));
  for (const auto& o : j.at("outcomes")) {
    CheckOutcome c;
    c.name = o.at("name").get<std::string>();
    c.kind = o.at("kind").get<std::string>();
    c.measured = number(o.at("measured"));
    c.limit = number(o.at("limit"));
    c.tolerance = number(o.at("tolerance"));
    c.rationale = o.at("rationale").get<std::string>();
    c.passed = o.at("passed").get<bool>();
    r.outcomes.push_back(c);
  }
  const json& m = j.at("measurements");
  for (auto it = m.at("metrics").begin(); it != m.at("metrics").end(); ++it)
    r.measurements.metrics[it.key()] = number(it.value());
  for (auto it = m.at("series").begin(); it != m.at("series").end(); ++it) {
    Series s;
    s.x_label = it.value().at("x_label").get<std::string>();
    s.y_label = it.value().at("y_label").get<std::string>();
    s.x = numbers(it.value().at("x"));
    s.y = numbers(it.value().at("y"));
    r.measurements.series[it.key()] = s;
  }
  r.measurements.notes = m.at("notes").get<std::vector<std::string>>();
  r.measurements.data = m.at("data");
  return r;
}

SuiteCheckpoint::SuiteCheckpoint(fs::path dir, const json& suite, bool resume) : dir_(std::move(dir)) {
  const fs::path suite_file = dir_ / "suite.json";
  if (resume) {
    if (!fs::exists(suite_file))
      throw Error("--resume: no checkpoint in " + dir_.string() +
                  " (nothing was interrupted, or the last run finished; run without --resume)");
    std::ifstream in(suite_file);
    json stored;
    try {
      stored = json::parse(in);
    } catch (const json::exception& e) {
      throw Error(suite_file.string() + ": unreadable checkpoint (" + e.what() + ")");
    }
    if (stored != suite)
      throw Error("--resume: the checkpoint in " + dir_.string() + " is of a different suite (" +
                  stored.dump() + "; now " + suite.dump() +
                  "): resume with the same options, or run without --resume to start again");
    return;
  }
  fs::remove_all(dir_);
  fs::create_directories(dir_);
  write_file_atomically(suite_file, suite.dump(2) + "\n");
}

std::optional<CaseResult> SuiteCheckpoint::find(const std::string& name) const {
  const fs::path f = dir_ / (name + ".json");
  if (!fs::exists(f)) return std::nullopt;
  std::ifstream in(f);
  try {
    return case_result_from_json(json::parse(in));
  } catch (const json::exception& e) {
    throw Error(f.string() + ": unreadable checkpoint (" + e.what() + ")");
  }
}

void SuiteCheckpoint::store(const CaseResult& r) const {
  write_file_atomically(dir_ / (r.name + ".json"), case_result_to_json(r).dump() + "\n");
}

void SuiteCheckpoint::remove() const { fs::remove_all(dir_); }

std::size_t SuiteCheckpoint::stored() const {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir_))
    if (e.path().extension() == ".json" && e.path().filename() != "suite.json") ++n;
  return n;
}

}  // namespace tmlab::verify
