// Synthetic data sets: see synthetic_data.hpp.
#include "calibration/fit/synthetic_data.hpp"

#include <algorithm>
#include <optional>
#include <string>

namespace tmlab::fit::synthetic {

measured::DataSet indentation_data(const std::vector<double>& depths, double t_end, double thickness) {
  measured::DataSet d;
  d.meta.name = "synthetic_indentation";
  d.meta.test = measured::TestType::indentation;
  d.meta.indenter = measured::Indenter{measured::IndenterShape::sphere, 5e-3, std::nullopt};
  if (thickness > 0.0) {
    d.meta.sample.shape = measured::SampleShape::block;
    d.meta.sample.size_m = {0.1, 0.1, thickness};
    d.meta.sample.bottom = measured::Interface::bonded;
  } else {
    d.meta.sample.shape = measured::SampleShape::half_space;
  }
  for (std::size_t k = 0; k < depths.size(); ++k) {
    measured::Test t;
    t.id = "d" + std::to_string(k + 1);
    for (double s = 0.0; s <= t_end + 1e-9; s += (s < 1.0 - 1e-9 ? 0.1 : 0.25)) {
      t.time_s.push_back(s);
      t.displacement_m.push_back(depths[k] * std::min(s, 1.0));
      t.force_N.push_back(0.0);
    }
    d.tests.push_back(t);
  }
  return d;
}

measured::DataSet compression_data(double strain, int n) {
  measured::DataSet d;
  d.meta.name = "synthetic_compression";
  d.meta.test = measured::TestType::unconfined_compression;
  d.meta.sample.shape = measured::SampleShape::cylinder;
  d.meta.sample.radius_m = 0.025;
  d.meta.sample.height_m = 0.03;
  d.meta.sample.bottom = measured::Interface::frictionless;
  d.meta.sample.platens = measured::Interface::frictionless;
  measured::Test t;
  for (int i = 0; i < n; ++i) {
    t.time_s.push_back(0.1 * i);
    t.displacement_m.push_back(0.03 * strain * i / (n - 1));
    t.force_N.push_back(0.0);
  }
  d.tests.push_back(t);
  return d;
}

measured::DataSet block_compression_data(const std::vector<double>& strains, double t_end, bool bonded) {
  measured::DataSet d;
  d.meta.name = "synthetic_block";
  d.meta.test = measured::TestType::unconfined_compression;
  d.meta.sample.shape = measured::SampleShape::block;
  d.meta.sample.size_m = {0.02, 0.02, 0.01};
  d.meta.sample.bottom = bonded ? measured::Interface::bonded : measured::Interface::frictionless;
  d.meta.sample.platens = d.meta.sample.bottom;
  for (std::size_t k = 0; k < strains.size(); ++k) {
    measured::Test t;
    t.id = "s" + std::to_string(k + 1);
    for (double s = 0.0; s <= t_end + 1e-9; s += (s < 1.0 - 1e-9 ? 0.2 : 0.5)) {
      t.time_s.push_back(s);
      t.displacement_m.push_back(0.01 * strains[k] * std::min(s, 1.0));
      t.force_N.push_back(1.0);
    }
    d.tests.push_back(t);
  }
  return d;
}

void set_forces(measured::DataSet& d, const std::vector<double>& force) {
  std::size_t i = 0;
  for (auto& t : d.tests)
    for (double& f : t.force_N) f = force[i++];
}

}  // namespace tmlab::fit::synthetic
