// `tmlab hereditary` end to end (quick mode): the result directory follows the RunOutput protocol
// (summary.json last, no RUNNING/FAILED), hereditary.h5 holds the sweeps, the amplification factors
// and the liver runs, the plots exist, and bad input exits non-zero with a message naming it.
#include "core/io/hdf5_file.hpp"

#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace {

namespace fs = std::filesystem;

using tmlab::cli_test::Result;
using tmlab::cli_test::run;

class CliHereditary : public tmlab::testing::TempDirTest {};

TEST_F(CliHereditary, QuickRunWritesACompleteResult) {
  const Result r = run("hereditary --quick --results '" + dir_.string() + "'");
  ASSERT_EQ(r.status, 0) << r.output;
  const fs::path out = dir_ / "hereditary";
  ASSERT_TRUE(fs::exists(out / "summary.json")) << r.output;
  EXPECT_FALSE(fs::exists(out / "RUNNING"));
  EXPECT_FALSE(fs::exists(out / "FAILED"));
  for (const char* f : {"manifest.json", "hereditary.h5", "hereditary.md", "error_vs_dt_over_tau.png",
                        "time_history.png", "amplification.png", "haptic.png", "liver_error.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;

  std::ifstream in(out / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  EXPECT_EQ(s.at("status"), "complete");
  // Quick sweep: the fit window dt/tau <= 0.05 holds 1e-3, 3.2e-3, 1e-2, 3.2e-2; on the smooth sine
  // (omega tau = 1) the slopes are 2.00, 2.00, 1.00 there (0.1: the fit of 4 asymptotic points).
  const auto& rh = s.at("histories").at("sine_w1").at("schemes");
  EXPECT_NEAR(rh.at("midpoint").at("order").get<double>(), 2.0, 0.1);
  EXPECT_NEAR(rh.at("exact_linear").at("order").get<double>(), 2.0, 0.1);
  EXPECT_NEAR(rh.at("backward_euler").at("order").get<double>(), 1.0, 0.1);
  EXPECT_GT(s.at("amplification").at("midpoint").at("min_a").get<double>(), 0.0);
  EXPECT_LT(s.at("reference_quadrature_check_max").get<double>(), 1e-12);
  for (const char* hist : {"nodal_force"}) {  // quick: the seed's form only
    const auto& liver = s.at("liver").at(hist);
    EXPECT_EQ(liver.at("runs").size(), 6u) << hist;  // 3 schemes x dt 0.2, 0.1 s
    // the two Richardson references (exact_linear, midpoint) agree far below the smallest error
    // measured with them (1.6e-4 for exact_linear at dt = 0.1 s in the quick run)
    EXPECT_LT(liver.at("reference_check_midpoint_vs_exact_linear").get<double>(), 1e-6) << hist;
  }
  EXPECT_LT(s.at("liver").at("nodal_force").at("path_check").get<double>(), 1e-6);
  EXPECT_FALSE(s.at("liver").contains("pk2"));

  tmlab::H5File h5 = tmlab::H5File::open_read((out / "hereditary.h5").string());
  for (const char* d : {"/sweep/ramp_hold/midpoint/error", "/sweep/random/exact_linear/dt_over_tau",
                        "/amplification/midpoint_a", "/liver/nodal_force/force_ref",
                        "/liver/nodal_force/backward_euler/error", "/haptic/tau"})
    EXPECT_TRUE(h5.exists(d)) << d;
  EXPECT_EQ(h5.read_double("/sweep/sine_w1/midpoint/error").size(), 9u);  // quick sweep: 10^(k/2), k = -6..2
}

TEST_F(CliHereditary, BadInputIsRefusedWithAClearMessage) {
  const Result g = run("hereditary --histories ramp_hold,steps --no-liver --results '" + dir_.string() + "'");
  EXPECT_EQ(g.status, 1) << g.output;
  EXPECT_NE(g.output.find("unknown history group 'steps'"), std::string::npos) << g.output;
  const Result o = run("hereditary --frobnicate");
  EXPECT_EQ(o.status, 2) << o.output;
  const Result p = run("hereditary --quick --histories sine --params '" + (dir_ / "missing.json").string() +
                       "' --results '" + dir_.string() + "' --no-plots");
  EXPECT_EQ(p.status, 1) << p.output;
  EXPECT_NE(p.output.find("missing.json"), std::string::npos) << p.output;
  EXPECT_FALSE(fs::exists(dir_ / "hereditary" / "summary.json"));  // a failed run never looks complete
  // Issue 26: --seed is a whole number under the one grammar ("2.0" and "1e3" used to be taken).
  for (const char* seed : {"2.0", "1e3", "0x10", "-1"}) {
    const Result s = run(std::string("hereditary --quick --no-liver --histories sine --no-plots --seed ") +
                         seed + " --results '" + (dir_ / "seed").string() + "'");
    EXPECT_EQ(s.status, 2) << seed << "\n" << s.output;
    EXPECT_NE(s.output.find("--seed needs a whole number"), std::string::npos) << s.output;
  }
  EXPECT_FALSE(fs::exists(dir_ / "seed"));
}

}  // namespace
