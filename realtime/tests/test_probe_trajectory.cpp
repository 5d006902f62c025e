// Probe trajectories: scripted motions are closed and smooth; the CSV reader is strict and its
// errors name the file and line; a case's trajectory file stays in the case's folder.
#include "realtime/probe_trajectory.hpp"
#include "realtime/realtime_case.hpp"

#include "core/base/error.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

namespace tmlab::rt {
namespace {

namespace fs = std::filesystem;

TEST(ProbeTrajectory, PokeIsClosedAndReachesItsDepth) {
  const Vec3 s(0.0, 0.0, 1.0);
  const ProbeTrajectory p = ProbeTrajectory::poke(s, Vec3(0, 0, -2), 0.01, 0.5, 0.3);
  EXPECT_DOUBLE_EQ(p.duration(), 1.3);
  EXPECT_LT((p.position(0.0) - s).norm(), 1e-15);
  EXPECT_NEAR(p.position(0.6).z(), 0.99, 1e-15);
  EXPECT_NEAR(p.position(0.25).z(), 0.995, 1e-15);
  EXPECT_LT((p.position(1.3) - s).norm(), 1e-15);
  EXPECT_LT((p.position(5.0) - s).norm(), 1e-15);
}

TEST(ProbeTrajectory, EllipsePeriodsAreClosed) {
  const ProbeTrajectory p =
      ProbeTrajectory::ellipse(Vec3::Zero(), -Vec3::UnitZ(), Vec3(1, 0, 1), 0.02, 0.004, 0.5, 2, 0.2);
  EXPECT_LT((p.position(0.2) - p.position(0.7)).norm(), 1e-15);
  EXPECT_LT((p.position(0.7) - p.position(1.2)).norm(), 1e-15);
  EXPECT_NEAR(p.position(0.2 + 0.125).z(), -0.02, 1e-15);  // deepest point
  EXPECT_NEAR(p.position(0.2 + 0.25).x(), 0.008, 1e-15);   // widest point, lateral made orthogonal
  EXPECT_LT(p.position(p.duration()).norm(), 1e-15);
}

class TrajectoryCsv : public tmlab::testing::TempDirTest {
 protected:
  std::string write(const std::string& text) {
    const std::string path = (dir_ / "probe.csv").string();
    std::ofstream(path) << text;
    return path;
  }
  std::string error_of(const std::string& text) {
    const std::string path = write(text);
    try {
      ProbeTrajectory::read_csv(path);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(TrajectoryCsv, ReadsAndInterpolates) {
  const std::string path = write("# comment\n\nt,x,y,z\n0,0,0,1\n0.5, 0.1, 0, 1\n1.0,0.1,0.2,1\n");
  const ProbeTrajectory p = ProbeTrajectory::read_csv(path);
  EXPECT_DOUBLE_EQ(p.duration(), 1.0);
  EXPECT_NEAR(p.position(0.25).x(), 0.05, 1e-15);
  EXPECT_NEAR(p.position(0.75).y(), 0.1, 1e-15);
  EXPECT_NEAR(p.position(2.0).y(), 0.2, 1e-15);
  // Round trip through write_csv.
  const std::string out = (dir_ / "out.csv").string();
  ProbeTrajectory::write_csv(out, {0.0, 0.25}, {Vec3(1, 2, 3), Vec3(4, 5, 6)});
  EXPECT_NEAR(ProbeTrajectory::read_csv(out).position(0.125).z(), 4.5, 1e-15);
}

TEST_F(TrajectoryCsv, ErrorsNameFileAndLine) {
  const std::string p = (dir_ / "probe.csv").string();
  EXPECT_EQ(error_of("t,x,y\n0,0,0\n"), p + ":1: the header must be 't,x,y,z' (got 't,x,y')");
  EXPECT_EQ(error_of("t,x,y,z\n0,0,0,1\n0.1,0,abc,1\n"),
            p + ":3: column 3 (y): 'abc' is not a number (decimal: [+-]digits[.digits][e[+-]digits])");
  EXPECT_EQ(error_of("t,x,y,z\n0,0,0,1\n0.1,0,0\n"),
            p + ":3: expected 4 comma-separated columns t,x,y,z (got 3)");
  EXPECT_EQ(error_of("t,x,y,z\n0,0,0,1\n0.1,0,0,1,5\n"),
            p + ":3: expected 4 comma-separated columns t,x,y,z (got 5)");
  EXPECT_EQ(error_of("t,x,y,z\n0,0,0,1\n0.1,0,0,1\n0.1,0,0,1\n"),
            p + ":4: time 0.1 is not after the previous sample's (0.1)");
  EXPECT_EQ(error_of("t,x,y,z\n0.5,0,0,1\n"), p + ":2: the first sample must be at t = 0 (got t = 0.5)");
  EXPECT_EQ(error_of("t,x,y,z\n0,0,nan,1\n"), p + ":2: column 3 (y): NaN is not a value");
  EXPECT_EQ(error_of("t,x,y,z\n0,0,1e999,1\n"),
            p + ":2: column 3 (y): '1e999' is out of the range of a double");
  EXPECT_EQ(error_of("t,x,y,z\n0,0x1p-1,0,1\n").substr(p.size()),
            ":2: column 2 (x): '0x1p-1' is not a number "
            "(decimal: [+-]digits[.digits][e[+-]digits])");
  EXPECT_EQ(error_of(""), p + ": empty trajectory file (expected the header 't,x,y,z')");
  EXPECT_EQ(error_of("t,x,y,z\n"), p + ": the trajectory has a header but no sample");
  EXPECT_NE(error_of("t,x,y,z\n0,,0,1\n").find(":2: column 2 (x)"), std::string::npos);
  // A message quotes at most 40 characters of the file, control characters escaped: never a whole line.
  const std::string secret(200, 's');
  const std::string header = error_of("\x1b[31m" + secret + "\n");
  EXPECT_EQ(header.find(secret.substr(0, 41)), std::string::npos) << header;
  EXPECT_EQ(header.find('\x1b'), std::string::npos) << header;
  EXPECT_NE(header.find(":1: the header must be 't,x,y,z' (got '\\x1b[31m"), std::string::npos) << header;
  const std::string field = error_of("t,x,y,z\n0,0," + secret + ",1\n");
  EXPECT_EQ(field.find(secret.substr(0, 41)), std::string::npos) << field;
  EXPECT_NE(field.find(":2: column 3 (y): 'ssss"), std::string::npos) << field;
  EXPECT_EQ(error_of("t,x,y,z\n0,0,0,1\n" + secret + "," + secret + "\n").find(secret.substr(0, 10)),
            std::string::npos);
  EXPECT_THROW(ProbeTrajectory::read_csv((dir_ / "missing.csv").string()), Error);
}

TEST_F(TrajectoryCsv, SamplesOutsideTheBoundsNameFileAndLine) {
  // A path written in millimetres against a mesh in metres: refused at its first sample outside.
  const ProbeBounds b{Vec3(-0.1, -0.1, 1.4), Vec3(0.1, 0.1, 1.7), "the reach"};
  const std::string path = write("t,x,y,z\n0,0,0,1.65\n# now in mm\n0.5,-40,-57,1636\n");
  try {
    ProbeTrajectory::read_csv(path, &b);
    FAIL() << "a sample outside the bounds was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path +
                                         ":4: the probe centre (-40, -57, 1636) m lies outside the reach, "
                                         "(-0.1, -0.1, 1.4) to (0.1, 0.1, 1.7) m: positions are in metres, "
                                         "in the mesh frame");
  }
  // On the box itself is inside; without bounds nothing is checked.
  EXPECT_NO_THROW(ProbeTrajectory::read_csv(write("t,x,y,z\n0,-0.1,0.1,1.7\n"), &b));
  EXPECT_NO_THROW(ProbeTrajectory::read_csv(write("t,x,y,z\n0,0,0,1.65\n0.5,-40,-57,1636\n")));
}

/// A case's trajectory file must lie in the case file's folder (or below it): a path leading out,
/// directly or through a symbolic link, is refused naming where it resolved to, and nothing of the
/// outside file is read or quoted (issue 26).
TEST_F(TrajectoryCsv, CaseTrajectoryFileStaysInTheCaseFolder) {
  const fs::path folder = dir_ / "case";
  fs::create_directories(folder / "sub");
  std::ofstream(dir_ / "secret.csv") << "root:x:0:0:secret\n";
  std::ofstream(folder / "sub" / "probe.csv") << "t,x,y,z\n0,-0.04,-0.057,1.636\n1,-0.04,-0.057,1.626\n";
  std::ifstream in(fs::path(TMLAB_SOURCE_DIR) / "cases" / "realtime" / "liver-poke.json");
  const std::string src((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto case_with = [&](const std::string& file) {
    std::string c = src;
    const auto a = c.find("\"trajectory\": {");
    c.replace(a, c.find('}', a) - a + 1, "\"trajectory\": {\"type\": \"csv\", \"file\": \"" + file + "\"}");
    std::ofstream(folder / "c.json") << c;
    return (folder / "c.json").string();
  };
  const auto error_of_case = [&](const std::string& file) -> std::string {
    try {
      load_realtime_case(case_with(file), TMLAB_SOURCE_DIR);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  const std::string canonical_folder = fs::canonical(folder).string();
  for (const std::string& out : {std::string("../secret.csv"), std::string("../../../../../../etc/passwd"),
                                 (dir_ / "secret.csv").string(), std::string("sub/../../secret.csv")}) {
    const std::string e = error_of_case(out);
    EXPECT_NE(e.find("key 'trajectory.file' = '" + out + "' resolves to "), std::string::npos) << e;
    EXPECT_NE(e.find(", outside the case file's folder " + canonical_folder +
                     ": a trajectory file must lie in that folder or below it"),
              std::string::npos)
        << e;
    EXPECT_EQ(e.find("root:"), std::string::npos) << e;
  }
  // A symbolic link in the folder that leads out is followed, and refused.
  std::error_code ec;
  fs::create_symlink(dir_ / "secret.csv", folder / "link.csv", ec);
  if (!ec) {
    const std::string e = error_of_case("link.csv");
    EXPECT_NE(e.find("resolves to " + fs::canonical(dir_ / "secret.csv").string() + ", outside"),
              std::string::npos)
        << e;
  }
  // Inside the folder: read, and its errors name the resolved file.
  const RealtimeCase c = load_realtime_case(case_with("sub/probe.csv"), TMLAB_SOURCE_DIR);
  EXPECT_EQ(c.trajectory->describe(), fs::canonical(folder / "sub" / "probe.csv").string());
  std::ofstream(folder / "sub" / "probe.csv") << "t,x,y,z\n0,-0.04,oops,1.636\n";
  EXPECT_NE(error_of_case("./sub/probe.csv")
                .find(fs::canonical(folder / "sub" / "probe.csv").string() + ":2: column 3 (y): 'oops'"),
            std::string::npos);
}

TEST(ProbeTrajectory, BadScriptsAreRefused) {
  EXPECT_THROW(ProbeTrajectory::poke(Vec3::Zero(), Vec3::Zero(), 0.01, 0.5, 0.0), Error);
  EXPECT_THROW(ProbeTrajectory::poke(Vec3::Zero(), -Vec3::UnitZ(), -0.01, 0.5, 0.0), Error);
  EXPECT_THROW(ProbeTrajectory::ellipse(Vec3::Zero(), -Vec3::UnitZ(), -Vec3::UnitZ(), 0.01, 0.0, 1.0, 1, 0.1),
               Error);
  EXPECT_THROW(ProbeTrajectory::ellipse(Vec3::Zero(), -Vec3::UnitZ(), Vec3::UnitX(), 0.01, 0.0, 1.0, 0, 0.1),
               Error);
}

}  // namespace
}  // namespace tmlab::rt
