// The number formats: exactly printf's, which the reports and messages were written with.
#include "core/base/format.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab {
namespace {

TEST(Format, PrintfStyles) {
  EXPECT_EQ(significant(0.499, 3), "0.499");
  EXPECT_EQ(significant(2.0, 3), "2");
  EXPECT_EQ(significant(1.23456789e-9, 6), "1.23457e-09");
  EXPECT_EQ(scientific(3.2e-9, 3), "3.200e-09");
  EXPECT_EQ(scientific(-1.0, 1), "-1.0e+00");
  EXPECT_EQ(fixed_point(1.966, 2), "1.97");
  EXPECT_EQ(fixed_point(12.5, 0), "12");  // round half to even, as printf
  EXPECT_EQ(significant(std::nan(""), 3), "nan");
  EXPECT_EQ(scientific(-INFINITY, 3), "-inf");
}

TEST(Format, ChoiceList) {
  EXPECT_EQ(choice_list({"a"}), "'a'");
  EXPECT_EQ(choice_list({"a", "b"}), "'a' or 'b'");
  EXPECT_EQ(choice_list({"a", "b", "c"}, "\""), "\"a\", \"b\" or \"c\"");
  EXPECT_EQ(choice_list({"seed", "objective"}, ""), "seed or objective");
  EXPECT_EQ(choice_list({}), "");
}

}  // namespace
}  // namespace tmlab
