// The silicone phantom converter on the copied upstream files (calibration/data/phantom/): the
// geometry, the units, the sign, the attribution, and a malformed file named by line and column.
#include "calibration/data/phantom_converter.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

namespace {

namespace fs = std::filesystem;
using namespace tmlab::measured;

const fs::path kPhantom = fs::path(TMLAB_SOURCE_DIR) / "calibration" / "data" / "phantom";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string error_of(const std::string& text) {
  try {
    convert_phantom_text(text, "x.csv");
  } catch (const tmlab::Error& e) {
    return e.what();
  }
  return "";
}

TEST(PhantomConverter, ConvertsEf10A1) {
  const fs::path f = kPhantom / "EF10_0T" / "EF10_0T_A1.csv";
  EXPECT_TRUE(is_phantom_csv(slurp(f)));
  const DataSet d = convert_phantom(f);
  EXPECT_EQ(d.meta.name, "EF10_0T_A1");
  EXPECT_EQ(d.meta.test, TestType::unconfined_compression);
  EXPECT_EQ(d.meta.sample.shape, SampleShape::cylinder);
  EXPECT_DOUBLE_EQ(d.meta.sample.radius_m, 0.025);
  EXPECT_DOUBLE_EQ(d.meta.sample.height_m, 0.030);
  EXPECT_EQ(d.meta.sample.platens, Interface::frictionless);
  EXPECT_EQ(d.meta.sample.bottom, Interface::frictionless);
  EXPECT_EQ(d.meta.license, "CC-BY-4.0");
  EXPECT_NE(d.meta.source.find("Dawood A.B."), std::string::npos);
  EXPECT_NE(d.meta.source.find("tissue-phantom-material-database"), std::string::npos);
  EXPECT_NE(d.meta.source.find("EF10_0T_A_sample_1"), std::string::npos);
  EXPECT_NE(d.meta.notes.find("INSTRON 5900 (load cell 1kN), crosshead 10 mm/min"), std::string::npos)
      << d.meta.notes;
  ASSERT_EQ(d.tests.size(), 1u);
  const tmlab::measured::Test& t = d.tests[0];
  // The file: 8 header lines, then 1202 samples; first and last rows as written upstream.
  EXPECT_EQ(t.size(), 1202u);
  EXPECT_EQ(t.first_line, 9);
  EXPECT_EQ(t.time_s.front(), 0.0);
  EXPECT_EQ(t.force_N.front(), -0.009120);
  EXPECT_EQ(t.time_s.back(), 120.021);
  // mm -> m rounded once: the double nearest the decimal value in metres.
  EXPECT_EQ(t.displacement_m.back(), 20.000040e-3);
  EXPECT_EQ(t.displacement_m[2], 2.7470e-05);  // "0.027470" mm
  EXPECT_EQ(t.force_N.back(), 499.323150);
  EXPECT_EQ(*std::max_element(t.force_N.begin(), t.force_N.end()), 499.323150);
  EXPECT_TRUE(t.extra.empty());
}

TEST(PhantomConverter, EveryCopiedFileConvertsAndReadsBack) {
  const fs::path out = fs::temp_directory_path() / ("tmlab_phantom_" + std::to_string(::getpid()));
  int files = 0;
  for (const char* grade : {"EF10_0T", "EF30_0T", "EF50_0T"}) {
    for (const auto& e : fs::directory_iterator(kPhantom / grade)) {
      const DataSet d = convert_phantom(e.path(), {Interface::bonded});
      const DataSet r = read_data_set(write_data_set(d, out));
      ASSERT_EQ(r.tests.size(), 1u) << e.path();
      EXPECT_EQ(r.tests[0].force_N, d.tests[0].force_N) << e.path();
      EXPECT_EQ(r.tests[0].displacement_m, d.tests[0].displacement_m) << e.path();
      EXPECT_EQ(r.meta.sample.platens, Interface::bonded);
      EXPECT_TRUE(r.notes.empty()) << r.notes.front().text;
      // Monotonic ramps to 20 mm, pushing back: positive force at the end.
      EXPECT_NEAR(r.tests[0].displacement_m.back(), 0.020, 1e-6) << e.path();
      EXPECT_GT(r.tests[0].force_N.back(), 400.0) << e.path();
      ++files;
    }
  }
  EXPECT_EQ(files, 30);
  fs::remove_all(out);
}

const char* kHeader =
    "S1\nCompression test;\nCylinder Diameter: 50mm;\nCylinder Height: 30mm;\n"
    "Time (s),Compression (mm),Load (N),Engineering Strain [-],Engineering Stress (kPa),True Strain [-],True "
    "Stress (kPa)\n";

TEST(PhantomConverter, NegativeLoadIsFlippedWithANote) {
  // 10 N on 1963.5 mm^2 is 5.093 kPa.
  const DataSet d =
      convert_phantom_text(std::string(kHeader) + "0,0,0,0,0,0,0\n1,1.5E+1,-10,-0.5,-5.093,0,0\n", "s.csv");
  EXPECT_EQ(d.tests[0].force_N.back(), 10.0);
  EXPECT_EQ(d.tests[0].displacement_m.back(), 0.015);
  EXPECT_NE(d.meta.notes.find("was negated"), std::string::npos);
}

TEST(PhantomConverter, MalformedFilesAreNamed) {
  EXPECT_NE(error_of("time_s,displacement_m,force_N\n0,0,0\n").find("x.csv:1:1: not a silicone phantom CSV"),
            std::string::npos);
  const std::string row = error_of(std::string(kHeader) + "0,0,0,0,0,0,0\n0.1,0.1,nan,0,0,0,0\n");
  EXPECT_NE(row.find("x.csv:7:9: column 'Load (N)': NaN"), std::string::npos) << row;
  const std::string time = error_of(std::string(kHeader) + "0,0,0,0,0,0,0\n0,0.1,1,0,0.5093,0,0\n");
  EXPECT_NE(time.find("x.csv:7:1: column 'Time (s)': time does not increase"), std::string::npos) << time;
  const std::string empty = error_of(kHeader);
  EXPECT_NE(empty.find("x.csv:6:1: no samples"), std::string::npos) << empty;
  std::string no_height = kHeader;
  no_height.replace(no_height.find("Cylinder Height: 30mm;\n"), 23, "");
  EXPECT_NE(error_of(no_height + "0,0,0,0,0,0,0\n").find("no 'Cylinder Height"), std::string::npos);
  // The stress column says kPa for a 50 mm cylinder; a header claiming 40 mm is caught.
  std::string wrong = kHeader;
  wrong.replace(wrong.find("50mm"), 4, "40mm");
  const std::string geo = error_of(wrong + "0,0,0,0,0,0,0\n1,1,10,-0.033,-5.093,0,0\n");
  EXPECT_NE(
      geo.find("x.csv:7:1: 'Engineering Stress (kPa)' is -5.093 but Load / (pi (D/2)^2) is 7.95775 kPa"),
      std::string::npos)
      << geo;
}

TEST(PhantomConverter, ACompressionBeyondTheHeightAndASingleSampleAreRefused) {
  // The header says 30 mm high; a row compresses it by 35 mm (stress consistent with D = 50 mm).
  const std::string deep =
      error_of(std::string(kHeader) + "0,0,0,0,0,0,0\n1,35.0,10,-1.17,-5.093,0,0\n2,10,5,-0.33,-2.546,0,0\n");
  EXPECT_NE(
      deep.find("x.csv:7:3: column 'Compression (mm)': the compression reaches 35 mm, not less than the "
                "height 30 mm of 'Cylinder Height' (line 4)"),
      std::string::npos)
      << deep;
  // Exactly the height is refused too (the sample would have no thickness left).
  EXPECT_NE(error_of(std::string(kHeader) + "0,0,0,0,0,0,0\n1,30,10,-1,-5.093,0,0\n").find("reaches 30 mm"),
            std::string::npos);
  const std::string one = error_of(std::string(kHeader) + "0,0.1,1,0,0.5093,0,0\n");
  EXPECT_NE(one.find("x.csv:6:1: one sample only (line 6): a force-displacement curve needs at least two"),
            std::string::npos)
      << one;
}

TEST(PhantomConverter, DirectoriesAndFifosAreNamed) {
  const fs::path dir = fs::temp_directory_path() / ("tmlab_phantom_kinds_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "d.csv");
  ASSERT_EQ(::mkfifo((dir / "f.csv").c_str(), 0600), 0);
  for (const auto& [path, what] :
       {std::pair<fs::path, std::string>{dir / "d.csv", "is a directory, not a file"},
        {dir / "f.csv", "is not a regular file (a FIFO)"}}) {
    try {
      convert_phantom(path);
      ADD_FAILURE() << "converted " << path;
    } catch (const tmlab::Error& e) {
      EXPECT_EQ(std::string(e.what()), path.string() + ": " + what);
    }
  }
  fs::remove_all(dir);
}

}  // namespace
