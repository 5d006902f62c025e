// The tmlab-measured/1 reader: every error of the format names the file, line and column; unknown
// columns and keys are kept and reported; what the writer writes reads back bit for bit.
#include "calibration/data/measured_data.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace tmlab::measured;

const char* kIndentationJson = R"({
  "format": "tmlab-measured/1",
  "name": "a",
  "test": "indentation",
  "indenter": { "shape": "sphere", "radius_m": 0.005 },
  "sample": { "shape": "block", "size_m": [0.04, 0.04, 0.02], "bottom": "bonded" },
  "temperature_C": 37,
  "source": "made up for a test",
  "license": "CC0-1.0"
}
)";

class MeasuredData : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tmlab_measured_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }
  /// Writes a.csv and a.json, reads them, and returns the error message ("" when it read).
  std::string error_of(const std::string& csv, const std::string& json = kIndentationJson) const {
    write("a.csv", csv);
    write("a.json", json);
    try {
      read_data_set(dir_ / "a.csv");
    } catch (const tmlab::Error& e) {
      return e.what();
    }
    return "";
  }
  std::string csv_name() const { return (dir_ / "a.csv").string(); }
  std::string json_name() const { return (dir_ / "a.json").string(); }
  /// kIndentationJson with `from` replaced by `to` (which must occur).
  static std::string json_with(const std::string& from, const std::string& to) {
    std::string j = kIndentationJson;
    const std::size_t at = j.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) j.replace(at, from.size(), to);
    return j;
  }
  fs::path dir_;
};

const char* kGoodCsv =
    "# depth 1 mm\n"
    "time_s,displacement_m,force_N\n"
    "0,0,0\n"
    "0.5,0.0005,0.01\n"
    "1,0.001,0.03\n";

TEST_F(MeasuredData, ReadsAValidFileWithItsMetadata) {
  write("a.csv", kGoodCsv);
  write("a.json", kIndentationJson);
  const DataSet d = read_data_set(dir_ / "a.csv");
  EXPECT_EQ(d.meta.name, "a");
  EXPECT_EQ(d.meta.test, TestType::indentation);
  ASSERT_TRUE(d.meta.indenter.has_value());
  EXPECT_EQ(d.meta.indenter->shape, IndenterShape::sphere);
  EXPECT_EQ(d.meta.indenter->radius_m, 0.005);
  EXPECT_EQ(d.meta.sample.shape, SampleShape::block);
  EXPECT_EQ(d.meta.sample.size_m[2], 0.02);
  EXPECT_EQ(d.meta.sample.bottom, Interface::bonded);
  EXPECT_FALSE(d.meta.sample.platens.has_value());
  EXPECT_EQ(d.meta.temperature_C, 37.0);
  ASSERT_EQ(d.tests.size(), 1u);
  EXPECT_EQ(d.tests[0].id, "");
  EXPECT_EQ(d.tests[0].first_line, 3);
  EXPECT_EQ(d.tests[0].size(), 3u);
  EXPECT_EQ(d.tests[0].time_s[1], 0.5);
  EXPECT_EQ(d.tests[0].displacement_m[2], 0.001);
  EXPECT_EQ(d.tests[0].force_N[2], 0.03);
  EXPECT_TRUE(d.notes.empty());
}

TEST_F(MeasuredData, ToleratesBomCrLfBlanksAndCommentLines) {
  write("a.csv",
        "\xEF\xBB\xBFtime_s , displacement_m,force_N\r\n\r\n# a comment\r\n 0 ,0,+1e-3\r\n2,1E-3,-0.5\r\n");
  write("a.json", kIndentationJson);
  const DataSet d = read_data_set(dir_ / "a.csv");
  ASSERT_EQ(d.tests.size(), 1u);
  EXPECT_EQ(d.tests[0].force_N[0], 1e-3);
  EXPECT_EQ(d.tests[0].force_N[1], -0.5);
  EXPECT_EQ(d.tests[0].displacement_m[1], 1e-3);
}

