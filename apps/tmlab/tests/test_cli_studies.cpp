// Smoke tests of the study commands of the tmlab command line: `tmlab workprecision --quick` into a
// temporary results directory (complete result protocol: summary.json, HDF5, table, manifest) and its
// usage errors.
#include "core/io/hdf5_file.hpp"

#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace {

namespace fs = std::filesystem;

using tmlab::cli_test::Result;
using tmlab::cli_test::run;

TEST(CliStudies, WorkPrecisionQuickWritesACompleteResult) {
  const fs::path dir = fs::temp_directory_path() / ("tmlab_cli_wp_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const Result r =
      run("workprecision --problem incompressible --quick --no-plots --results '" + dir.string() + "'");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("[workprecision] incompressible: reference CVODE BDF + spgmr+prec"),
            std::string::npos)
      << r.output;  // progress on stderr
  const fs::path out = dir / "workprecision";
  ASSERT_TRUE(fs::exists(out / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "manifest.json"));
  EXPECT_TRUE(fs::exists(out / "workprecision.md"));
  EXPECT_FALSE(fs::exists(out / "FAILED"));
  const nlohmann::json s = nlohmann::json::parse(std::ifstream(out / "summary.json"));
  ASSERT_EQ(s.at("problems").size(), 1u);
  EXPECT_EQ(s["problems"][0]["name"], "incompressible");
  EXPECT_EQ(s["problems"][0]["failed_runs"], 0);
  const tmlab::H5File f = tmlab::H5File::open_read((out / "workprecision.h5").string());
  const std::vector<double> e = f.read_double("/incompressible/cvode_bdf_spgmr_prec/error");
  ASSERT_FALSE(e.empty());
  for (double x : e) EXPECT_TRUE(x > 0.0 && x < 1e-2) << x;  // quick CVODE runs at rtol 1e-4, 1e-6
  fs::remove_all(dir);
}

TEST(CliStudies, WorkPrecisionUsageErrors) {
  const Result bad = run("workprecision --problem kidney");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("--problem must be liver, incompressible or all"), std::string::npos)
      << bad.output;
  const Result tol = run("workprecision --reference-rtol 0.1");
  EXPECT_EQ(tol.status, 2);
  EXPECT_NE(tol.output.find("--reference-rtol"), std::string::npos) << tol.output;
  const Result opt = run("workprecision --frobnicate");
  EXPECT_EQ(opt.status, 2);
}

TEST(CliStudies, DepthLimitCellsAreWholeNumbers) {
  // Issue 26: "4.0" and "4e0" used to be taken as 4; every count is a whole number under the one
  // grammar, the option named (exit 2, before anything runs or is written).
  const fs::path out = fs::temp_directory_path() / ("tmlab_depth_limit_cells_" + std::to_string(::getpid()));
  for (const char* cells : {"4.0", "4e0", "0x4", " 4", "1", "65"}) {
    const Result r = run(std::string("depth-limit --quick --no-plots --laws stvk --cells '") + cells +
                         "' --results '" + out.string() + "'");
    EXPECT_EQ(r.status, 2) << cells << "\n" << r.output;
    EXPECT_NE(r.output.find("--cells needs a whole number"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(out);
}

TEST(CliStudies, TheOldInversionCommandNamesItsNewName) {
  // Issue 27: 'tmlab inversion' (element inversion depth) read like inverse identification beside
  // 'tmlab fit'; it is 'tmlab depth-limit' now, and the old name says so (exit 2, nothing run).
  const fs::path out = fs::temp_directory_path() / ("tmlab_old_inversion_" + std::to_string(::getpid()));
  const Result r = run("inversion --quick --no-plots --results '" + out.string() + "'");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("tmlab inversion is now tmlab depth-limit"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliStudies, DepthLimitRangesAreCheckedBeforeAnythingIsWritten) {
  // The depth, increment and grading are declared with their ranges: an impossible value is a usage
  // error naming the option (exit 2), and no result folder is made.
  const fs::path out = fs::temp_directory_path() / ("tmlab_depth_limit_range_" + std::to_string(::getpid()));
  for (const char* bad : {"--max-depth 0", "--max-depth 0.03", "--increment -1", "--grading 0.5"}) {
    const Result r =
        run(std::string("depth-limit --quick --no-plots ") + bad + " --results '" + out.string() + "'");
    EXPECT_EQ(r.status, 2) << bad << "\n" << r.output;
    EXPECT_NE(r.output.find(std::string(bad).substr(0, std::string(bad).find(' '))), std::string::npos)
        << r.output;
  }
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(out);
}

TEST(CliStudies, HereditaryLiverHistoryNeedsTheLiver) {
  const Result r =
      run("hereditary --quick --no-liver --liver-history pk2 --no-plots --results /nonexistent-tmlab");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--liver-history"), std::string::npos) << r.output;
}

}  // namespace
