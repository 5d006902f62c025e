// `tmlab fit` as a user meets it (issue 14): the phantom converted and fitted end to end (fit.json
// with every field, fit.h5, the PNGs, the manifest, summary.json last), and a fit that cannot run
// leaving FAILED and no complete-looking result; bad specs and bad data refused naming the problem.
#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;

using tmlab::cli_test::Result;
using tmlab::cli_test::run_argv;
using tmlab::testing::read_file;

const fs::path kPhantomA1 = tmlab::cli_test::phantom_a1();

class CliFit : public tmlab::cli_test::CliTest {
 protected:
  fs::path convert() const {
    const Result c = tmlab({"data", "convert", kPhantomA1.string(), "--out", (dir_ / "data").string()});
    EXPECT_EQ(c.status, 0) << c.output;
    return dir_ / "data" / "EF10_0T_A1.csv";
  }
};

TEST_F(CliFit, FitsThePhantomWithErrorBars) {
  const fs::path csv = convert();
  const fs::path out = dir_ / "fit";
  const Result r =
      tmlab({"fit", csv.string(), "--model", "mooney_rivlin,poisson=0.49", "--out", out.string()});
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("iter"), std::string::npos) << r.output;  // progress on standard error
  EXPECT_NE(r.output.find("SE:"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(out / "summary.json"));
  const nlohmann::json j = nlohmann::json::parse(read_file(out / "fit.json"));
  ASSERT_EQ(j["parameters"].size(), 3u);
  for (const auto& p : j["parameters"]) {
    EXPECT_TRUE(p.contains("standard_error")) << p;
    EXPECT_TRUE(p.contains("interval95")) << p;
    EXPECT_TRUE(p.contains("unit")) << p;
  }
  EXPECT_EQ(j["parameters"][0]["name"], "c10");
  EXPECT_EQ(j["correlation"]["matrix"].size(), 2u);
  EXPECT_GT(j["forward_solves"].get<long>(), 10);
  EXPECT_GT(j["residual_rms_percent_of_peak"].get<double>(), 0.0);
  EXPECT_LT(j["residual_rms_percent_of_peak"].get<double>(), 10.0);
  EXPECT_TRUE(j.contains("aic") && j.contains("bic") && j.contains("wall_seconds") && j.contains("profile"));
  EXPECT_TRUE(fs::exists(out / "fit.h5"));
  EXPECT_TRUE(fs::exists(out / "manifest.json"));
  for (const char* png : {"fit_data_vs_model.png", "fit_residuals.png", "fit_profile.png"}) {
    ASSERT_TRUE(fs::exists(out / png)) << png << "\n" << r.output;
    EXPECT_EQ(read_file(out / png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  }
}

TEST_F(CliFit, AnnealingAndAPriorAreReported) {
  // Neo-Hookean on frictionless platens: nu barely moves the force, so a prior on it decides it.
  const fs::path csv = convert();
  const fs::path out = dir_ / "siman";
  const Result r =
      tmlab({"fit", csv.string(), "--model", "neo_hookean", "--global", "siman", "--siman-evaluations", "300",
             "--prior", "poisson=0.45:0.02", "--out", out.string(), "--no-plots", "--no-profile", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("siman global stage"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("note: prior on poisson"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("from the forward model 'platen_unconfined'"), std::string::npos) << r.output;
  const nlohmann::json j = nlohmann::json::parse(read_file(out / "fit.json"));
  EXPECT_EQ(j["global_stage"]["kind"], "siman");
  EXPECT_EQ(j["priors"][0]["parameter"], "poisson");
  EXPECT_GT(j["noise_sigma_N"].get<double>(), 0.0);
  // Bad values of the new options are usage errors.
  EXPECT_EQ(tmlab({"fit", csv.string(), "--model", "neo_hookean", "--global", "annealing"}).status, 2);
  EXPECT_EQ(tmlab({"fit", csv.string(), "--model", "neo_hookean", "--prior", "poisson=0.45"}).status, 2);
  EXPECT_EQ(tmlab({"fit", csv.string(), "--model", "neo_hookean", "--forward", "fem"}).status, 2);
  EXPECT_EQ(tmlab({"fit", csv.string(), "--model", "neo_hookean", "--mesh", "6"}).status, 2);
}

TEST_F(CliFit, AFitThatCannotRunLeavesFailed) {
  const fs::path csv = convert();
  // An Ogden term with alpha = 0 is not a law: no start can be evaluated, the fit fails inside.
  const fs::path out = dir_ / "ogden";
  const Result r =
      tmlab({"fit", csv.string(), "--model", "ogden,alpha1=0", "--out", out.string(), "--no-plots"});
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("cannot be evaluated"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "FAILED")) << r.output;
  EXPECT_FALSE(fs::exists(out / "summary.json"));
  EXPECT_FALSE(fs::exists(out / "fit.json"));
}

TEST_F(CliFit, AnInterruptedFitLeavesInterruptedAndNoResult) {
  const fs::path csv = convert();
  const fs::path out = dir_ / "stopped";
  // SIGTERM raised by the driver itself right after its first checkpoint, the one after the global
  // stage (the deterministic stop point of core/base/interrupt.hpp): the fit stops before its local
  // stage.
  ::setenv("TMLAB_TEST_STOP_AFTER_PROGRESS", "1:SIGTERM", 1);
  const Result r = tmlab({"fit", csv.string(), "--model", "mooney_rivlin,poisson=0.49", "--out", out.string(),
                          "--checkpoint-every", "1"});
  ::unsetenv("TMLAB_TEST_STOP_AFTER_PROGRESS");
  EXPECT_EQ(r.status, 128 + 15) << r.output;
  EXPECT_NE(r.output.find("SIGTERM received before local fit 1"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(out / "INTERRUPTED")) << r.output;
  EXPECT_NE(read_file(out / "INTERRUPTED").find("SIGTERM"), std::string::npos);
  EXPECT_NE(read_file(out / "INTERRUPTED").find("checkpoint after the global stage"), std::string::npos)
      << read_file(out / "INTERRUPTED");
  EXPECT_FALSE(fs::exists(out / "summary.json"));
  EXPECT_FALSE(fs::exists(out / "fit.json"));
  EXPECT_FALSE(fs::exists(out / "RUNNING"));
}

TEST_F(CliFit, BadSpecsAndDataAreRefused) {
  const fs::path csv = convert();
  Result r = tmlab({"fit", csv.string(), "--model", "rubber"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("unknown law 'rubber'"), std::string::npos) << r.output;
  r = tmlab({"fit", csv.string(), "--model", "neo_hookean", "--fix", "poisson=0.7"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("outside the bounds"), std::string::npos) << r.output;
  r = tmlab({"fit", csv.string(), "--model", "neo_hookean+prony:1"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("Prony terms"), std::string::npos) << r.output;
  r = tmlab({"fit", csv.string()});
  EXPECT_EQ(r.status, 2) << r.output;
  r = tmlab({"fit", csv.string(), "--model", "yeoh", "--cost", "l2"});
  EXPECT_EQ(r.status, 2) << r.output;
  // Data whose force is zero everywhere: refused before any result directory is made.
  std::string text = read_file(csv);
  std::ofstream(dir_ / "data" / "zero.json") << read_file(dir_ / "data" / "EF10_0T_A1.json");
  {
    std::ofstream z(dir_ / "data" / "zero.csv");
    z << "time_s,displacement_m,force_N\n0,0,0\n1,0.001,0\n2,0.002,0\n";
  }
  r = tmlab(
      {"fit", (dir_ / "data" / "zero.csv").string(), "--model", "yeoh", "--out", (dir_ / "z").string()});
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("the force is zero at every sample"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "z" / "summary.json"));
}

}  // namespace