TEST_F(MeasuredData, SeveralTestsAndUnknownColumnsAndKeysAreKeptAndReported) {
  write("a.csv",
        "test_id,time_s,displacement_m,force_N,temperature_C\n"
        "d1,0,0,0,37\n"
        "d1,1,0.001,0.1,37.1\n"
        "d2,0,0,0,36.9\n"
        "d2,2,0.002,0.4,37\n");
  write("a.json",
        json_with("\"license\": \"CC0-1.0\"",
                  "\"license\": \"CC0-1.0\", \"operator\": \"A. N. Other\", \"humidity_percent\": 40"));
  const DataSet d = read_data_set(dir_ / "a.csv");
  ASSERT_EQ(d.tests.size(), 2u);
  EXPECT_EQ(d.tests[0].id, "d1");
  EXPECT_EQ(d.tests[1].id, "d2");
  EXPECT_EQ(d.tests[1].first_line, 4);
  ASSERT_EQ(d.tests[1].extra.size(), 1u);
  EXPECT_EQ(d.tests[1].extra[0].name, "temperature_C");
  EXPECT_EQ(d.tests[1].extra[0].values[0], 36.9);
  ASSERT_EQ(d.meta.extra.size(), 2u);
  ASSERT_EQ(d.notes.size(), 3u);
  std::string all;
  for (const Note& n : d.notes) all += n.where + ": " + n.text + "\n";
  EXPECT_NE(all.find(csv_name() + ":1:39: column 'temperature_C' is not part of tmlab-measured/1"),
            std::string::npos)
      << all;
  EXPECT_NE(all.find("key 'operator' is not part of"), std::string::npos) << all;
  EXPECT_NE(all.find(json_name() + ":9:"), std::string::npos) << all;
}

TEST_F(MeasuredData, WrittenDataSetReadsBackBitForBit) {
  DataSet d;
  d.meta.name = "rt";
  d.meta.test = TestType::unconfined_compression;
  d.meta.sample.shape = SampleShape::cylinder;
  d.meta.sample.radius_m = 0.025;
  d.meta.sample.height_m = 0.03;
  d.meta.sample.bottom = Interface::bonded;
  d.meta.sample.platens = Interface::bonded;
  d.meta.source = "a test";
  d.meta.license = "CC-BY-4.0";
  d.meta.notes = "round trip";
  d.meta.extra.push_back({"sample", "colour", "blue"});
  d.meta.extra.push_back({"", "rate_m_per_s", 1.0 / 6000.0});
  for (int k = 0; k < 2; ++k) {
    tmlab::measured::Test t;
    t.id = "r" + std::to_string(k);
    for (int i = 0; i < 50; ++i) {
      t.time_s.push_back(0.1 * i + 1e-9 * k);
      t.displacement_m.push_back(std::sqrt(2.0) * 1e-4 * i);
      t.force_N.push_back(1.0 / 3.0 * i * i - 1e-300 * k);
    }
    t.extra.push_back({"stress_kPa", t.force_N});
    d.tests.push_back(t);
  }
  const fs::path csv = write_data_set(d, dir_ / "out");
  EXPECT_EQ(csv, dir_ / "out" / "rt.csv");
  const DataSet r = read_data_set(csv);
  EXPECT_EQ(format_metadata(r.meta), format_metadata(d.meta));
  EXPECT_EQ(r.meta.sample.platens, Interface::bonded);
  ASSERT_EQ(r.tests.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(r.tests[k].id, d.tests[k].id);
    EXPECT_EQ(r.tests[k].time_s, d.tests[k].time_s);
    EXPECT_EQ(r.tests[k].displacement_m, d.tests[k].displacement_m);
    EXPECT_EQ(r.tests[k].force_N, d.tests[k].force_N);
    ASSERT_EQ(r.tests[k].extra.size(), 1u);
    EXPECT_EQ(r.tests[k].extra[0].values, d.tests[k].extra[0].values);
  }
  // The unknown key came back inside "sample", and is reported again.
  EXPECT_EQ(r.notes.size(), 3u);
  EXPECT_EQ(format_samples(r), format_samples(d));
}

