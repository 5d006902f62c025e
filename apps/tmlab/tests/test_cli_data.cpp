// `tmlab data convert|show` as a user meets it (issue 14): the phantom CSV converted into
// tmlab-measured/1, its summary and plot, and bad input refused with a non-zero exit naming the file
// (and line and column) with nothing written that looks complete.
#include "cli_test_support.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

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

// --- issue 26 ------------------------------------------------------------------------------------

TEST_F(CliData, ConvertNeverWritesOverItsInput) {
  fs::create_directories(dir_ / "raw");
  const fs::path raw = dir_ / "raw" / "EF10_0T_A1.csv";
  fs::copy_file(kPhantomA1, raw);
  const std::string before = read_file(raw);
  fs::create_directory_symlink(dir_ / "raw", dir_ / "link");
  for (const fs::path& out : {dir_ / "raw", dir_ / "link"})
    for (const bool overwrite : {false, true}) {
      std::vector<std::string> args = {"data", "convert", raw.string(), "--out", out.string()};
      if (overwrite) args.push_back("--overwrite");
      const Result r = tmlab(args);
      EXPECT_EQ(r.status, 1) << r.output;
      EXPECT_NE(r.output.find((out / "EF10_0T_A1.csv").string() + ": is the input " + raw.string()),
                std::string::npos)
          << r.output;
    }
  EXPECT_EQ(read_file(raw), before);
  EXPECT_FALSE(fs::exists(dir_ / "raw" / "EF10_0T_A1.json"));
}

TEST_F(CliData, ConvertReplacesNoFileUnlessAsked) {
  fs::create_directories(dir_ / "out");
  write("out/EF10_0T_A1.json", "my notes");
  const Result r = tmlab({"data", "convert", kPhantomA1.string(), "--out", (dir_ / "out").string()});
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find((dir_ / "out" / "EF10_0T_A1.json").string() +
                          ": exists already; nothing was written (give --overwrite to replace it"),
            std::string::npos)
      << r.output;
  // Both files are checked first: the CSV was not written either.
  EXPECT_FALSE(fs::exists(dir_ / "out" / "EF10_0T_A1.csv"));
  EXPECT_EQ(read_file(dir_ / "out" / "EF10_0T_A1.json"), "my notes");
  const Result o =
      tmlab({"data", "convert", kPhantomA1.string(), "--out", (dir_ / "out").string(), "--overwrite"});
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_NE(read_file(dir_ / "out" / "EF10_0T_A1.json").find("tmlab-measured/1"), std::string::npos);
  // A second conversion into the same folder is refused again (the files are there now).
  EXPECT_EQ(tmlab({"data", "convert", kPhantomA1.string(), "--out", (dir_ / "out").string()}).status, 1);
}

TEST_F(CliData, ShowReplacesNoPlotUnlessAskedAndKeepsItsTemporaryOutOfTheFolder) {
  ASSERT_EQ(tmlab({"data", "convert", kPhantomA1.string(), "--out", (dir_ / "conv").string()}).status, 0);
  const fs::path csv = dir_ / "conv" / "EF10_0T_A1.csv";
  fs::create_directories(dir_ / "mine");
  write("mine/EF10_0T_A1.png", "my picture");
  write("mine/EF10_0T_A1_plot.json", "my plot settings");
  const Result r = tmlab({"data", "show", csv.string(), "--out", (dir_ / "mine").string()});
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find((dir_ / "mine" / "EF10_0T_A1.png").string() + ": exists already"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("unconfined_compression"), std::string::npos) << r.output;  // refused first
  EXPECT_EQ(read_file(dir_ / "mine" / "EF10_0T_A1.png"), "my picture");
  const Result o = tmlab({"data", "show", csv.string(), "--out", (dir_ / "mine").string(), "--overwrite"});
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_EQ(read_file(dir_ / "mine" / "EF10_0T_A1.png").substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // The plot's input went to a temporary directory of its own: the user's file of that name is intact.
  EXPECT_EQ(read_file(dir_ / "mine" / "EF10_0T_A1_plot.json"), "my plot settings");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir_ / "mine")) names.push_back(e.path().filename().string());
  EXPECT_EQ(names.size(), 2u);  // no temporary left behind
}

TEST_F(CliData, DirectoriesAndFifosAreNamedAndNeverBlock) {
  fs::create_directories(dir_ / "folder.csv");
  ASSERT_EQ(::mkfifo((dir_ / "pipe.csv").c_str(), 0600), 0);
  for (const char* sub : {"show", "convert"}) {
    const Result d = tmlab({"data", sub, (dir_ / "folder.csv").string(), "--out", (dir_ / "o").string()});
    EXPECT_EQ(d.status, 1) << d.output;
    EXPECT_NE(d.output.find((dir_ / "folder.csv").string() + ": is a directory, not a file"),
              std::string::npos)
        << sub << ": " << d.output;
    // With no writer, opening the FIFO for reading would wait for ever.
    const Result f = tmlab({"data", sub, (dir_ / "pipe.csv").string(), "--out", (dir_ / "o").string()});
    EXPECT_EQ(f.status, 1) << f.output;
    EXPECT_NE(f.output.find((dir_ / "pipe.csv").string() + ": is not a regular file (a FIFO)"),
              std::string::npos)
        << sub << ": " << f.output;
  }
  EXPECT_FALSE(fs::exists(dir_ / "o"));
}

