#include "calibration/fit/parameter.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"

#include <cmath>

namespace tmlab::fit {

Transform Parameter::transform() const {
  const bool lo = std::isfinite(lower), hi = std::isfinite(upper);
  if (lo && hi) return Transform::Logit;
  if (lo || hi) return Transform::Log;
  return Transform::Identity;
}

double Parameter::to_internal(double x) const {
  switch (transform()) {
    case Transform::Identity:
      return x;
    case Transform::Log:
      return std::isfinite(lower) ? std::log(x - lower) : std::log(upper - x);
    case Transform::Logit: {
      const double u = (x - lower) / (upper - lower);
      return std::log(u / (1.0 - u));
    }
  }
  return x;
}

double Parameter::to_physical(double t) const {
  switch (transform()) {
    case Transform::Identity:
      return t;
    case Transform::Log:
      return std::isfinite(lower) ? lower + std::exp(t) : upper - std::exp(t);
    case Transform::Logit:
      // 1 / (1 + exp(-t)) written to stay finite for large |t|.
      return t >= 0 ? lower + (upper - lower) / (1.0 + std::exp(-t))
                    : lower + (upper - lower) * std::exp(t) / (1.0 + std::exp(t));
  }
  return t;
}

double Parameter::derivative(double t) const {
  switch (transform()) {
    case Transform::Identity:
      return 1.0;
    case Transform::Log:
      return std::isfinite(lower) ? std::exp(t) : -std::exp(t);
    case Transform::Logit: {
      const double e = std::exp(-std::abs(t));
      return (upper - lower) * e / ((1.0 + e) * (1.0 + e));
    }
  }
  return 1.0;
}

std::string to_string(Transform t) {
  switch (t) {
    case Transform::Identity:
      return "identity";
    case Transform::Log:
      return "log";
    case Transform::Logit:
      return "logit";
  }
  return "?";
}

void validate(const std::vector<Parameter>& params) {
  for (std::size_t i = 0; i < params.size(); ++i) {
    const Parameter& p = params[i];
    const std::string where = "fit parameter '" + p.name + "'";
    for (std::size_t j = 0; j < i; ++j)
      if (params[j].name == p.name) throw Error(where + " appears twice");
    if (!(p.lower < p.upper)) throw Error(where + ": lower bound must be below the upper bound");
    auto inside = [&](double x) { return std::isfinite(x) && x > p.lower && x < p.upper; };
    if (!inside(p.value))
      throw Error(where + ": value " + significant(p.value, 6) + " is not strictly inside (" +
                  significant(p.lower, 6) + ", " + significant(p.upper, 6) + ")");
    if (!p.fixed && (!inside(p.start_low) || !inside(p.start_high) || !(p.start_low <= p.start_high)))
      throw Error(where + ": the start range [" + significant(p.start_low, 6) + ", " +
                  significant(p.start_high, 6) + "] must lie inside the bounds");
  }
}

std::size_t index_of(const std::vector<Parameter>& params, const std::string& name) {
  std::string names;
  for (std::size_t i = 0; i < params.size(); ++i) {
    if (params[i].name == name) return i;
    names += (i ? ", " : "") + params[i].name;
  }
  throw Error("no fit parameter named '" + name + "' (this model has: " + names + ")");
}

void fix(std::vector<Parameter>& params, const std::string& name, double value) {
  Parameter& p = params[index_of(params, name)];
  if (!(std::isfinite(value) && value > p.lower && value < p.upper))
    throw Error("--fix " + name + "=" + significant(value, 6) + ": outside the bounds (" +
                significant(p.lower, 6) + ", " + significant(p.upper, 6) + ") of '" + name + "'");
  p.value = value;
  p.fixed = true;
}

}  // namespace tmlab::fit