TEST_F(MeasuredData, WriterRefusesWhatTheReaderWouldRefuse) {
  DataSet d;
  d.meta.name = "bad";
  d.meta.test = TestType::indentation;  // no indenter
  d.meta.sample.shape = SampleShape::half_space;
  d.tests.push_back({"", 0, {0.0, 1.0}, {0.0, 1e-3}, {0.0, 1.0}, {}});
  EXPECT_THROW(write_data_set(d, dir_ / "out"), tmlab::Error);
  d.meta.indenter = Indenter{IndenterShape::flat_punch, 0.002, {}};
  d.tests[0].time_s[1] = 0.0;  // not increasing
  EXPECT_THROW(write_data_set(d, dir_ / "out"), tmlab::Error);
  d.tests[0].time_s[1] = 1.0;
  d.tests[0].force_N[1] = std::nan("");
  EXPECT_THROW(write_data_set(d, dir_ / "out"), tmlab::Error);
  EXPECT_FALSE(fs::exists(dir_ / "out" / "bad.csv"));
  d.tests[0].force_N[1] = 1.0;
  EXPECT_NO_THROW(write_data_set(d, dir_ / "out"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "bad.json"));
}

// --- the errors of issue 14, each naming file, line and column ---------------------------------

TEST_F(MeasuredData, MissingColumnIsNamed) {
  const std::string e = error_of("# comment\ntime_s,displacement_m\n0,0\n");
  EXPECT_NE(e.find(csv_name() + ":2:1: missing column 'force_N'"), std::string::npos) << e;
  const std::string mm = error_of("time_s,displacement_mm,force_N\n0,0,0\n");
  EXPECT_NE(mm.find(csv_name() + ":1:1: missing column 'displacement_m' (found 'displacement_mm': the format "
                                 "wants SI units"),
            std::string::npos)
      << mm;
}

TEST_F(MeasuredData, MissingKeyIsNamed) {
  // No sample: the document (line 1, column 1) is where it is missing.
  const std::string j = json_with(
      "\"sample\": { \"shape\": \"block\", \"size_m\": [0.04, 0.04, 0.02], \"bottom\": \"bonded\" },\n", "");
  const std::string e = error_of(kGoodCsv, j);
  EXPECT_NE(e.find(json_name() + ":1:1: missing key 'sample'"), std::string::npos) << e;
  // No radius: the indenter object (line 5, column 15) is where it is missing.
  const std::string r = error_of(kGoodCsv, json_with(", \"radius_m\": 0.005", ""));
  EXPECT_NE(r.find(json_name() + ":5:15: missing key 'indenter.radius_m' in 'indenter'"), std::string::npos)
      << r;
  const std::string mm = error_of(kGoodCsv, json_with("\"radius_m\": 0.005", "\"radius_mm\": 5"));
  EXPECT_NE(mm.find("missing key 'indenter.radius_m' in 'indenter' (found 'radius_mm'"), std::string::npos)
      << mm;
  const std::string p =
      error_of(kGoodCsv, json_with("\"test\": \"indentation\"", "\"test\": \"confined_compression\""));
  EXPECT_NE(p.find(json_name() + ":5:15: key 'indenter' is only for indentation tests"), std::string::npos)
      << p;
}

TEST_F(MeasuredData, UnitLessNumbersAreErrors) {
  const std::string e = error_of(kGoodCsv, json_with("\"radius_m\": 0.005", "\"radius\": 0.005"));
  EXPECT_NE(e.find(json_name() + ":5:46: key 'indenter.radius' is a unit-less number"), std::string::npos)
      << e;
  const std::string t = error_of(kGoodCsv, json_with("\"temperature_C\": 37", "\"temperature\": 37"));
  EXPECT_NE(t.find(json_name() + ":7:18: key 'temperature' is a unit-less number"), std::string::npos) << t;
  const std::string a = error_of(kGoodCsv, json_with("\"license\"", "\"depths\": [1, 2], \"license\""));
  EXPECT_NE(a.find(json_name() + ":9:13: key 'depths' is a unit-less number"), std::string::npos) << a;
  const std::string c = error_of("time_s,displacement_m,force_N,stiffness\n0,0,0,1\n");
  EXPECT_NE(c.find(csv_name() + ":1:31: column 'stiffness' is a unit-less number"), std::string::npos) << c;
  const std::string u = error_of("time,displacement_m,force_N\n0,0,0\n");
  EXPECT_NE(u.find(csv_name() + ":1:1: column 'time' is a unit-less number"), std::string::npos) << u;
}

