// Scalar functions of time that scale prescribed displacements and loads: constant, ramp,
// ramp-and-hold, smooth step, sine and piecewise-linear tables. Value types; evaluated with an
// explicit t (no clocks, no globals).
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <utility>
#include <vector>

namespace tmlab {

class TimeFunction {
 public:
  enum class Kind { Constant, Ramp, SmoothRamp, Sine, Table };

  /// f(t) = 1 for all t.
  static TimeFunction constant(double value = 1.0);
  /// 0 before t0, linear from 0 at t0 to 1 at t1, 1 after (ramp-and-hold).
  static TimeFunction ramp(double t0, double t1);
  /// As ramp, with a C1 cubic (3s^2 - 2s^3) profile: no velocity jump for dynamics.
  static TimeFunction smooth_ramp(double t0, double t1);
  /// offset + amplitude sin(2 pi frequency t + phase).
  static TimeFunction sine(double amplitude, double frequency, double phase = 0.0, double offset = 0.0);
  /// Piecewise linear through (t_i, f_i), constant outside. Times must increase strictly.
  static TimeFunction table(std::vector<std::pair<double, double>> points);

  /// Parses {"type": "constant"|"ramp"|"smooth_ramp"|"sine"|"table", ...}; `where` names the
  /// config key for error messages. Unknown keys are rejected.
  static TimeFunction from_json(const nlohmann::json& j, const std::string& where);
  nlohmann::json to_json() const;

  double operator()(double t) const;
  Kind kind() const { return kind_; }

 private:
  Kind kind_ = Kind::Constant;
  double a_ = 1.0, b_ = 0.0, c_ = 0.0, d_ = 0.0;
  std::vector<std::pair<double, double>> table_;
};

}  // namespace tmlab
