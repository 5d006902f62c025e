// core/results/python/tmlab_plot.py: writes a PNG from a small timeseries.h5 written with H5File, and fails
// clearly on a missing dataset. Skipped when no python3 with matplotlib and h5py is found.
#include "core/io/hdf5_file.hpp"

#include "core/base/process.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

namespace fs = std::filesystem;

namespace {

/// True when the python3 the plots use (tmlab::python_interpreter(), the one lookup) imports
/// matplotlib and h5py.
bool python_has_plotting() {
  return tmlab::run_process({tmlab::python_interpreter(), "-c", "import matplotlib, h5py"},
                            tmlab::ProcessOutput::discard())
      .ok();
}

class TmlabPlotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!python_has_plotting()) {
      GTEST_SKIP() << tmlab::python_interpreter()
                   << " lacks matplotlib or h5py (apt-get install python3-matplotlib python3-h5py)";
    }
    dir_ = fs::temp_directory_path() / ("tmlab_plot_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    tmlab::H5File f = tmlab::H5File::create((dir_ / "timeseries.h5").string());
    for (int k = 0; k < 20; ++k) {
      f.append("/series/time", 0.1 * k);
      f.append("/series/kinetic", 1.0 / (1 + k));
      f.append("/series/elastic", 0.5 + 0.01 * k);
    }
    f.set_attribute("/series/time", "unit", "s");
    f.set_attribute("/series/kinetic", "unit", "J");
    f.set_attribute("/series/elastic", "unit", "J");
    f.close();
  }
  void TearDown() override {
    if (!dir_.empty()) fs::remove_all(dir_);
  }
  int plot() const {
    const fs::path script = fs::path(TMLAB_SOURCE_DIR) / "core/results/python/tmlab_plot.py";
    const tmlab::ProcessStatus st =
        tmlab::run_python(script, {dir_.string()}, tmlab::ProcessOutput::to_file(dir_ / "log.txt"));
    return st.started && st.signal == 0 ? st.exit_code : -1;
  }
  std::string log() const {
    std::ifstream in(dir_ / "log.txt");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  fs::path dir_;
};

TEST_F(TmlabPlotTest, WritesPng) {
  std::ofstream(dir_ / "plots.json") << R"([{"file": "energy.png", "x": "time", "y": ["kinetic", "elastic"],
    "title": "Energy", "xlabel": "t [s]", "ylabel": "E [J]", "logy": true}])";
  ASSERT_EQ(plot(), 0) << log();
  std::ifstream png(dir_ / "energy.png", std::ios::binary);
  ASSERT_TRUE(png.good());
  char magic[8] = {};
  png.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

TEST_F(TmlabPlotTest, MissingDatasetFailsWithMessage) {
  std::ofstream(dir_ / "plots.json") << R"([{"file": "x.png", "y": ["no_such_series"]}])";
  EXPECT_NE(plot(), 0);
  EXPECT_NE(log().find("/series/no_such_series"), std::string::npos) << log();
  EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

TEST_F(TmlabPlotTest, MissingPlotsJsonFails) {
  EXPECT_NE(plot(), 0);
  EXPECT_NE(log().find("plots.json"), std::string::npos) << log();
}

}  // namespace