TEST_F(MeasuredData, NonIncreasingTimeIsAnError) {
  const std::string e = error_of("time_s,displacement_m,force_N\n0,0,0\n0.5,0,0\n0.5,0,0\n");
  EXPECT_NE(e.find(csv_name() + ":4:1: column 'time_s': time 0.5 does not increase"), std::string::npos) << e;
  // Within a test: a new test may start again at 0; going back inside one may not.
  const std::string t =
      error_of("test_id,time_s,displacement_m,force_N\na,0,0,0\na,1,0,0\nb,0,0,0\nb,  0.9,0,0\nb,0.8,0,0\n");
  EXPECT_NE(t.find(csv_name() + ":6:3: column 'time_s': time 0.8 does not increase"), std::string::npos) << t;
  EXPECT_NE(t.find("in test 'b'"), std::string::npos) << t;
}

TEST_F(MeasuredData, NanAndInfinityAreErrors) {
  const std::string e = error_of("time_s,displacement_m,force_N\n0,0,0\n1,0.001,NaN\n");
  EXPECT_NE(e.find(csv_name() + ":3:9: column 'force_N': NaN is not a measurement"), std::string::npos) << e;
  const std::string i = error_of("time_s,displacement_m,force_N\n0,-inf,0\n");
  EXPECT_NE(i.find(csv_name() + ":2:3: column 'displacement_m': an infinite value"), std::string::npos) << i;
  const std::string big = error_of("time_s,displacement_m,force_N\n0,1e999,0\n");
  EXPECT_NE(big.find(csv_name() + ":2:3: column 'displacement_m': '1e999' is out of the range"),
            std::string::npos)
      << big;
}

TEST_F(MeasuredData, EmptyTestIsAnError) {
  const std::string e = error_of("# nothing measured\ntime_s,displacement_m,force_N\n# still nothing\n");
  EXPECT_NE(e.find(csv_name() + ":3:1: no samples after the header (an empty test)"), std::string::npos) << e;
  const std::string f = error_of("");
  EXPECT_NE(f.find(csv_name() + ":1:1: no header line"), std::string::npos) << f;
  const std::string id = error_of("test_id,time_s,displacement_m,force_N\n,0,0,0\n");
  EXPECT_NE(id.find(csv_name() + ":2:1: column 'test_id': empty test_id"), std::string::npos) << id;
}

TEST_F(MeasuredData, OtherMalformedSamplesAreNamed) {
  const std::string text = error_of("time_s,displacement_m,force_N\n0,zero,0\n");
  EXPECT_NE(text.find(csv_name() + ":2:3: column 'displacement_m': 'zero' is not a number"),
            std::string::npos)
      << text;
  const std::string empty = error_of("time_s,displacement_m,force_N\n0,,0\n");
  EXPECT_NE(empty.find(csv_name() + ":2:3: column 'displacement_m': empty field"), std::string::npos)
      << empty;
  const std::string many = error_of("time_s,displacement_m,force_N\n0,0,0,7\n");
  EXPECT_NE(many.find(csv_name() + ":2:7: 4 fields, but the header (line 1) has 3 columns"),
            std::string::npos)
      << many;
  const std::string few = error_of("time_s,displacement_m,force_N\n0,0\n");
  EXPECT_NE(few.find(csv_name() + ":2:4: 2 fields"), std::string::npos) << few;
  const std::string split = error_of("test_id,time_s,displacement_m,force_N\na,0,0,0\nb,0,0,0\na,1,0,0\n");
  EXPECT_NE(split.find(csv_name() + ":4:1: test 'a' (begun at line 2) continues after test 'b'"),
            std::string::npos)
      << split;
  const std::string dup = error_of("time_s,time_s,displacement_m,force_N\n0,0,0,0\n");
  EXPECT_NE(dup.find(csv_name() + ":1:8: column 'time_s' appears twice"), std::string::npos) << dup;
  const std::string layout = error_of("Time (s),Compression (mm),Load (N)\n0,0,0\n");
  EXPECT_NE(layout.find(csv_name() + ":1:1: column name 'Time (s)' is not a tmlab-measured/1 name"),
            std::string::npos)
      << layout;
}

