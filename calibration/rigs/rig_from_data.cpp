// Measured data -> rig (rig_from_data.hpp has the mapping).
#include "calibration/rigs/rig_from_data.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace tmlab::rigs {

namespace {

namespace ms = tmlab::measured;
using ms::DataSet;

std::string key(const DataSet& d, const std::string& k) { return d.meta.name + ".json: key '" + k + "'"; }

std::string test_where(const DataSet& d, std::size_t k) {
  const ms::Test& t = d.tests[k];
  return d.meta.name + ".csv: test " + (t.id.empty() ? std::to_string(k + 1) : "'" + t.id + "'");
}

Support support(ms::Interface i) {
  return i == ms::Interface::bonded ? Support::Bonded : Support::Frictionless;
}

}  // namespace

double rig_from_data_time_shift(const DataSet& d, std::size_t k) {
  const ms::Test& t = d.tests.at(k);
  if (t.size() < 2) return 0.0;
  return t.displacement_m.front() != 0.0 ? t.time_s[1] - t.time_s[0] : 0.0;
}

RigSpec rig_from_data(const DataSet& d, std::size_t k, const RigFromDataMesh& mesh) {
  if (k >= d.tests.size())
    throw Error(d.meta.name + ": no test " + std::to_string(k + 1) + " (the data set has " +
                std::to_string(d.tests.size()) + ")");
  const ms::Test& t = d.tests[k];
  if (t.size() < 2) throw Error(test_where(d, k) + ": a rig needs at least 2 samples");
  const ms::Metadata& m = d.meta;
  RigSpec s;
  s.name = "data_rig";
  if (mesh.contact_cells > 0) {
    s.contact_cells = mesh.contact_cells;
  } else {
    s.cells = mesh.cells;
    s.layers = mesh.layers;
    s.grading = mesh.grading;
  }
  s.steps_per_sample = 1;
  switch (m.test) {
    case ms::TestType::indentation:
      s.test = RigTest::Indentation;
      break;
    case ms::TestType::unconfined_compression:
      s.test = RigTest::UnconfinedCompression;
      break;
    case ms::TestType::confined_compression:
      s.test = RigTest::ConfinedCompression;
      break;
    case ms::TestType::uniaxial_tension:
      s.test = RigTest::UniaxialTension;
      break;
  }

  // The driving history: data time from the first sample, at rest at t = 0.
  const double shift = rig_from_data_time_shift(d, k);
  s.history.t.clear();
  s.history.d.clear();
  if (shift > 0.0) {
    s.history.t.push_back(0.0);
    s.history.d.push_back(0.0);
  }
  for (std::size_t i = 0; i < t.size(); ++i) {
    s.history.t.push_back(t.time_s[i] - t.time_s[0] + shift);
    s.history.d.push_back(t.displacement_m[i]);
  }
  const double dmax = s.history.peak();

  const ms::Sample& sm = m.sample;
  if (m.test == ms::TestType::indentation) {
    if (!m.indenter) throw Error(key(d, "indenter") + ": missing (an indentation test needs its indenter)");
    const ms::Indenter& ind = *m.indenter;
    if (ind.shape == ms::IndenterShape::cylinder)
      throw Error(key(d, "indenter.shape") +
                  ": a cylinder on its side has no rig (sphere and flat_punch have)");
    if (!(ind.radius_m > 0.0)) throw Error(key(d, "indenter.radius_m") + ": must be positive");
    s.indenter =
        ind.shape == ms::IndenterShape::sphere ? rigs::IndenterShape::Sphere : rigs::IndenterShape::FlatPunch;
    s.indenter_radius = ind.radius_m;
    s.shape = rigs::SampleShape::Block;
    if (sm.shape == ms::SampleShape::cylinder) {
      throw Error(key(d, "sample.shape") +
                  ": an indented cylinder has no rig (indentation rigs are blocks; give the sample as a "
                  "block of the same height or as a half_space)");
    } else if (sm.shape == ms::SampleShape::block) {
      s.size_x = sm.size_m[0];
      s.size_y = sm.size_m[1];
      s.height = sm.size_m[2];
      if (!sm.bottom) throw Error(key(d, "sample.bottom") + ": missing (bonded or frictionless support)");
      s.bottom = support(*sm.bottom);
    } else {
      const double a = ind.shape == ms::IndenterShape::sphere ? std::sqrt(ind.radius_m * dmax) : ind.radius_m;
      s.height = 20.0 * a;
      s.size_x = s.size_y = std::max(10.0 * ind.radius_m, 2.0 * s.height);
      s.bottom = Support::Frictionless;
    }
  } else {
    if (sm.shape == ms::SampleShape::half_space)
      throw Error(key(d, "sample.shape") + ": a " + to_string(m.test) +
                  " test needs a finite sample (block or cylinder), not a half_space");
    if (!sm.platens) throw Error(key(d, "sample.platens") + ": missing (bonded or frictionless platens)");
    s.platens = support(*sm.platens);
    if (sm.bottom && *sm.bottom != *sm.platens)
      throw Error(key(d, "sample.bottom") + ": is " + to_string(*sm.bottom) + " but sample.platens is " +
                  to_string(*sm.platens) + ": the platen rigs give both platens one interface (omit " +
                  "'bottom' or make it equal to 'platens')");
    if (sm.shape == ms::SampleShape::cylinder) {
      s.shape = rigs::SampleShape::Cylinder;
      s.radius = sm.radius_m;
      s.height = sm.height_m;
    } else {
      s.shape = rigs::SampleShape::Block;
      s.size_x = sm.size_m[0];
      s.size_y = sm.size_m[1];
      s.height = sm.size_m[2];
    }
  }
  // The rig's own checks (a depth beyond the sample, an indenter wider than the top face, pushing
  // and pulling mixed ...), reported against the data.
  try {
    validate(s);
  } catch (const Error& e) {
    throw Error(test_where(d, k) + ": no rig for this test: " + e.what());
  }
  return s;
}

}  // namespace tmlab::rigs
