// Time functions: values of each kind, and strict reading from JSON.
#include "core/base/error.hpp"
#include "core/config/time_function.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace tmlab {
namespace {

TEST(TimeFunction, ValuesAndErrors) {
  EXPECT_DOUBLE_EQ(TimeFunction::ramp(1, 3)(2.0), 0.5);
  EXPECT_DOUBLE_EQ(TimeFunction::ramp(1, 3)(5.0), 1.0);
  EXPECT_DOUBLE_EQ(TimeFunction::smooth_ramp(0, 1)(0.5), 0.5);
  EXPECT_DOUBLE_EQ(TimeFunction::table({{0, 0}, {1, 2}, {2, 0}})(1.5), 1.0);
  EXPECT_THROW(TimeFunction::ramp(1, 1), Error);
  EXPECT_THROW(TimeFunction::from_json(nlohmann::json{{"type", "ramp"}, {"t1", 1.0}, {"bogus", 1}}, "f"),
               Error);
  EXPECT_THROW(TimeFunction::from_json(nlohmann::json{{"type", "nope"}}, "f"), Error);
  const auto f = TimeFunction::from_json(nlohmann::json{{"type", "sine"}, {"frequency", 2.0}}, "f");
  EXPECT_NEAR(f(0.125), 1.0, 1e-15);
}

TEST(TimeFunction, JsonRoundTrip) {
  for (const TimeFunction& f :
       {TimeFunction::constant(2.0), TimeFunction::ramp(0.5, 1.5), TimeFunction::smooth_ramp(0.0, 1.0),
        TimeFunction::sine(2.0, 3.0, 0.1, 0.5), TimeFunction::table({{0, 0}, {1, 2}, {2, 0}})}) {
    const TimeFunction g = TimeFunction::from_json(f.to_json(), "f");
    for (double t : {-1.0, 0.0, 0.3, 0.5, 1.0, 1.7, 2.5})
      EXPECT_EQ(g(t), f(t)) << f.to_json().dump() << " at " << t;
  }
}

}  // namespace
}  // namespace tmlab
