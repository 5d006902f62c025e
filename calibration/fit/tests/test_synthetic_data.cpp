// The synthetic data sets against their documented sampling (ramp and hold steps, end times,
// displacements), metadata and placeholder forces; each must pass the tmlab-measured/1 validation.
#include "calibration/fit/synthetic_data.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace tmlab::fit::synthetic {
namespace {

namespace ms = tmlab::measured;

TEST(SyntheticData, IndentationRampAndHold) {
  const ms::DataSet d = indentation_data({1e-3, 2e-3}, 2.0);
  ASSERT_EQ(d.tests.size(), 2u);
  EXPECT_EQ(d.meta.test, ms::TestType::indentation);
  EXPECT_EQ(d.meta.sample.shape, ms::SampleShape::half_space);
  ASSERT_TRUE(d.meta.indenter.has_value());
  EXPECT_EQ(d.meta.indenter->shape, ms::IndenterShape::sphere);
  EXPECT_DOUBLE_EQ(d.meta.indenter->radius_m, 5e-3);
  const ms::Test& t = d.tests[1];
  EXPECT_EQ(t.id, "d2");
  // 0, 0.1, ..., 1.0 on the ramp (11 samples), then 1.25, 1.5, 1.75, 2.0 in the hold.
  ASSERT_EQ(t.time_s.size(), 15u);
  EXPECT_NEAR(t.time_s[5], 0.5, 1e-12);
  EXPECT_NEAR(t.time_s[10], 1.0, 1e-12);
  EXPECT_NEAR(t.time_s[11], 1.25, 1e-12);
  EXPECT_NEAR(t.time_s.back(), 2.0, 1e-12);
  EXPECT_NEAR(t.displacement_m[5], 1e-3, 1e-15);
  EXPECT_DOUBLE_EQ(t.displacement_m[12], 2e-3);
  EXPECT_DOUBLE_EQ(t.displacement_m.back(), 2e-3);
  for (double f : t.force_N) EXPECT_EQ(f, 0.0);
  EXPECT_NO_THROW(ms::validate(d));
}

TEST(SyntheticData, IndentationIntoABondedLayer) {
  const ms::DataSet d = indentation_data({1e-3}, 1.0, 4e-3);
  EXPECT_EQ(d.meta.sample.shape, ms::SampleShape::block);
  EXPECT_EQ(d.meta.sample.bottom, ms::Interface::bonded);
  EXPECT_DOUBLE_EQ(d.meta.sample.size_m[2], 4e-3);
  ASSERT_EQ(d.tests.size(), 1u);
  EXPECT_EQ(d.tests[0].time_s.size(), 11u);
  EXPECT_NO_THROW(ms::validate(d));
}

TEST(SyntheticData, CylinderCompression) {
  const ms::DataSet d = compression_data(0.1, 3);
  EXPECT_EQ(d.meta.test, ms::TestType::unconfined_compression);
  EXPECT_EQ(d.meta.sample.shape, ms::SampleShape::cylinder);
  EXPECT_DOUBLE_EQ(d.meta.sample.radius_m, 0.025);
  EXPECT_DOUBLE_EQ(d.meta.sample.height_m, 0.03);
  ASSERT_EQ(d.tests.size(), 1u);
  const ms::Test& t = d.tests[0];
  EXPECT_EQ(t.time_s, (std::vector<double>{0.0, 0.1, 0.2}));
  ASSERT_EQ(t.displacement_m.size(), 3u);
  EXPECT_DOUBLE_EQ(t.displacement_m[0], 0.0);
  EXPECT_NEAR(t.displacement_m[1], 1.5e-3, 1e-15);
  EXPECT_NEAR(t.displacement_m[2], 3e-3, 1e-15);
  EXPECT_NO_THROW(ms::validate(d));
}

TEST(SyntheticData, BlockCompressionPerStrain) {
  for (bool bonded : {false, true}) {
    const ms::DataSet d = block_compression_data({0.1, 0.2}, 3.0, bonded);
    EXPECT_EQ(d.meta.name, "synthetic_block");
    EXPECT_EQ(d.meta.sample.shape, ms::SampleShape::block);
    const ms::Interface want = bonded ? ms::Interface::bonded : ms::Interface::frictionless;
    EXPECT_EQ(d.meta.sample.bottom, want);
    EXPECT_EQ(d.meta.sample.platens, want);
    EXPECT_DOUBLE_EQ(d.meta.sample.size_m[2], 0.01);
    ASSERT_EQ(d.tests.size(), 2u);
    EXPECT_EQ(d.tests[0].id, "s1");
    EXPECT_EQ(d.tests[1].id, "s2");
    const ms::Test& t = d.tests[1];
    // 0, 0.2, ..., 1.0 on the ramp (6 samples), then 1.5, 2.0, 2.5, 3.0 in the hold.
    ASSERT_EQ(t.time_s.size(), 10u);
    EXPECT_NEAR(t.time_s[5], 1.0, 1e-12);
    EXPECT_NEAR(t.time_s[6], 1.5, 1e-12);
    EXPECT_NEAR(t.time_s.back(), 3.0, 1e-12);
    EXPECT_NEAR(t.displacement_m[1], 0.01 * 0.2 * 0.2, 1e-15);
    EXPECT_DOUBLE_EQ(t.displacement_m.back(), 0.01 * 0.2);
    for (double f : t.force_N) EXPECT_EQ(f, 1.0);
    EXPECT_NO_THROW(ms::validate(d));
  }
}

TEST(SyntheticData, SetForcesFillsTestsInOrder) {
  ms::DataSet d = block_compression_data({0.1, 0.2}, 1.0, false);
  ASSERT_EQ(d.tests[0].force_N.size(), 6u);
  std::vector<double> f;
  for (int i = 0; i < 12; ++i) f.push_back(0.5 * i);
  set_forces(d, f);
  EXPECT_EQ(d.tests[0].force_N.front(), 0.0);
  EXPECT_EQ(d.tests[0].force_N.back(), 2.5);
  EXPECT_EQ(d.tests[1].force_N.front(), 3.0);
  EXPECT_EQ(d.tests[1].force_N.back(), 5.5);
}

}  // namespace
}  // namespace tmlab::fit::synthetic
