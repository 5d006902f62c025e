// Tests of rig_from_data: every field of the rig comes from the data set (test type, indenter,
// sample, supports, history), and missing or rig-less metadata is an error naming the JSON key.
#include "calibration/rigs/rig_from_data.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::rigs {
namespace {

namespace ms = tmlab::measured;

ms::DataSet indentation(double first_depth = 0.0) {
  ms::DataSet d;
  d.meta.name = "ind";
  d.meta.test = ms::TestType::indentation;
  d.meta.indenter = ms::Indenter{ms::IndenterShape::sphere, 0.004, std::nullopt};
  d.meta.sample.shape = ms::SampleShape::block;
  d.meta.sample.size_m = {0.05, 0.04, 0.02};
  d.meta.sample.bottom = ms::Interface::frictionless;
  ms::Test t;
  t.id = "a";
  for (int i = 0; i < 5; ++i) {
    t.time_s.push_back(10.0 + 0.5 * i);
    t.displacement_m.push_back(first_depth + 0.0005 * i);
    t.force_N.push_back(0.1 * i);
  }
  d.tests.push_back(t);
  return d;
}

ms::DataSet compression(ms::TestType type) {
  ms::DataSet d;
  d.meta.name = "cmp";
  d.meta.test = type;
  d.meta.sample.shape = ms::SampleShape::cylinder;
  d.meta.sample.radius_m = 0.025;
  d.meta.sample.height_m = 0.03;
  d.meta.sample.bottom = ms::Interface::bonded;
  d.meta.sample.platens = ms::Interface::bonded;
  const double sign = type == ms::TestType::uniaxial_tension ? -1.0 : 1.0;
  ms::Test t;
  for (int i = 0; i < 4; ++i) {
    t.time_s.push_back(0.1 * i);
    t.displacement_m.push_back(sign * 0.001 * i);
    t.force_N.push_back(sign * i);
  }
  d.tests.push_back(t);
  return d;
}

void expect_error(const ms::DataSet& d, const std::string& part) {
  try {
    rig_from_data(d, 0);
    FAIL() << "no error, expected one containing " << part;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(RigFromData, IndentationBlockTakesEveryFieldFromTheData) {
  const RigSpec s = rig_from_data(indentation(), 0);
  EXPECT_EQ(s.test, RigTest::Indentation);
  EXPECT_EQ(s.shape, SampleShape::Block);
  EXPECT_EQ(s.indenter, IndenterShape::Sphere);
  EXPECT_DOUBLE_EQ(s.indenter_radius, 0.004);
  EXPECT_DOUBLE_EQ(s.size_x, 0.05);
  EXPECT_DOUBLE_EQ(s.size_y, 0.04);
  EXPECT_DOUBLE_EQ(s.height, 0.02);
  EXPECT_EQ(s.bottom, Support::Frictionless);
  // The history starts at the first sample (time 10 s -> 0) and follows the displacement column.
  ASSERT_EQ(s.history.t.size(), 5u);
  EXPECT_DOUBLE_EQ(s.history.t[0], 0.0);
  EXPECT_DOUBLE_EQ(s.history.t[4], 2.0);
  EXPECT_DOUBLE_EQ(s.history.d[4], 0.002);
  EXPECT_DOUBLE_EQ(rig_from_data_time_shift(indentation(), 0), 0.0);
}

TEST(RigFromData, ALoadedFirstSampleGetsARestStateOneIntervalBefore) {
  const ms::DataSet d = indentation(0.0002);
  const RigSpec s = rig_from_data(d, 0);
  ASSERT_EQ(s.history.t.size(), 6u);
  EXPECT_DOUBLE_EQ(s.history.d[0], 0.0);
  EXPECT_DOUBLE_EQ(s.history.t[1], 0.5);
  EXPECT_DOUBLE_EQ(s.history.d[1], 0.0002);
  EXPECT_DOUBLE_EQ(rig_from_data_time_shift(d, 0), 0.5);
}

TEST(RigFromData, AHalfSpaceBecomesALargeBlockOnAFrictionlessSupport) {
  ms::DataSet d = indentation();
  d.meta.sample.shape = ms::SampleShape::half_space;
  d.meta.sample.bottom.reset();
  const RigSpec s = rig_from_data(d, 0);
  const double a = std::sqrt(0.004 * 0.002);
  EXPECT_NEAR(s.height, 20.0 * a, 1e-15);
  EXPECT_NEAR(s.size_x, std::max(0.04, 40.0 * a), 1e-15);
  EXPECT_EQ(s.bottom, Support::Frictionless);
}

TEST(RigFromData, PlatenTestsTakeTheCylinderAndThePlatens) {
  for (const auto type : {ms::TestType::unconfined_compression, ms::TestType::confined_compression,
                          ms::TestType::uniaxial_tension}) {
    const RigSpec s = rig_from_data(compression(type), 0);
    EXPECT_EQ(s.shape, SampleShape::Cylinder);
    EXPECT_DOUBLE_EQ(s.radius, 0.025);
    EXPECT_DOUBLE_EQ(s.height, 0.03);
    EXPECT_EQ(s.platens, Support::Bonded);
    EXPECT_EQ(rig_test_name(s.test), ms::to_string(type));
  }
}

TEST(RigFromData, MissingOrRiglessMetadataNamesTheKey) {
  ms::DataSet d = indentation();
  d.meta.indenter.reset();
  expect_error(d, "ind.json: key 'indenter'");
  d = indentation();
  d.meta.indenter->shape = ms::IndenterShape::cylinder;
  expect_error(d, "key 'indenter.shape'");
  d = indentation();
  d.meta.sample.bottom.reset();
  expect_error(d, "key 'sample.bottom'");
  d = indentation();
  d.meta.sample.shape = ms::SampleShape::cylinder;
  expect_error(d, "key 'sample.shape'");
  d = compression(ms::TestType::unconfined_compression);
  d.meta.sample.platens.reset();
  expect_error(d, "cmp.json: key 'sample.platens'");
  d = compression(ms::TestType::uniaxial_tension);
  d.meta.sample.bottom.reset();
  d.meta.sample.platens = ms::Interface::frictionless;
  expect_error(d, "platens");
  // The platen rigs give both platens one interface: a different bottom is refused, not ignored.
  d = compression(ms::TestType::unconfined_compression);
  d.meta.sample.platens = ms::Interface::frictionless;
  expect_error(d, "cmp.json: key 'sample.bottom': is bonded but sample.platens is frictionless");
  // A displacement reaching the sample height: the rig's check, reported against the test.
  d = indentation();
  d.tests[0].displacement_m.back() = 0.03;
  expect_error(d, "ind.csv: test 'a': no rig for this test");
  EXPECT_THROW(rig_from_data(indentation(), 1), Error);
}

}  // namespace
}  // namespace tmlab::rigs
