// `tmlab fit` as a user meets it (issue 14): the phantom converted and fitted end to end (fit.json
// with every field, fit.h5, the PNGs, the manifest, summary.json last), and a fit that cannot run
// leaving FAILED and no complete-looking result; bad specs and bad data refused naming the problem.
#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
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

TEST_F(CliFit, RelaxationBandsOrderThePronyTimes) {
  // A ramp-and-hold set (the discover benchmark's sphere-indentation noise-only set, Prony times
  // 0.5 and 15 s, whose closed form, Lee-Radok, carries Prony terms) fitted with
  // --relaxation-bands 0.5,1: tau1 and tau2 in ordered, disjoint bands, tau2's ceiling the longest
  // test's duration, each parameter's bounds and edge in fit.json, the option in the manifest.
  const fs::path bench = dir_ / "bench";
  const Result w = tmlab({"discover", "--benchmark", "--rig", "sphere_indentation", "--only", "noise_only",
                          "--write-sets", "--out", bench.string()});
  ASSERT_EQ(w.status, 0) << w.output;
  fs::path full;
  for (const auto& e : fs::directory_iterator(bench / "sets"))
    if (e.path().extension() == ".csv") full = e.path();
  ASSERT_FALSE(full.empty());
  // Lee-Radok covers loading and hold: each test's samples up to the start of its unloading.
  const fs::path csv = dir_ / "hold.csv";
  {
    std::ifstream in(full);
    std::ofstream o(csv);
    std::string line, test;
    std::getline(in, line);
    o << line << "\n";
    double peak = -1.0;
    bool unloading = false;
    while (std::getline(in, line)) {
      const auto c1 = line.find(','), c2 = line.find(',', c1 + 1), c3 = line.find(',', c2 + 1);
      const std::string id = line.substr(0, c1);
      const double d = std::stod(line.substr(c2 + 1, c3 - c2 - 1));
      if (id != test) test = id, peak = -1.0, unloading = false;
      unloading = unloading || d < peak;
      peak = std::max(peak, d);
      if (!unloading) o << line << "\n";
    }
  }
  std::ofstream(fs::path(csv).replace_extension(".json"))
      << read_file(fs::path(full).replace_extension(".json"));
  const fs::path out = dir_ / "banded";
  const Result r = tmlab({"fit", csv.string(), "--model", "stvk+prony:2,poisson=0.49", "--relaxation-bands",
                          "0.5,1", "--no-plots", "--no-profile", "--quiet", "--out", out.string()});
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(read_file(out / "fit.json"));
  nlohmann::json tau1, tau2;
  for (const auto& p : j["parameters"]) {
    EXPECT_TRUE(p.contains("bounds") && p.contains("at_bound")) << p;
    if (p["name"] == "tau1") tau1 = p;
    if (p["name"] == "tau2") tau2 = p;
  }
  ASSERT_TRUE(tau1.is_object() && tau2.is_object()) << j["parameters"];
  EXPECT_LE(tau1["bounds"][1].get<double>(), tau2["bounds"][0].get<double>() * (1 + 1e-12));
  EXPECT_GT(tau1["bounds"][0].get<double>(), 0.0);
  EXPECT_GE(tau1["value"].get<double>(), tau1["bounds"][0].get<double>());
  EXPECT_LE(tau2["value"].get<double>(), tau2["bounds"][1].get<double>());
  const nlohmann::json m = nlohmann::json::parse(read_file(out / "manifest.json"));
  EXPECT_NE(m.dump().find("\"relaxation_bands\":\"0.5,1\""), std::string::npos) << m.dump();
  // Refused: one number, a non-positive factor, a model without Prony terms.
  Result bad = tmlab({"fit", csv.string(), "--model", "stvk+prony:2", "--relaxation-bands", "0.5"});
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("FLOOR,CEILING"), std::string::npos) << bad.output;
  bad = tmlab({"fit", csv.string(), "--model", "stvk+prony:2", "--relaxation-bands", "0,1"});
  EXPECT_EQ(bad.status, 2) << bad.output;
  bad = tmlab({"fit", csv.string(), "--model", "stvk", "--relaxation-bands", "0.5,1"});
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("needs Prony terms"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("e.g. stvk+prony:2"), std::string::npos) << bad.output;  // the SPEC syntax
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

