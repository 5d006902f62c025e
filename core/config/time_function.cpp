#include "core/config/time_function.hpp"

#include "core/base/error.hpp"
#include "core/config/config_reader.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace tmlab {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TimeFunction TimeFunction::constant(double value) {
  TimeFunction f;
  f.kind_ = Kind::Constant;
  f.a_ = value;
  return f;
}

TimeFunction TimeFunction::ramp(double t0, double t1) {
  if (!(t1 > t0))
    throw Error("ramp time function needs t1 > t0 (got t0=" + std::to_string(t0) +
                ", t1=" + std::to_string(t1) + ")");
  TimeFunction f;
  f.kind_ = Kind::Ramp;
  f.a_ = t0;
  f.b_ = t1;
  return f;
}

TimeFunction TimeFunction::smooth_ramp(double t0, double t1) {
  TimeFunction f = ramp(t0, t1);
  f.kind_ = Kind::SmoothRamp;
  return f;
}

TimeFunction TimeFunction::sine(double amplitude, double frequency, double phase, double offset) {
  TimeFunction f;
  f.kind_ = Kind::Sine;
  f.a_ = amplitude;
  f.b_ = frequency;
  f.c_ = phase;
  f.d_ = offset;
  return f;
}

TimeFunction TimeFunction::table(std::vector<std::pair<double, double>> points) {
  if (points.empty()) throw Error("table time function needs at least one point");
  for (std::size_t i = 1; i < points.size(); ++i)
    if (!(points[i].first > points[i - 1].first))
      throw Error("table time function: times must increase strictly (point " + std::to_string(i) + ")");
  TimeFunction f;
  f.kind_ = Kind::Table;
  f.table_ = std::move(points);
  return f;
}

double TimeFunction::operator()(double t) const {
  switch (kind_) {
    case Kind::Constant:
      return a_;
    case Kind::Ramp:
    case Kind::SmoothRamp: {
      const double s = std::clamp((t - a_) / (b_ - a_), 0.0, 1.0);
      return kind_ == Kind::Ramp ? s : s * s * (3.0 - 2.0 * s);
    }
    case Kind::Sine:
      return d_ + a_ * std::sin(2.0 * kPi * b_ * t + c_);
    case Kind::Table: {
      if (t <= table_.front().first) return table_.front().second;
      if (t >= table_.back().first) return table_.back().second;
      const auto it =
          std::upper_bound(table_.begin(), table_.end(), t,
                           [](double x, const std::pair<double, double>& p) { return x < p.first; });
      const auto& p1 = *it;
      const auto& p0 = *(it - 1);
      const double s = (t - p0.first) / (p1.first - p0.first);
      return (1.0 - s) * p0.second + s * p1.second;
    }
  }
  return 0.0;
}

TimeFunction TimeFunction::from_json(const nlohmann::json& j, const std::string& where) {
  ConfigReader r(j, where);
  const std::string type = r.get<std::string>("type", "constant");
  TimeFunction f;
  if (type == "constant") {
    f = constant(r.get<double>("value", 1.0));
  } else if (type == "ramp" || type == "smooth_ramp") {
    const double t0 = r.get<double>("t0", 0.0);
    const double t1 = r.require<double>("t1");
    if (!(t1 > t0)) throw r.error("t1", "must be greater than t0");
    f = type == "ramp" ? ramp(t0, t1) : smooth_ramp(t0, t1);
  } else if (type == "sine") {
    f = sine(r.get<double>("amplitude", 1.0), r.require<double>("frequency"), r.get<double>("phase", 0.0),
             r.get<double>("offset", 0.0));
  } else if (type == "table") {
    const auto pts = r.require<std::vector<std::vector<double>>>("points");
    std::vector<std::pair<double, double>> p;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      if (pts[i].size() != 2) throw r.error("points", "entry " + std::to_string(i) + " must be [t, value]");
      if (i > 0 && !(pts[i][0] > pts[i - 1][0]))
        throw r.error("points", "times must increase strictly (entry " + std::to_string(i) + ")");
      p.emplace_back(pts[i][0], pts[i][1]);
    }
    if (p.empty()) throw r.error("points", "needs at least one [t, value] pair");
    f = table(std::move(p));
  } else {
    throw r.error(
        "type", "unknown time function '" + type + "' (expected constant, ramp, smooth_ramp, sine or table)");
  }
  r.finish();
  return f;
}

nlohmann::json TimeFunction::to_json() const {
  switch (kind_) {
    case Kind::Constant:
      return {{"type", "constant"}, {"value", a_}};
    case Kind::Ramp:
      return {{"type", "ramp"}, {"t0", a_}, {"t1", b_}};
    case Kind::SmoothRamp:
      return {{"type", "smooth_ramp"}, {"t0", a_}, {"t1", b_}};
    case Kind::Sine:
      return {{"type", "sine"}, {"amplitude", a_}, {"frequency", b_}, {"phase", c_}, {"offset", d_}};
    case Kind::Table: {
      nlohmann::json pts = nlohmann::json::array();
      for (const auto& p : table_) pts.push_back({p.first, p.second});
      return {{"type", "table"}, {"points", pts}};
    }
  }
  return {};
}

}  // namespace tmlab