TEST_F(MeasuredData, MalformedMetadataIsNamed) {
  const std::string f = error_of(kGoodCsv, json_with("tmlab-measured/1", "tmlab-measured/2"));
  EXPECT_NE(f.find(json_name() + ":2:13: key 'format' must be \"tmlab-measured/1\""), std::string::npos) << f;
  const std::string t = error_of(kGoodCsv, json_with("\"indentation\"", "\"poking\""));
  EXPECT_NE(t.find(json_name() + ":4:11: key 'test' must be one of indentation, unconfined_compression"),
            std::string::npos)
      << t;
  const std::string n = error_of(kGoodCsv, json_with("\"name\": \"a\"", "\"name\": \"../a\""));
  EXPECT_NE(n.find(json_name() + ":3:11: key 'name' must be a plain file stem"), std::string::npos) << n;
  const std::string s = error_of(kGoodCsv, json_with("[0.04, 0.04, 0.02]", "[0.04, 0.04, -0.02]"));
  EXPECT_NE(s.find(json_name() + ":6:56: key 'sample.size_m[2]' must be > 0"), std::string::npos) << s;
  const std::string p = error_of(
      kGoodCsv, json_with("\"bottom\": \"bonded\"", "\"bottom\": \"bonded\", \"platens\": \"bonded\""));
  EXPECT_NE(p.find("key 'sample.platens' is only for compression tests"), std::string::npos) << p;
  const std::string c = error_of(
      kGoodCsv,
      json_with("\"test\": \"indentation\",\n  \"indenter\": { \"shape\": \"sphere\", \"radius_m\": 0.005 },",
                "\"test\": \"unconfined_compression\","));
  EXPECT_NE(c.find(json_name() + ":5:13: missing key 'sample.platens' in 'sample'"), std::string::npos) << c;
  const std::string syntax = error_of(kGoodCsv, "{\"format\": \"tmlab-measured/1\",\n \"name\": }");
  EXPECT_NE(syntax.find(json_name() + ": invalid JSON"), std::string::npos) << syntax;
  EXPECT_NE(syntax.find("line 2, column 10"), std::string::npos) << syntax;
  const std::string twice =
      error_of(kGoodCsv, json_with("\"name\": \"a\",", "\"name\": \"a\", \"name\": \"b\","));
  EXPECT_NE(twice.find(json_name() + ": key 'name' is given twice"), std::string::npos) << twice;
  const std::string deep = error_of(
      kGoodCsv,
      json_with("\"license\"", "\"x\": " + std::string(100, '[') + std::string(100, ']') + ", \"license\""));
  EXPECT_NE(deep.find("nested deeper than"), std::string::npos) << deep;
}

TEST_F(MeasuredData, MissingMetadataFileIsNamed) {
  write("a.csv", kGoodCsv);
  try {
    read_data_set(dir_ / "a.csv");
    FAIL() << "read without a.json";
  } catch (const tmlab::Error& e) {
    EXPECT_NE(std::string(e.what()).find(json_name() + ": missing"), std::string::npos) << e.what();
  }
}