/// `csv` (tmlab-measured/1, force_N its third column) with the sign of every force flipped, written
/// beside it as NAME_flipped.csv + .json; returns its path.
fs::path flip_force(const fs::path& csv) {
  const fs::path dir = csv.parent_path(), out = dir / (csv.stem().string() + "_flipped.csv");
  std::ifstream in(csv);
  std::ofstream o(out);
  bool header_seen = false;
  for (std::string line; std::getline(in, line);) {
    const bool data = header_seen && !line.empty() && line[0] != '#';
    header_seen = header_seen || (!line.empty() && line[0] != '#');
    if (data) {
      const std::size_t a = line.find(',') + 1, b = line.find(',', a) + 1;
      line.insert(b, "-");
      if (line.compare(b, 2, "--") == 0) line.erase(b, 2);
    }
    o << line << "\n";
  }
  std::ofstream(dir / (csv.stem().string() + "_flipped.json"))
      << read_file(dir / (csv.stem().string() + ".json"));
  return out;
}

TEST_F(CliFit, AForceOfTheWrongSignIsRefusedBeforeAnyResult) {
  // Issue 26: compression data with a negative force crashed a St VK fit in the profile likelihood (SIGSEGV,
  // a stale RUNNING) and with --no-profile "fitted" E = 3.5e-12 Pa.
  const fs::path csv = flip_force(convert());
  for (const bool profile : {true, false}) {
    const fs::path out = dir_ / (profile ? "with_profile" : "no_profile");
    std::vector<std::string> args = {"fit",   csv.string(), "--model",   "neo_hookean",
                                     "--out", out.string(), "--no-plots"};
    if (!profile) args.push_back("--no-profile");
    const Result r = tmlab(args);
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find(csv.string() + ": test 1 (unconfined_compression): force must be positive in "
                                           "compression"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("samples are negative; flip the sign of force_N"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << r.output;  // refused before the result directory
  }
}

TEST_F(CliFit, AValueGivenTwiceIsRefusedNamingBoth) {
  const fs::path csv = convert();
  const auto refused = [&](const std::vector<std::string>& extra, const std::string& what) {
    std::vector<std::string> args = {"fit", csv.string(), "--out", (dir_ / "twice").string(), "--no-plots"};
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = tmlab(args);
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "twice")) << r.output;
  };
  refused({"--model", "neo_hookean,poisson=0.3", "--fix", "poisson=0.45"},
          "'poisson' is fixed twice: 0.3 in --model 'neo_hookean,poisson=0.3' and 0.45 by --fix");
  refused({"--model", "neo_hookean", "--fix", "poisson=0.45", "--fix", "poisson=0.4"},
          "--fix poisson is given twice (0.45 and 0.4)");
  refused({"--model", "neo_hookean,poisson=0.45,poisson=0.4"}, "'poisson' is fixed twice (0.45 and 0.4)");
  refused({"--model", "neo_hookean", "--prior", "poisson=0.45:0.02", "--prior", "poisson=0.4:0.05"},
          "two priors on 'poisson' (mean 0.45, sd 0.02 and mean 0.4, sd 0.05)");
}

TEST_F(CliFit, NumbersFollowTheStrictGrammarEverywhere) {
  const fs::path csv = convert();
  const auto refused = [&](const std::vector<std::string>& extra, int status, const std::string& what) {
    std::vector<std::string> args = {"fit", csv.string(), "--out", (dir_ / "n").string(), "--no-plots"};
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = tmlab(args);
    EXPECT_EQ(r.status, status) << r.output;
    EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "n")) << r.output;
  };
  refused({"--model", "neo_hookean", "--fix", "poisson=0x0.8p-1"}, 2, "--fix poisson needs a number");
  refused({"--model", "neo_hookean,poisson=0x0.8p-1"}, 1, "--model 'neo_hookean,poisson=0x0.8p-1'");
  refused({"--model", "neo_hookean,young= 1.9e4"}, 1, "is not a number");
  refused({"--model", "ogden:2.0"}, 1, "the number of Ogden terms must be a whole number");
  refused({"--model", "neo_hookean", "--starts", " 12"}, 2, "--starts needs a whole number");
  refused({"--model", "neo_hookean", "--starts", "12.0"}, 2, "--starts needs a whole number");
  refused({"--model", "neo_hookean", "--local-runs", "0x3"}, 2, "--local-runs needs a whole number");
  refused({"--model", "neo_hookean", "--seed", "1e3"}, 2, "--seed needs a whole number");
  refused({"--model", "neo_hookean", "--forward", "fe_rig", "--mesh", "6,2.5"}, 2,
          "--mesh LAYERS needs a whole number");
  refused({"--model", "neo_hookean", "--noise", ".5"}, 2, "--noise needs a number");
}

