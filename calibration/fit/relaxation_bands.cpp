// Relaxation-time bands (relaxation_bands.hpp explains why).
#include "calibration/fit/relaxation_bands.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"

#include <cmath>
#include <limits>

namespace tmlab::fit {

RelaxationRange relaxation_range(const measured::DataSet& d, double floor_fraction, double ceiling_factor) {
  const std::string& name = d.meta.name;
  if (!(floor_fraction > 0.0) || !(ceiling_factor > 0.0) || !std::isfinite(floor_fraction) ||
      !std::isfinite(ceiling_factor))
    throw Error(name + ": the relaxation-time floor fraction and ceiling factor must be positive");
  double dt_min = std::numeric_limits<double>::infinity(), duration = 0.0;
  for (std::size_t k = 0; k < d.tests.size(); ++k) {
    const measured::Test& t = d.tests[k];
    if (t.size() < 2)
      throw Error(name + " test " + std::to_string(k + 1) + ": fewer than 2 samples, no sampling interval");
    for (std::size_t i = 1; i < t.size(); ++i) {
      const double dt = t.time_s[i] - t.time_s[i - 1];
      if (dt > 0.0) dt_min = std::min(dt_min, dt);
    }
    duration = std::max(duration, t.time_s.back() - t.time_s.front());
  }
  if (!std::isfinite(dt_min) || !(duration > 0.0))
    throw Error(name + ": the time does not advance, no relaxation time can be bounded");
  RelaxationRange r{floor_fraction * dt_min, ceiling_factor * duration};
  if (!(r.tau_min < r.tau_max))
    throw Error(name + ": the relaxation-time floor " + significant(r.tau_min, 4) +
                " s (floor fraction x shortest sampling interval) is not below the ceiling " +
                significant(r.tau_max, 4) + " s (ceiling factor x duration)");
  return r;
}

void band_relaxation_times(std::vector<Parameter>& params, const ModelSpec& spec, const RelaxationRange& r) {
  const int m = spec.prony_terms;
  if (m == 0) return;
  if (!(r.tau_min > 0.0) || !(r.tau_min < r.tau_max))
    throw Error("relaxation-time bands: need 0 < tau_min < tau_max (got " + significant(r.tau_min, 4) + ", " +
                significant(r.tau_max, 4) + ")");
  const double span = std::log(r.tau_max / r.tau_min) / m;  // band width in ln(tau)
  for (int j = 0; j < m; ++j) {
    Parameter& p = params[index_of(params, "tau" + std::to_string(j + 1))];
    if (p.fixed)
      throw Error("relaxation-time bands: " + p.name +
                  " is fixed; the bands order free relaxation times only (free it or do not use bands)");
    const double lo = r.tau_min * std::exp(span * j),
                 hi = j + 1 == m ? r.tau_max : r.tau_min * std::exp(span * (j + 1));
    p.lower = lo;
    p.upper = hi;
    p.value = std::sqrt(lo * hi);
    p.start_low = lo * std::exp(0.1 * span);
    p.start_high = lo * std::exp(0.9 * span);
  }
  validate(params);
}

std::string bound_reached(const Parameter& p, double x, double fraction) {
  if (p.fixed || !std::isfinite(p.lower) || !std::isfinite(p.upper)) return "";
  const double w = p.upper - p.lower;
  if (x - p.lower <= fraction * w) return "lower";
  if (p.upper - x <= fraction * w) return "upper";
  return "";
}

}  // namespace tmlab::fit
