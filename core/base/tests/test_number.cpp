// The one number grammar users type: what it takes, what it refuses and how it says so.
#include "core/base/number.hpp"

#include "core/base/format.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>

namespace tmlab {
namespace {

TEST(Number, DecimalsUnderTheGrammar) {
  double v = 0.0;
  std::string why;
  EXPECT_TRUE(parse_decimal("1.5", v, why));
  EXPECT_EQ(v, 1.5);
  EXPECT_TRUE(parse_decimal("-1.5e-3", v, why));
  EXPECT_EQ(v, -1.5e-3);
  EXPECT_TRUE(parse_decimal("+7", v, why));
  EXPECT_EQ(v, 7.0);
  EXPECT_TRUE(parse_decimal("2E+4", v, why));
  EXPECT_EQ(v, 2e4);
  EXPECT_TRUE(parse_decimal("0.0", v, why));
  EXPECT_EQ(v, 0.0);
}

TEST(Number, EverythingElseIsRefusedWithAReason) {
  double v = 0.0;
  for (const char* bad : {"", "+.5", ".5", "7.", " 1.9e4", "1.9e4 ", "0x4A3B", "0x0.8p-1", "1e", "1e+", "--1",
                          "+", "nan", "-inf", "Infinity", "1,5", "1.5.2", "abc", "1e999"}) {
    std::string why;
    EXPECT_FALSE(parse_decimal(bad, v, why)) << bad;
    EXPECT_FALSE(why.empty()) << bad;
  }
  std::string why;
  EXPECT_FALSE(parse_decimal("1e999", v, why));
  EXPECT_NE(why.find("out of the range"), std::string::npos) << why;
}

TEST(Number, WholeNumbersWithARange) {
  std::int64_t n = 0;
  std::string why;
  EXPECT_TRUE(parse_whole("12", 1, 100, n, why));
  EXPECT_EQ(n, 12);
  EXPECT_TRUE(parse_whole("+3", 1, 100, n, why));
  EXPECT_EQ(n, 3);
  EXPECT_TRUE(parse_whole("-3", -5, 5, n, why));
  EXPECT_EQ(n, -3);
  EXPECT_FALSE(parse_whole("0", 1, 100, n, why));
  EXPECT_NE(why.find("outside 1 .. 100"), std::string::npos) << why;
  EXPECT_FALSE(parse_whole("1e8", 1, 100, n, why));
  EXPECT_NE(why.find("not a whole number"), std::string::npos) << why;
  EXPECT_FALSE(parse_whole("2.5", 1, 100, n, why));
  EXPECT_FALSE(parse_whole("0x10", 1, 100, n, why));
  EXPECT_FALSE(parse_whole(" 4", 1, 100, n, why));
  EXPECT_FALSE(parse_whole("99999999999999999999999", 1, std::numeric_limits<std::int64_t>::max(), n, why));
  EXPECT_NE(why.find("outside"), std::string::npos) << why;
}

TEST(Number, MessagesShowControlCharactersEscaped) {
  double v = 0.0;
  std::string why;
  const std::string with_nul(
      "1\0"
      "2",
      3);
  EXPECT_FALSE(parse_decimal(with_nul, v, why));
  EXPECT_NE(why.find("1\\x002"), std::string::npos) << why;
  EXPECT_FALSE(parse_decimal("\x1b[31mred", v, why));
  EXPECT_EQ(why.find('\x1b'), std::string::npos) << why;
  EXPECT_NE(why.find("\\x1b[31mred"), std::string::npos) << why;
}

TEST(Format, PrintableEscapesAndCuts) {
  EXPECT_EQ(printable("plain"), "plain");
  EXPECT_EQ(printable(std::string("a\0b", 3)), "a\\x00b");
  EXPECT_EQ(printable("\x1b[2J"), "\\x1b[2J");
  EXPECT_EQ(printable("tab\there"), "tab\\x09here");
  EXPECT_EQ(printable("abcdef", 3), "abc...");
  EXPECT_EQ(printable("\xc3\xa9"), "\xc3\xa9");  // UTF-8 passes
}

}  // namespace
}  // namespace tmlab
