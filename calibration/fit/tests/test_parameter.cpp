// Tests of the parameter transforms: round trip, bounds always respected, the derivative against a
// central difference, and the validation messages.
#include "calibration/fit/parameter.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tmlab::fit {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Parameter make(double lo, double hi, double v) {
  Parameter p;
  p.name = "p";
  p.lower = lo;
  p.upper = hi;
  p.value = v;
  p.start_low = v;
  p.start_high = v;
  return p;
}

TEST(Parameter, TransformsRoundTripStayInsideAndHaveTheirDerivative) {
  const Parameter ps[] = {make(-kInf, kInf, 3.0), make(0.0, kInf, 2e4), make(1.0, kInf, 5.0),
                          make(-kInf, 2.0, -7.0), make(0.0, 0.4999, 0.3)};
  const Transform expect[] = {Transform::Identity, Transform::Log, Transform::Log, Transform::Log,
                              Transform::Logit};
  for (int k = 0; k < 5; ++k) {
    const Parameter& p = ps[k];
    EXPECT_EQ(p.transform(), expect[k]);
    const double t = p.to_internal(p.value);
    EXPECT_NEAR(p.to_physical(t), p.value, 1e-12 * std::max(1.0, std::abs(p.value)));
    const double h = 1e-6;
    EXPECT_NEAR(p.derivative(t), (p.to_physical(t + h) - p.to_physical(t - h)) / (2 * h),
                1e-6 * std::max(1.0, std::abs(p.derivative(t))));
    for (const double far : {-50.0, 50.0}) {
      const double x = p.to_physical(far);
      EXPECT_TRUE(x >= p.lower && x <= p.upper) << k;
    }
  }
}

TEST(Parameter, ValidationNamesTheParameter) {
  std::vector<Parameter> v = {make(0.0, 1.0, 0.5)};
  EXPECT_NO_THROW(validate(v));
  v[0].value = 1.5;
  try {
    validate(v);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'p'"), std::string::npos);
  }
  v[0].value = 0.5;
  EXPECT_THROW(fix(v, "q", 0.2), Error);
  EXPECT_THROW(fix(v, "p", 2.0), Error);
  fix(v, "p", 0.25);
  EXPECT_TRUE(v[0].fixed);
  EXPECT_EQ(v[0].value, 0.25);
}

}  // namespace
}  // namespace tmlab::fit
