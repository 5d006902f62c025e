// The per-step scalar series a run writes to timeseries.h5 (/series/<name>, with a unit): the
// tensor-mass runner and the deal.II reference record the same names through this one type.
#pragma once

#include <string>
#include <vector>

namespace tmlab {

class SeriesTable {
 public:
  struct Series {
    std::string name, unit;
    std::vector<double> values;
  };

  /// Appends v to the series `name` (created with `unit` on first use).
  void add(const std::string& name, const std::string& unit, double v) {
    for (auto& s : series_)
      if (s.name == name) {
        s.values.push_back(v);
        return;
      }
    series_.push_back({name, unit, {v}});
  }
  /// The last value of `name` (0 when the series does not exist or is empty).
  double last(const std::string& name) const {
    for (const auto& s : series_)
      if (s.name == name && !s.values.empty()) return s.values.back();
    return 0.0;
  }
  const std::vector<Series>& series() const { return series_; }

 private:
  std::vector<Series> series_;
};

}  // namespace tmlab