TEST_F(CliFit, TheLocalRunsThatRanAreRecorded) {
  const fs::path csv = convert();
  const fs::path out = dir_ / "runs";
  const Result r = tmlab({"fit", csv.string(), "--model", "neo_hookean", "--starts", "3", "--local-runs",
                          "100", "--out", out.string(), "--no-plots", "--no-profile", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(read_file(out / "fit.json"));
  EXPECT_EQ(j["global_stage"]["local_runs"], 3) << j["global_stage"];
  EXPECT_EQ(j["global_stage"]["local_runs_requested"], 100) << j["global_stage"];
  EXPECT_NE(j["notes"].dump().find("--local-runs 100 asked for more"), std::string::npos) << j["notes"];
  EXPECT_NE(r.output.find("note: --local-runs 100 asked for more"), std::string::npos) << r.output;
}

TEST_F(CliFit, ResumeOfAFinishedFitSaysItFinished) {
  const fs::path csv = convert();
  const fs::path out = dir_ / "done";
  const std::vector<std::string> args = {"fit",        csv.string(), "--model",      "neo_hookean", "--out",
                                         out.string(), "--no-plots", "--no-profile", "--quiet"};
  ASSERT_EQ(tmlab(args).status, 0);
  const std::string summary = read_file(out / "summary.json");
  std::vector<std::string> resume = args;
  resume.push_back("--resume");
  const Result r = tmlab(resume);
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("nothing to resume: " + out.string() +
                          " holds a complete fit (summary.json); run without --resume to redo it"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("stopped before writing"), std::string::npos) << r.output;
  EXPECT_EQ(read_file(out / "summary.json"), summary);  // the result is left as it was
  EXPECT_FALSE(fs::exists(out / "RUNNING"));
}

/// A tiny platen data set (20 x 20 x 10 mm block between bonded platens, 10 % strain in 1 s, 6
/// samples, forces of a neo-Hookean E = 5 kPa block roughly): an FE-rig fit of it on a 2 x 2 x 2
/// rig takes a second.
fs::path write_block_data(const fs::path& dir) {
  fs::create_directories(dir);
  const fs::path csv = dir / "block.csv";
  {
    std::ofstream o(csv);
    o << "time_s,displacement_m,force_N\n";
    for (int i = 0; i <= 5; ++i)
      o << 0.2 * i << "," << 2e-4 * i << "," << (i == 0 ? 0.0 : 0.045 * i + 0.0007 * i * i) << "\n";
  }
  std::ofstream(dir / "block.json")
      << R"({"format": "tmlab-measured/1", "name": "block", "test": "unconfined_compression",
             "sample": {"shape": "block", "size_m": [0.02, 0.02, 0.01], "platens": "bonded"}})";
  return csv;
}