TEST_F(CliData, ConvertRefusesACompressionBeyondTheHeightAndASingleSample) {
  const std::string header =
      "S\nCompression test;\nCylinder Diameter: 50mm;\nCylinder Height: 30mm;\n"
      "Time (s),Compression (mm),Load (N)\n";
  const fs::path deep = write("deep.csv", header + "0,0,0\n1,35,10\n");
  const Result r = tmlab({"data", "convert", deep.string(), "--out", (dir_ / "conv").string()});
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find(deep.string() + ":7:3: column 'Compression (mm)': the compression reaches 35 mm, "
                                          "not less than the height 30 mm"),
            std::string::npos)
      << r.output;
  const fs::path one = write("one.csv", header + "0,0.1,1\n");
  const Result o = tmlab({"data", "convert", one.string(), "--out", (dir_ / "conv").string()});
  EXPECT_EQ(o.status, 1) << o.output;
  EXPECT_NE(o.output.find(one.string() + ":6:1: one sample only"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir_ / "conv"));
}

TEST_F(CliData, DeeplyNestedMetadataFailsNamingWhere) {
  const fs::path csv = write("deep.csv", "time_s,displacement_m,force_N\n0,0,0\n1,0.001,1\n");
  write("deep.json", "{\"format\": \"tmlab-measured/1\", \"x\": " + std::string(100000, '[') +
                         std::string(100000, ']') + "}");
  const Result r = tmlab({"data", "show", csv.string(), "--no-plots"});
  EXPECT_EQ(r.status, 1) << r.output.substr(0, 400);
  EXPECT_NE(r.output.find((dir_ / "deep.json").string() + ":1:100: nested deeper than 64 levels"),
            std::string::npos)
      << r.output.substr(0, 400);
}

TEST_F(CliData, APointWithoutLeadingDigitsIsNotANumber) {
  const fs::path csv = write("plus.csv", "time_s,displacement_m,force_N\n0,0,0\n1,0.001,+.5\n");
  write("plus.json", R"({"format": "tmlab-measured/1", "name": "plus", "test": "indentation",
    "indenter": {"shape": "flat_punch", "radius_m": 0.002}, "sample": {"shape": "half_space"}})");
  const Result r = tmlab({"data", "show", csv.string(), "--no-plots"});
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find(csv.string() + ":3:9: column 'force_N': '+.5' is not a number"), std::string::npos)
      << r.output;
}

TEST_F(CliData, ControlCharactersInMessagesAreShownEscaped) {
  const std::string json = R"({"format": "tmlab-measured/1", "name": "c", "test": "indentation",
    "indenter": {"shape": "flat_punch", "radius_m": 0.002}, "sample": {"shape": "half_space"}})";
  // A NUL and an ANSI colour sequence in header names: neither cuts nor colours the message.
  const fs::path nul = write("c.csv", std::string("time_s,displacement_m,force_N,x\0y_s\n0,0,0,0\n", 44));
  write("c.json", json);
  const Result n = tmlab({"data", "show", nul.string(), "--no-plots"});
  EXPECT_EQ(n.status, 1) << n.output;
  EXPECT_NE(n.output.find(nul.string() + ":1:31: column name 'x\\x00y_s' is not a tmlab-measured/1 name"),
            std::string::npos)
      << n.output;
  const fs::path esc = write("e.csv", "time_s,displacement_m,force_N,\x1b[31mred_s\n0,0,0,0\n");
  write("e.json", json);
  const Result e = tmlab({"data", "show", esc.string(), "--no-plots"});
  EXPECT_EQ(e.status, 1) << e.output;
  EXPECT_NE(e.output.find("column name '\\x1b[31mred_s'"), std::string::npos) << e.output;
  EXPECT_EQ(e.output.find('\x1b'), std::string::npos) << e.output;
  // The last defence in main(): a message from elsewhere (here the JSON parser's duplicate-key
  // guard) that quotes a key with ESC and a carriage return is escaped before it is printed.
  const fs::path dup = write("d.csv", "time_s,displacement_m,force_N\n0,0,0\n");
  write("d.json", R"({"format": "tmlab-measured/1", "k\u001b[2J\r": 1, "k\u001b[2J\r": 2})");
  const Result d = tmlab({"data", "show", dup.string(), "--no-plots"});
  EXPECT_EQ(d.status, 1) << d.output;
  EXPECT_NE(d.output.find("key 'k\\x1b[2J\\x0d' is given twice"), std::string::npos) << d.output;
  EXPECT_EQ(d.output.find('\x1b'), std::string::npos) << d.output;
  EXPECT_EQ(d.output.find('\r'), std::string::npos) << d.output;
}

}  // namespace