TEST(MeasuredDataUnits, UnitSuffixes) {
  for (const char* ok : {"time_s", "force_N", "radius_m", "temperature_C", "speed_m_per_s", "strain_1",
                         "stress_kPa", "rate_mm_per_min", "accel_m_per_s2", "true_stress_kPa"})
    EXPECT_TRUE(has_unit_suffix(ok)) << ok;
  for (const char* bad :
       {"time", "force", "_s", "s", "speed_per_s", "stiffness", "depth_", "x__m", "Time (s)"})
    EXPECT_FALSE(has_unit_suffix(bad)) << bad;
}

TEST(MeasuredDataNumbers, Decimals) {
  double v = 0;
  std::string why;
  EXPECT_TRUE(parse_decimal("-1.5e-3", v, why));
  EXPECT_EQ(v, -1.5e-3);
  EXPECT_TRUE(parse_decimal("+0.25", v, why));
  EXPECT_EQ(v, 0.25);
  // The documented grammar [+-]digits[.digits][e[+-]digits]: digits on both sides of the point.
  for (const char* bad :
       {"", ".", "+.25", "7.", ".5", "e5", "1e", "1.2.3", "0x10", "1,5", "nan", "-Infinity", "1e400", " 1"})
    EXPECT_FALSE(parse_decimal(bad, v, why)) << bad;
}

// --- issue 26: every bad input named, nothing of the user's written over ----------------------

const char* kCompressionJson = R"({
  "format": "tmlab-measured/1",
  "name": "a",
  "test": "unconfined_compression",
  "sample": { "shape": "cylinder", "radius_m": 0.025, "height_m": 0.03, "platens": "bonded" }
}
)";

TEST_F(MeasuredData, CompressionTakesPlatensAloneAsTheBottomToo) {
  // Between two platens the bottom platen is the bottom: `platens` alone says both.
  write("a.csv", kGoodCsv);
  write("a.json", kCompressionJson);
  const DataSet d = read_data_set(dir_ / "a.csv");
  EXPECT_EQ(d.meta.sample.platens, Interface::bonded);
  EXPECT_EQ(d.meta.sample.bottom, Interface::bonded);
  EXPECT_TRUE(d.notes.empty());
  // A `bottom` that differs is kept as written, with a note that the rigs use `platens`.
  std::string differs = kCompressionJson;
  differs.replace(differs.find("\"platens\""), 9, "\"bottom\": \"frictionless\", \"platens\"");
  write("a.json", differs);
  const DataSet e = read_data_set(dir_ / "a.csv");
  EXPECT_EQ(e.meta.sample.bottom, Interface::frictionless);
  ASSERT_EQ(e.notes.size(), 1u);
  EXPECT_EQ(e.notes[0].where, json_name() + ":5:83");
  EXPECT_NE(
      e.notes[0].text.find("key 'sample.bottom' is \"frictionless\" but 'sample.platens' is \"bonded\""),
      std::string::npos)
      << e.notes[0].text;
  // `bottom` alone does not say what the top platen is: refused, saying what to write.
  std::string bottom_only = kCompressionJson;
  bottom_only.replace(bottom_only.find("\"platens\""), 9, "\"bottom\"");
  const std::string b = error_of(kGoodCsv, bottom_only);
  EXPECT_NE(b.find(json_name() + ":5:13: missing key 'sample.platens' in 'sample' (a sample compressed "
                                 "between two platens needs their interface"),
            std::string::npos)
      << b;
  // Still refused: platens in a test without platens.
  const std::string p = error_of(
      kGoodCsv, json_with("\"bottom\": \"bonded\"", "\"bottom\": \"bonded\", \"platens\": \"bonded\""));
  EXPECT_NE(p.find("key 'sample.platens' is only for compression tests"), std::string::npos) << p;
}