TEST_F(CliFit, AnFeRigFitReportsItsDiscretisationShift) {
  const fs::path csv = write_block_data(dir_ / "block");
  const fs::path out = dir_ / "fe";
  const Result r = tmlab({"fit", csv.string(), "--model", "neo_hookean,poisson=0.45", "--forward", "fe_rig",
                          "--mesh", "2,2", "--starts", "2", "--local-runs", "1", "--no-profile", "--no-plots",
                          "--out", out.string()});
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("discretisation check: one solve on the refined rig 4,4"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("discretisation shift"), std::string::npos) << r.output;
  const nlohmann::json j = nlohmann::json::parse(read_file(out / "fit.json"));
  ASSERT_TRUE(j.contains("discretisation")) << j.dump(1);
  const auto& d = j["discretisation"];
  for (const char* k : {"method", "refine_ratio", "option", "rig", "refined_rig", "force_change_rms_N",
                        "force_change_max_N", "refined_solve_seconds", "warning_rule", "warnings"})
    EXPECT_TRUE(d.contains(k)) << k;
  EXPECT_EQ(d["refine_ratio"].get<double>(), 2.0);
  EXPECT_EQ(d["rig"]["cells"], 2);
  EXPECT_EQ(d["refined_rig"]["cells"], 4);
  EXPECT_EQ(d["refined_rig"]["layers"], 4);
  EXPECT_GT(d["force_change_rms_N"].get<double>(), 0.0);  // bonded platens: the mesh matters
  const auto& young = j["parameters"][0];
  ASSERT_EQ(young["name"], "young");
  ASSERT_TRUE(young.contains("discretisation")) << young;
  for (const char* k : {"shift", "shift_relative", "shift_per_standard_error",
                        "interval95_with_discretisation", "warning", "refined_mesh", "option"})
    EXPECT_TRUE(young["discretisation"].contains(k)) << k;
  EXPECT_TRUE(young["discretisation"]["shift"].is_number());
  EXPECT_NE(young["discretisation"]["option"].get<std::string>().find("--refine-ratio 2"), std::string::npos);
  EXPECT_TRUE(j["parameters"][1]["discretisation"]["shift"].is_null());  // poisson is fixed
  // Every warning is printed and in the notes.
  for (const auto& w : d["warnings"]) {
    EXPECT_NE(r.output.find("WARNING: " + w.get<std::string>()), std::string::npos) << r.output;
    EXPECT_NE(j["notes"].dump().find(w.get<std::string>()), std::string::npos);
  }
  // Off: no block, no column.
  const fs::path off = dir_ / "fe-off";
  const Result r2 = tmlab({"fit", csv.string(), "--model", "neo_hookean,poisson=0.45", "--forward", "fe_rig",
                           "--mesh", "2,2", "--starts", "2", "--local-runs", "1", "--no-profile",
                           "--no-plots", "--discretisation-check", "off", "--out", off.string()});
  ASSERT_EQ(r2.status, 0) << r2.output;
  const nlohmann::json j2 = nlohmann::json::parse(read_file(off / "fit.json"));
  EXPECT_FALSE(j2.contains("discretisation"));
  EXPECT_FALSE(j2["parameters"][0].contains("discretisation"));
  EXPECT_EQ(r2.output.find("discretisation"), std::string::npos) << r2.output;
}

TEST_F(CliFit, DiscretisationOptionsOutsideAnFeRigFitAreRefused) {
  const fs::path csv = write_block_data(dir_ / "block");
  const auto refused = [&](const std::vector<std::string>& extra, const std::string& what) {
    std::vector<std::string> args = {"fit",   csv.string(),          "--model",   "neo_hookean,poisson=0.45",
                                     "--out", (dir_ / "x").string(), "--no-plots"};
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = tmlab(args);
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(what), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "x")) << r.output;
  };
  refused({"--discretisation-check", "on"},
          "--discretisation-check on is for the FE rig forward model (--forward fe_rig): this fit's forward "
          "model is the closed form 'platen_unconfined'");
  refused({"--refine-ratio", "3"}, "--refine-ratio is for the FE rig forward model");
  refused({"--forward", "fe_rig", "--mesh", "2,2", "--refine-ratio", "1"}, "--refine-ratio");
  refused({"--forward", "fe_rig", "--mesh", "2,2", "--refine-ratio", "1.1"}, "unrefined after rounding");
  refused({"--forward", "fe_rig", "--mesh", "2,2", "--discretisation-check", "off", "--refine-ratio", "3"},
          "not with --discretisation-check off");
  refused({"--forward", "fe_rig", "--discretisation-check", "maybe"}, "--discretisation-check");
}

}  // namespace
