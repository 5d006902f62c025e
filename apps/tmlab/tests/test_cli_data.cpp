// `tmlab data convert|show` as a user meets it (issue 14): the phantom CSV converted into
// tmlab-measured/1, its summary and plot, and bad input refused with a non-zero exit naming the file
// (and line and column) with nothing written that looks complete.
#include "cli_test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

using tmlab::cli_test::Result;
using tmlab::cli_test::run_argv;
using tmlab::testing::read_file;

const fs::path kPhantomA1 = tmlab::cli_test::phantom_a1();

class CliData : public tmlab::cli_test::CliTest {
 protected:
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
};

TEST_F(CliData, ConvertThenShowThePhantom) {
  const Result c = tmlab({"data", "convert", kPhantomA1.string(), "--out", (dir_ / "conv").string()});
  ASSERT_EQ(c.status, 0) << c.output;
  const fs::path csv = dir_ / "conv" / "EF10_0T_A1.csv";
  ASSERT_TRUE(fs::exists(csv)) << c.output;
  ASSERT_TRUE(fs::exists(dir_ / "conv" / "EF10_0T_A1.json"));
  EXPECT_NE(c.output.find("cylinder 50 mm diameter x 30 mm high, bottom frictionless, platens frictionless"),
            std::string::npos)
      << c.output;
  EXPECT_NE(c.output.find("1202 samples"), std::string::npos) << c.output;
  const std::string meta = read_file(dir_ / "conv" / "EF10_0T_A1.json");
  EXPECT_NE(meta.find("\"license\": \"CC-BY-4.0\""), std::string::npos) << meta;
  EXPECT_NE(meta.find("Dawood A.B."), std::string::npos) << meta;

  const Result s = tmlab({"data", "show", csv.string(), "--out", (dir_ / "show").string()});
  ASSERT_EQ(s.status, 0) << s.output;
  // One test: 1202 samples over 120.021 s, 0 .. 20.00004 mm, peak 499.323 N at the deepest point.
  EXPECT_NE(s.output.find("unconfined_compression"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("(all)"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("1202"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("120.021"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("0 .. 20"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("499.323"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("licence: CC-BY-4.0"), std::string::npos) << s.output;
  const fs::path png = dir_ / "show" / "EF10_0T_A1.png";
  ASSERT_TRUE(fs::exists(png)) << s.output;
  EXPECT_EQ(read_file(png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_GT(fs::file_size(png), 10000u);
  EXPECT_FALSE(fs::exists(dir_ / "show" / "EF10_0T_A1_plot.json"));  // the plot's input is removed
}

TEST_F(CliData, ShowReportsSeveralTestsAndWhatWasKept) {
  const fs::path csv = write("multi.csv",
                             "test_id,time_s,displacement_m,force_N,stress_kPa\n"
                             "slow,0,0,0,0\nslow,10,0.001,0.5,1\n"
                             "fast,0,0,0,0\nfast,1,0.001,0.8,2\nfast,2,0,-0.1,0\n");
  write("multi.json", R"({"format": "tmlab-measured/1", "name": "multi", "test": "indentation",
    "indenter": {"shape": "flat_punch", "radius_m": 0.002},
    "sample": {"shape": "half_space"}, "operator": "someone"})");
  const Result s = tmlab({"data", "show", csv.string(), "--no-plots"});
  ASSERT_EQ(s.status, 0) << s.output;
  EXPECT_NE(s.output.find("flat_punch indenter r 2 mm, half-space"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("slow"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("fast"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("-0.1 .. 0.8"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("column 'stress_kPa' is not part of tmlab-measured/1: kept, not used"),
            std::string::npos)
      << s.output;
  EXPECT_NE(s.output.find("key 'operator' is not part of"), std::string::npos) << s.output;
}

TEST_F(CliData, BadInputIsNamedAndExitsNonZero) {
  const fs::path nan = write("nan.csv", "time_s,displacement_m,force_N\n0,0,0\n1,0.001,nan\n");
  write("nan.json", R"({"format": "tmlab-measured/1", "name": "nan", "test": "uniaxial_tension",
    "sample": {"shape": "block", "size_m": [0.01, 0.01, 0.05], "bottom": "bonded"}})");
  const Result r = tmlab({"data", "show", nan.string(), "--out", (dir_ / "out").string()});
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find(nan.string() + ":3:9: column 'force_N': NaN"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));

  const fs::path no_json = write("lonely.csv", "time_s,displacement_m,force_N\n0,0,0\n");
  const Result m = tmlab({"data", "show", no_json.string()});
  EXPECT_EQ(m.status, 1) << m.output;
  EXPECT_NE(m.output.find((dir_ / "lonely.json").string() + ": missing"), std::string::npos) << m.output;

  const fs::path other = write("other.csv", "a,b,c\n1,2,3\n");
  const Result c = tmlab({"data", "convert", other.string(), "--out", (dir_ / "conv").string()});
  EXPECT_EQ(c.status, 1) << c.output;
  EXPECT_NE(c.output.find(other.string() + ": not a layout 'tmlab data convert' knows"), std::string::npos)
      << c.output;
  EXPECT_FALSE(fs::exists(dir_ / "conv"));

  const fs::path broken = write("broken.csv",
                                "S\nCompression test;\nCylinder Diameter: 50mm;\nCylinder Height: 30mm;\n"
                                "Time (s),Compression (mm),Load (N)\n0,0,0\n0.1,x,1\n");
  const Result b = tmlab({"data", "convert", broken.string(), "--out", (dir_ / "conv").string()});
  EXPECT_EQ(b.status, 1) << b.output;
  EXPECT_NE(b.output.find(broken.string() + ":7:5: column 'Compression (mm)': 'x' is not a number"),
            std::string::npos)
      << b.output;
  EXPECT_FALSE(fs::exists(dir_ / "conv"));

  const Result missing = tmlab({"data", "show", (dir_ / "nothere.csv").string()});
  EXPECT_EQ(missing.status, 1) << missing.output;
  EXPECT_NE(missing.output.find((dir_ / "nothere.csv").string() + ": no such file"), std::string::npos)
      << missing.output;
}

TEST_F(CliData, UsageErrors) {
  EXPECT_EQ(tmlab({"data"}).status, 2);
  EXPECT_EQ(tmlab({"data", "frob"}).status, 2);
  EXPECT_EQ(tmlab({"data", "convert", kPhantomA1.string()}).status, 2);  // no --out
  const Result p =
      tmlab({"data", "convert", kPhantomA1.string(), "--out", dir_.string(), "--platens", "glued"});
  EXPECT_EQ(p.status, 2);
  EXPECT_NE(p.output.find("--platens must be frictionless or bonded"), std::string::npos) << p.output;
  EXPECT_EQ(tmlab({"data", "show"}).status, 2);
}

}  // namespace