TEST_F(MeasuredData, ALongNameIsRefusedForItsLength) {
  const std::string n =
      error_of(kGoodCsv, json_with("\"name\": \"a\"", "\"name\": \"" + std::string(300, 'n') + "\""));
  EXPECT_NE(n.find(json_name() + ":3:11: key 'name' is 300 characters long: at most 200"), std::string::npos)
      << n;
  const std::string id =
      error_of("test_id,time_s,displacement_m,force_N\n" + std::string(201, 'i') + ",0,0,0\n");
  EXPECT_NE(id.find(csv_name() + ":2:1: column 'test_id': test_id is 201 characters long: at most 200"),
            std::string::npos)
      << id;
  // 200 is allowed; the character rule still holds.
  EXPECT_EQ(error_of("test_id,time_s,displacement_m,force_N\n" + std::string(200, 'i') + ",0,0,0\n"), "");
  const std::string bad = error_of("test_id,time_s,displacement_m,force_N\na b,0,0,0\n");
  EXPECT_NE(bad.find(csv_name() + ":2:1: column 'test_id': test_id must be a plain file stem"),
            std::string::npos)
      << bad;
}

TEST_F(MeasuredData, ControlCharactersInQuotedTextAreEscaped) {
  // A NUL in a header name: the message goes on past it, the NUL shown as \x00.
  const std::string nul = error_of(std::string("time_s,displacement_m,for\0ce_N\n0,0,0\n", 37));
  EXPECT_NE(nul.find(csv_name() + ":1:23: column name 'for\\x00ce_N' is not a tmlab-measured/1 name"),
            std::string::npos)
      << nul;
  // An ANSI colour sequence in a test_id: shown as text, no ESC reaches the terminal.
  const std::string esc = error_of("test_id,time_s,displacement_m,force_N\n\x1b[31mred,0,0,0\n");
  EXPECT_NE(esc.find("(got \"\\x1b[31mred\")"), std::string::npos) << esc;
  EXPECT_EQ(esc.find('\x1b'), std::string::npos) << esc;
  // A key of NAME.json (JSON escapes decode to the raw characters).
  const std::string key =
      error_of(kGoodCsv, json_with("\"license\"", "\"x\\u0000y\\u001b[31m\": 5, \"license\""));
  EXPECT_NE(key.find("key 'x\\x00y\\x1b[31m' is a unit-less number"), std::string::npos) << key;
  EXPECT_EQ(key.find('\x1b'), std::string::npos) << key;
  const std::string name = error_of(kGoodCsv, json_with("\"name\": \"a\"", "\"name\": \"a\\u001b[2Jb\""));
  EXPECT_NE(name.find("(got \"a\\x1b[2Jb\")"), std::string::npos) << name;
}

TEST_F(MeasuredData, DeepNestingFailsAtOnceNamingWhere) {
  // 100k levels took half a minute in the JSON parser: the depth is checked before it. Unclosed,
  // the parser would have called it invalid JSON (at the end of the file); it never gets there.
  const std::string open = "{\"format\": \"tmlab-measured/1\", \"x\": " + std::string(100000, '[');
  const std::string e = error_of(kGoodCsv, open);
  // The root object is level 1: the 64th '[' (column 37 + 63) opens level 65.
  EXPECT_NE(e.find(json_name() + ":1:100: nested deeper than 64 levels"), std::string::npos)
      << e.substr(0, 300);
  const std::string closed = error_of(kGoodCsv, open + std::string(100000, ']') + "}");
  EXPECT_NE(closed.find(json_name() + ":1:100: nested deeper than 64 levels"), std::string::npos)
      << closed.substr(0, 300);
  // Brackets in strings and comments are not nesting.
  const std::string many = std::string(100, '[') + std::string(100, '{');
  EXPECT_EQ(error_of(kGoodCsv, json_with("\"license\"", "\"note\": \"" + many + "\\\"" + many + "\", /* " +
                                                            many + " */ // " + many + "\n \"license\"")),
            "");
}

