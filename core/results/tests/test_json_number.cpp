// finite_or_null: finite values stay numbers bit for bit, infinity and NaN become null.
#include "core/results/json_number.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace tmlab {
namespace {

TEST(JsonNumber, FiniteValuesStayNumbers) {
  for (const double v : {0.0, -0.0, 1.5, -2e-300, std::numeric_limits<double>::max(), 0.1}) {
    const nlohmann::json j = finite_or_null(v);
    ASSERT_TRUE(j.is_number_float()) << v;
    EXPECT_EQ(j.get<double>(), v);
    EXPECT_EQ(nlohmann::json::parse(j.dump()).get<double>(), v);  // survives the text round trip
  }
}

TEST(JsonNumber, InfinityAndNaNBecomeNull) {
  for (const double v : {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                         std::numeric_limits<double>::quiet_NaN()})
    EXPECT_TRUE(finite_or_null(v).is_null()) << v;
  EXPECT_EQ(nlohmann::json({{"p", finite_or_null(std::nan(""))}}).dump(), "{\"p\":null}");
}

}  // namespace
}  // namespace tmlab
