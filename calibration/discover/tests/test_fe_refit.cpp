// The FE-rig refit's data handling (fe_refit.hpp), without running the FE rig: indentation data are
// cut before the first unloading sample, decimated to about the requested size with the indices
// of the kept samples, and a model with an effect the rig does not model is reported, not refitted.
#include "calibration/discover/fe_refit.hpp"

#include <gtest/gtest.h>

namespace tmlab::discover {
namespace {

measured::DataSet sphere_load_hold_unload() {
  measured::DataSet d;
  d.meta.name = "s";
  d.meta.test = measured::TestType::indentation;
  d.meta.indenter = measured::Indenter{measured::IndenterShape::sphere, 0.0025, std::nullopt};
  d.meta.sample.shape = measured::SampleShape::half_space;
  measured::Test t;
  for (int i = 0; i <= 300; ++i) {
    const double tt = 0.1 * i,
                 dd = tt <= 10.0 ? 1e-5 * tt : (tt <= 20.0 ? 1e-4 : std::max(0.0, 1e-4 - 1e-5 * (tt - 20.0)));
    t.time_s.push_back(tt);
    t.displacement_m.push_back(dd);
    t.force_N.push_back(1e-3 * dd / 1e-4 + 1e-6);
  }
  d.tests.push_back(t);
  return d;
}

TEST(FeRefit, IndentationDataEndBeforeUnloadingAndKeepTheirIndices) {
  const measured::DataSet d = sphere_load_hold_unload();
  const Prepared p = prepare(d, 100000);
  std::vector<std::vector<std::size_t>> kept;
  const measured::DataSet all = decimated_data(d, p, true, 100000, &kept);
  ASSERT_EQ(all.tests.size(), 1u);
  EXPECT_EQ(all.tests[0].size(), 201u);  // t = 0 .. 20 s: loading and hold
  EXPECT_EQ(kept[0].back(), 200u);
  const measured::DataSet few = decimated_data(d, p, true, 50, &kept);
  EXPECT_LE(few.tests[0].size(), 52u);
  for (std::size_t i = 0; i < few.tests[0].size(); ++i)
    EXPECT_EQ(few.tests[0].time_s[i], p.series[0].t[kept[0][i]]);
  EXPECT_EQ(decimated_data(d, p, false, 100000, nullptr).tests[0].size(), 301u);
}

TEST(FeRefit, AModelWithAnEffectTheRigLacksIsNotRefitted) {
  const measured::DataSet d = sphere_load_hold_unload();
  Report r;
  r.data = prepare(d, 100000);
  r.baseline.structure.effects = {"force_drift"};
  r.final.structure.effects = {"force_drift", "contact_offset"};
  r.baseline.prediction = r.final.prediction = {std::vector<double>(r.data.series[0].t.size(), 0.0)};
  const auto v = fe_rig_refit(d, r, Options{}, FeRefitOptions{});
  ASSERT_EQ(v.size(), 2u);
  for (const auto& f : v) {
    EXPECT_FALSE(f.done);
    EXPECT_NE(f.why_not.find("force_drift"), std::string::npos) << f.why_not;
  }
}

}  // namespace
}  // namespace tmlab::discover