TEST_F(MeasuredData, DirectoriesAndFifosAreNamedAndNeverBlock) {
  // No d.json beside it: the directory is named, not its missing metadata.
  fs::create_directory(dir_ / "d.csv");
  try {
    read_data_set(dir_ / "d.csv");
    FAIL() << "read a directory";
  } catch (const tmlab::Error& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "d.csv").string() + ": is a directory, not a file");
  }
  // A FIFO with no writer: opening it for reading would wait for ever.
  ASSERT_EQ(::mkfifo((dir_ / "f.csv").c_str(), 0600), 0);
  write("f.json", kIndentationJson);
  try {
    read_data_set(dir_ / "f.csv");
    FAIL() << "read a FIFO";
  } catch (const tmlab::Error& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "f.csv").string() + ": is not a regular file (a FIFO)");
  }
  write("g.csv", kGoodCsv);
  ASSERT_EQ(::mkfifo((dir_ / "g.json").c_str(), 0600), 0);
  try {
    read_data_set(dir_ / "g.csv");
    FAIL() << "read a FIFO as metadata";
  } catch (const tmlab::Error& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "g.json").string() + ": is not a regular file (a FIFO)");
  }
  try {
    read_input_file(dir_ / "none.csv");
    FAIL() << "read a missing file";
  } catch (const tmlab::Error& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "none.csv").string() + ": no such file");
  }
}

/// A small valid data set named `name`.
DataSet small_set(const std::string& name) {
  DataSet d;
  d.meta.name = name;
  d.meta.test = TestType::indentation;
  d.meta.indenter = Indenter{IndenterShape::flat_punch, 0.002, {}};
  d.meta.sample.shape = SampleShape::half_space;
  d.tests.push_back({"", 0, {0.0, 1.0}, {0.0, 1e-3}, {0.0, 1.0}, {}});
  return d;
}

TEST_F(MeasuredData, WriterIntoAUsersFolderReplacesNothingUnasked) {
  fs::create_directories(dir_ / "out");
  write("out/s.json", "the user's own notes");
  try {
    write_data_set(small_set("s"), dir_ / "out", {}, false);
    FAIL() << "wrote over s.json";
  } catch (const tmlab::Error& e) {
    EXPECT_NE(std::string(e.what()).find((dir_ / "out" / "s.json").string() + ": exists already"),
              std::string::npos)
        << e.what();
  }
  // Both targets are checked before either is written.
  EXPECT_FALSE(fs::exists(dir_ / "out" / "s.csv"));
  std::ifstream kept(dir_ / "out" / "s.json");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "the user's own notes");
  // With overwrite they are replaced, and nothing else appears in the folder (no temporary left).
  EXPECT_EQ(write_data_set(small_set("s"), dir_ / "out", {}, true), dir_ / "out" / "s.csv");
  EXPECT_EQ(read_data_set(dir_ / "out" / "s.csv").meta.name, "s");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir_ / "out")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"s.csv", "s.json"}));
}

TEST_F(MeasuredData, WriterNeverWritesOverAnInputEvenThroughLinks) {
  fs::create_directories(dir_ / "raw");
  write("raw/s.csv", "raw data");
  const fs::path input = dir_ / "raw" / "s.csv";
  const auto refused = [&](const fs::path& out, const std::string& target) {
    try {
      write_data_set(small_set("s"), out, {input}, true);
    } catch (const tmlab::Error& e) {
      return std::string(e.what()).find(target + ": is the input " + input.string()) != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(refused(dir_ / "raw", (dir_ / "raw" / "s.csv").string()));
  // The folder through a symbolic link, the file through a symbolic link and a hard link.
  fs::create_directory_symlink(dir_ / "raw", dir_ / "link");
  EXPECT_TRUE(refused(dir_ / "link", (dir_ / "link" / "s.csv").string()));
  fs::create_directories(dir_ / "viasym");
  fs::create_symlink(input, dir_ / "viasym" / "s.csv");
  EXPECT_TRUE(refused(dir_ / "viasym", (dir_ / "viasym" / "s.csv").string()));
  fs::create_directories(dir_ / "viahard");
  fs::create_hard_link(input, dir_ / "viahard" / "s.csv");
  EXPECT_TRUE(refused(dir_ / "viahard", (dir_ / "viahard" / "s.csv").string()));
  std::ifstream in(input);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "raw data");
  EXPECT_FALSE(fs::exists(dir_ / "raw" / "s.json"));
}

}  // namespace
