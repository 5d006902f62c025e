// The sign convention check shared by `tmlab fit` and `tmlab discover` (issue 26): a flipped force
// is refused naming the file, the test, its kind and the convention; noise near zero is not.
#include "calibration/data/sign_convention.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace tmlab::measured {
namespace {

/// One test of `kind`: a ramp to `stroke` (m, signed as the convention wants for the kind) with a
/// force proportional to it, `n` samples.
DataSet ramp(TestType kind, const std::string& id, int n = 50) {
  DataSet d;
  d.meta.name = "ramp";
  d.meta.test = kind;
  const double sign = kind == TestType::uniaxial_tension ? -1.0 : 1.0;
  Test t;
  t.id = id;
  for (int i = 0; i < n; ++i) {
    t.time_s.push_back(0.1 * i);
    t.displacement_m.push_back(sign * 1e-4 * i);
    t.force_N.push_back(sign * 0.5 * i);
  }
  d.tests.push_back(t);
  return d;
}

std::string refusal(const DataSet& d, const std::string& file) {
  try {
    check_force_sign(d, file);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(SignConvention, TheConventionsSignsAreAccepted) {
  for (const TestType kind : {TestType::indentation, TestType::unconfined_compression,
                              TestType::confined_compression, TestType::uniaxial_tension})
    EXPECT_NO_THROW(check_force_sign(ramp(kind, "a"), "a.csv")) << to_string(kind);
}

TEST(SignConvention, ANegativeCompressionForceIsRefusedNamingFileTestKindAndConvention) {
  DataSet d = ramp(TestType::unconfined_compression, "r1");
  for (double& f : d.tests[0].force_N) f = -f;
  const std::string m = refusal(d, "data/flipped.csv");
  ASSERT_FALSE(m.empty());
  EXPECT_NE(m.find("data/flipped.csv"), std::string::npos) << m;
  EXPECT_NE(m.find("test 'r1'"), std::string::npos) << m;
  EXPECT_NE(m.find("unconfined_compression"), std::string::npos) << m;
  EXPECT_NE(m.find("force must be positive in compression"), std::string::npos) << m;
  // Sample 0 is exactly zero: 49 of the 50 are negative.
  EXPECT_NE(m.find("49 of 50 samples are negative"), std::string::npos) << m;
  EXPECT_NE(m.find("flip the sign of force_N"), std::string::npos) << m;
  EXPECT_EQ(m.find("displacement_m"), std::string::npos) << m;  // the displacement is right
}

TEST(SignConvention, APositiveTensionForceIsRefused) {
  DataSet d = ramp(TestType::uniaxial_tension, "");
  for (double& f : d.tests[0].force_N) f = -f;
  const std::string m = refusal(d, "t.csv");
  EXPECT_NE(m.find("test 1 (uniaxial_tension): force must be negative in tension"), std::string::npos) << m;
  EXPECT_NE(m.find("49 of 50 samples are positive"), std::string::npos) << m;
}

TEST(SignConvention, BothColumnsFlippedAskForBothFlippedBack) {
  DataSet d = ramp(TestType::confined_compression, "c");
  for (double& f : d.tests[0].force_N) f = -f;
  for (double& u : d.tests[0].displacement_m) u = -u;
  const std::string m = refusal(d, "");
  EXPECT_NE(m.find("ramp: test 'c'"), std::string::npos) << m;  // no file: the data set's name
  EXPECT_NE(m.find("and of displacement_m"), std::string::npos) << m;
}

TEST(SignConvention, NoiseOfEitherSignNearZeroIsAccepted) {
  // Indentation with a long approach before contact: the force there is load-cell noise of either
  // sign (here 40 of 100 samples negative), then the contact curve, positive.
  DataSet d = ramp(TestType::indentation, "i", 100);
  measured::Test& t = d.tests[0];
  for (int i = 0; i < 100; ++i) {
    const double noise = 0.01 * std::sin(1.7 * i);
    t.force_N[std::size_t(i)] = i < 80 ? noise : 0.5 * (i - 80) + noise;
  }
  std::size_t negative = 0;
  for (const double f : t.force_N) negative += f < 0.0 ? 1 : 0;
  ASSERT_GT(negative, 30u);
  EXPECT_NO_THROW(check_force_sign(d, "noisy.csv"));
  // The same test mirrored is refused.
  for (double& f : t.force_N) f = -f;
  EXPECT_THROW(check_force_sign(d, "noisy.csv"), Error);
}

TEST(SignConvention, EveryTestIsCheckedAndTheCountOfBadOnesGiven) {
  DataSet d = ramp(TestType::unconfined_compression, "a");
  for (const char* id : {"b", "c"}) {
    DataSet e = ramp(TestType::unconfined_compression, id);
    for (double& f : e.tests[0].force_N) f = -f;
    d.tests.push_back(e.tests[0]);
  }
  const std::string m = refusal(d, "x.csv");
  EXPECT_NE(m.find("test 'b'"), std::string::npos) << m;
  EXPECT_NE(m.find("2 of the 3 tests have the wrong sign"), std::string::npos) << m;
}

}  // namespace
}  // namespace tmlab::measured
