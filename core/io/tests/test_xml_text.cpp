// xml_escape, base64_encode (RFC 4648 test vectors, every byte value) and format_double (shortest
// text that reads back exactly).
#include "core/io/xml_text.hpp"

#include "core/io/tests/xml_mini.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace tmlab {
namespace {

TEST(XmlText, Base64MatchesRfc4648Vectors) {
  const std::vector<std::pair<std::string, std::string>> cases = {{"", ""},
                                                                  {"f", "Zg=="},
                                                                  {"fo", "Zm8="},
                                                                  {"foo", "Zm9v"},
                                                                  {"foob", "Zm9vYg=="},
                                                                  {"fooba", "Zm9vYmE="},
                                                                  {"foobar", "Zm9vYmFy"}};
  for (const auto& [in, out] : cases) {
    EXPECT_EQ(base64_encode(in.data(), in.size()), out);
    const auto back = test::base64_decode(out);
    EXPECT_EQ(std::string(back.begin(), back.end()), in);
  }
}

TEST(XmlText, Base64OfEveryByteValue) {
  // High bytes must not be sign-extended: 0xff 0x00 0x80 is "/wCA"; all 256 values round-trip.
  const unsigned char high[] = {0xff, 0x00, 0x80};
  EXPECT_EQ(base64_encode(high, sizeof high), "/wCA");
  std::vector<unsigned char> all(256);
  for (int i = 0; i < 256; ++i) all[static_cast<std::size_t>(i)] = static_cast<unsigned char>(i);
  const std::string text = base64_encode(all.data(), all.size());
  EXPECT_EQ(text.size(), 4u * ((256 + 2) / 3));
  EXPECT_EQ(text.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/="),
            std::string::npos);
  const auto back = test::base64_decode(text);
  EXPECT_EQ(std::vector<unsigned char>(back.begin(), back.end()), all);
}

TEST(XmlText, EscapesTheFiveXmlCharactersOnly) {
  EXPECT_EQ(xml_escape("a<b & \"c\">'"), "a&lt;b &amp; &quot;c&quot;&gt;&apos;");
  EXPECT_EQ(xml_escape("stress [Pa], 50% / t=1e-3"), "stress [Pa], 50% / t=1e-3");
  EXPECT_EQ(xml_escape("&amp;"), "&amp;amp;");  // already-escaped text is escaped again
  EXPECT_EQ(xml_escape(""), "");
}

TEST(XmlText, FormatDoubleIsShortestAndExact) {
  EXPECT_EQ(format_double(0.1), "0.1");
  EXPECT_EQ(format_double(-2.5), "-2.5");
  EXPECT_EQ(format_double(0.0), "0");
  EXPECT_EQ(format_double(1e-300), "1e-300");
  EXPECT_EQ(format_double(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(format_double(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(format_double(std::numeric_limits<double>::quiet_NaN()), "nan");
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 300);
  for (int i = 0; i < 2000; ++i) {
    const double x = std::ldexp(mantissa(rng), exponent(rng));
    EXPECT_EQ(std::strtod(format_double(x).c_str(), nullptr), x) << format_double(x);
  }
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(std::strtod(format_double(tiny).c_str(), nullptr), tiny) << format_double(tiny);
}

}  // namespace
}  // namespace tmlab
