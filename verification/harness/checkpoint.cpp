#include "verification/harness/checkpoint.hpp"

#include "core/base/error.hpp"
#include "core/results/checkpoint.hpp"

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

namespace {
constexpr const char* kKind = "verify";

/// The JSON checkpoint directory of tmlab versions before the HDF5 one: <file without .h5>/.
fs::path legacy_dir(const fs::path& file) {
  fs::path d = file;
  d.replace_extension();
  return d;
}
}  // namespace

SuiteCheckpoint::SuiteCheckpoint(fs::path file, const json& suite, bool resume)
    : file_(std::move(file)), suite_(suite) {
  const fs::path legacy = legacy_dir(file_);
  if (resume) {
    if (!fs::exists(file_) && fs::exists(legacy / "suite.json"))
      throw Error("--resume: " + legacy.string() +
                  " is a JSON checkpoint of an earlier tmlab; this version checkpoints to HDF5 (" +
                  file_.filename().string() + ") and does not read it: run without --resume");
    if (!fs::exists(file_))
      throw Error("--resume: no checkpoint " + file_.string() +
                  " (nothing was interrupted, or the last run finished; run without --resume)");
    CheckpointData d;
    try {
      d = read_checkpoint(file_, kKind, suite);
    } catch (const Error& e) {
      const std::string m = e.what();
      if (m.find("another configuration") == std::string::npos) throw;
      throw Error(m + " (a checkpoint of a different suite)");
    }
    for (const auto& name : json::parse(d.text("cases")).get<std::vector<std::string>>()) {
      const std::string& text = d.text("case." + std::to_string(done_.size()));
      try {
        done_.emplace(name, case_result_from_json(json::parse(text)));
      } catch (const json::exception& e) {
        throw Error(file_.string() + ": unreadable result of case " + name + " (" + e.what() + ")");
      }
      order_.push_back(name);
    }
    return;
  }
  remove_checkpoint(file_);
  std::error_code ignored;
  fs::remove_all(legacy, ignored);
}

std::optional<CaseResult> SuiteCheckpoint::find(const std::string& name) const {
  const auto it = done_.find(name);
  if (it == done_.end()) return std::nullopt;
  return it->second;
}

void SuiteCheckpoint::store(const CaseResult& r) {
  if (!done_.count(r.name)) order_.push_back(r.name);
  done_[r.name] = r;
  // The whole suite state in one file, replaced atomically: a crash leaves the old or the new.
  CheckpointData d;
  d.put_text("cases", json(order_).dump());
  for (std::size_t i = 0; i < order_.size(); ++i)
    d.put_text("case." + std::to_string(i), case_result_to_json(done_.at(order_[i])).dump());
  fs::create_directories(file_.parent_path());
  write_checkpoint(file_, kKind, suite_, d);
}

void SuiteCheckpoint::remove() const { remove_checkpoint(file_); }

std::size_t SuiteCheckpoint::stored() const { return done_.size(); }

}  // namespace tmlab::verify
