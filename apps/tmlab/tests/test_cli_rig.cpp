// `tmlab rig`: a platen test written as a case file that `tmlab run` accepts, a measured data set's
// test (--data) driven by its displacement column, and clear refusals of impossible rigs (exit 1
// naming the field) and unknown tests (usage error, exit 2).
#include "cli_test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace {

namespace fs = std::filesystem;
using tmlab::cli_test::Result;
using tmlab::cli_test::run_argv;

using CliRig = tmlab::testing::TempDirTest;

TEST_F(CliRig, UnconfinedRigRunsAndReportsThePlatenForce) {
  const Result w =
      run_argv({"rig", "unconfined", "--out", (dir_ / "rig").string(), "--name", "phantom", "--depth",
                "0.003", "--cells", "4", "--layers", "3", "--E", "10000", "--nu", "0.3"},
               dir_ / "rig.log");
  ASSERT_EQ(w.status, 0) << w.output;
  ASSERT_TRUE(fs::exists(dir_ / "rig" / "phantom.json"));
  ASSERT_TRUE(fs::exists(dir_ / "rig" / "phantom.msh"));
  const Result r = run_argv({"run", (dir_ / "rig" / "phantom.json").string(), "--results",
                             (dir_ / "results").string(), "--no-plots"},
                            dir_ / "run.log");
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(dir_ / "results" / "phantom" / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  EXPECT_GT(std::abs(s["final_reactions_N"]["top_platen"][2].get<double>()), 0.0);
}

TEST_F(CliRig, IndentationRigRunsWithItsContactBody) {
  const Result w =
      run_argv({"rig", "indentation", "--out", (dir_ / "rig").string(), "--name", "ind", "--depth", "0.0005",
                "--cells", "6", "--layers", "4", "--steps-per-segment", "4"},
               dir_ / "rig.log");
  ASSERT_EQ(w.status, 0) << w.output;
  const Result r = run_argv(
      {"run", (dir_ / "rig" / "ind.json").string(), "--results", (dir_ / "results").string(), "--no-plots"},
      dir_ / "run.log");
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(dir_ / "results" / "ind" / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  const nlohmann::json& body = s["contact"]["bodies"][0];
  EXPECT_EQ(body["name"], "indenter");
  EXPECT_EQ(body["type"], "sphere");
  const double fz = body["final_force_N"][2].get<double>();
  EXPECT_GT(fz, 0.0);
  EXPECT_GE(body["final_active_nodes"].get<int>(), 1);
  // The indenter's force is carried by the bonded bottom.
  EXPECT_NEAR(fz, s["final_reactions_N"]["bottom"][2].get<double>(), 1e-6 * fz);
}

/// A tmlab-measured/1 data set in the test's directory: NAME.csv and NAME.json.
fs::path write_data(const fs::path& dir, const std::string& name, const std::string& csv,
                    const std::string& meta) {
  std::ofstream(dir / (name + ".json")) << meta;
  std::ofstream(dir / (name + ".csv")) << csv;
  return dir / (name + ".csv");
}

TEST_F(CliRig, DataSetTestBecomesARigDrivenByItsDisplacementColumn) {
  // Two unconfined compression tests of a 20 mm x 10 mm cylinder; test "b" ramps to 0.8 mm, holds,
  // and unloads half-way: no ramp-hold or cycle history the options could give.
  const fs::path csv =
      write_data(dir_, "disc",
                 "test_id,time_s,displacement_m,force_N\n"
                 "a,0,0,0\na,1,0.0005,0.1\n"
                 "b,5,0,0\nb,6,0.0004,0.05\nb,7,0.0008,0.1\nb,9,0.0008,0.09\nb,10,0.0004,0.04\n",
                 R"({"format": "tmlab-measured/1", "name": "disc", "test": "unconfined_compression",
    "sample": {"shape": "cylinder", "radius_m": 0.01, "height_m": 0.01, "platens": "frictionless"}})");
  const Result several =
      run_argv({"rig", "--data", csv.string(), "--out", (dir_ / "rig").string()}, dir_ / "s.log");
  EXPECT_EQ(several.status, 2) << several.output;
  EXPECT_NE(several.output.find("--test ID (a, b)"), std::string::npos) << several.output;
  const Result unknown = run_argv(
      {"rig", "--data", csv.string(), "--test", "c", "--out", (dir_ / "rig").string()}, dir_ / "u.log");
  EXPECT_EQ(unknown.status, 1) << unknown.output;
  EXPECT_NE(unknown.output.find("no test 'c'"), std::string::npos) << unknown.output;
  const Result mixed = run_argv(
      {"rig", "--data", csv.string(), "--test", "b", "--depth", "0.001", "--out", (dir_ / "rig").string()},
      dir_ / "m.log");
  EXPECT_EQ(mixed.status, 2) << mixed.output;
  EXPECT_NE(mixed.output.find("--depth does not go with --data"), std::string::npos) << mixed.output;
  EXPECT_FALSE(fs::exists(dir_ / "rig"));

  const Result w = run_argv({"rig", "--data", csv.string(), "--test", "b", "--out", (dir_ / "rig").string(),
                             "--cells", "4", "--layers", "3", "--E", "10000", "--nu", "0.3"},
                            dir_ / "rig.log");
  ASSERT_EQ(w.status, 0) << w.output;
  std::ifstream cin(dir_ / "rig" / "disc-b.json");
  const nlohmann::json c = nlohmann::json::parse(cin);
  EXPECT_EQ(c["material"]["E"].get<double>(), 10000.0);
  EXPECT_EQ(c["solver"]["t_end"].get<double>(), 5.0);  // data time from the test's first sample
  const nlohmann::json* top = nullptr;
  for (const auto& b : c["boundary"])
    if (b["name"] == "top_platen") top = &b;
  ASSERT_NE(top, nullptr) << c.dump(1);
  // The platen follows the displacement column: a table of d / d_max at the data's times.
  EXPECT_EQ((*top)["function"]["type"], "table") << top->dump();
  const nlohmann::json want = {{0.0, 0.0}, {1.0, 0.5}, {2.0, 1.0}, {4.0, 1.0}, {5.0, 0.5}};
  EXPECT_EQ((*top)["function"]["points"], want) << top->dump();
  const Result r = run_argv({"run", (dir_ / "rig" / "disc-b.json").string(), "--results",
                             (dir_ / "results").string(), "--no-plots"},
                            dir_ / "run.log");
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(dir_ / "results" / "disc-b" / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  // At the end the platen is back at 0.4 mm: the force is compressive.
  EXPECT_GT(std::abs(s["final_reactions_N"]["top_platen"][2].get<double>()), 0.0);
}

TEST_F(CliRig, RefusesImpossibleRigsAndUnknownTests) {
  const Result deep =
      run_argv({"rig", "indentation", "--out", (dir_ / "x").string(), "--depth", "0.05"}, dir_ / "a.log");
  EXPECT_EQ(deep.status, 1) << deep.output;
  EXPECT_NE(deep.output.find("history"), std::string::npos) << deep.output;
  EXPECT_FALSE(fs::exists(dir_ / "x" / "indentation.json"));
  const Result unknown = run_argv({"rig", "shear", "--out", (dir_ / "x").string()}, dir_ / "b.log");
  EXPECT_EQ(unknown.status, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("uniaxial_tension"), std::string::npos) << unknown.output;
  const Result no_out = run_argv({"rig", "tension"}, dir_ / "c.log");
  EXPECT_EQ(no_out.status, 2) << no_out.output;
}

/// Every option is checked before anything is written (issue 26): each refusal names the option,
/// exits 2 (a malformed option) or 1 (a rig `tmlab run` would refuse), and leaves no folder.
TEST_F(CliRig, OptionsAreCheckedBeforeAnythingIsWritten) {
  const std::string out = (dir_ / "x").string();
  const std::string ogden0 =
      R"({"law": "ogden", "mu": [1000], "alpha": [0], "kappa": 100000, "density": 1000})";
  const std::string neo = R"({"law": "neo_hookean", "E": 3000, "nu": 0.45, "density": 1000})";
  struct Case {
    std::vector<std::string> args;
    int status;
    std::string says;
  };
  const std::vector<Case> cases = {
      {{"--cells", "400", "--layers", "400"}, 1, "384,000,000 tets"},
      {{"--cells", "400", "--layers", "400"}, 1, "the limit is 2,000,000 tets"},
      {{"--steps-per-segment", "1e8"}, 2, "--steps-per-segment needs a whole number"},
      {{"--steps-per-segment", "100000000"}, 2, "--steps-per-segment needs a whole number"},
      {{"--steps-per-segment", "200000", "--hold", "10"}, 1, "2,200,000 load steps; the limit is 1,000,000"},
      {{"--at", "nan,0"}, 2, "--at needs a number"},
      {{"--at", "0.01,"}, 2, "--at needs a number"},
      {{"--at", "0.5,0.5"},
       1,
       "--at (the indenter centre cx, cy): (500 mm, 500 mm) lies outside the top face"},
      {{"--at", "0.018,0"}, 1, "--at (the indenter centre cx, cy): (18 mm, 0 mm) is too close to the edge"},
      {{"--cells", "0x10"}, 2, "--cells needs a whole number"},
      {{"--cells", "1.5"}, 2, "--cells needs a whole number"},
      {{"--layers", " 4"}, 2, "--layers needs a whole number"},
      {{"--cycles", "2.0"}, 2, "--cycles needs a whole number"},
      {{"--E", "-1"}, 1, "key 'material.E'"},
      {{"--material", R"({"E": 3000, "nu": 0.45, "density": 1000, "colour": "red"})"}, 1, "colour"},
      {{"--material", ogden0, "--model", "hyperelastic_tl"}, 1, "key 'material.alpha'"},
      {{"--material", neo}, 1, "use model hyperelastic_tl"},
      {{"--model", "fast"}, 1, "model: must be 'tensor_mass', 'tl_oracle' or 'hyperelastic_tl'"},
      // The contact mesh rule (docs/rigs.md): its fields named, and not mixed with the explicit form.
      {{"--contact-cells", "0"}, 2, "--contact-cells"},
      {{"--contact-cells", "3", "--cells", "8"}, 2, "does not go with --cells, --layers, --grading"},
      {{"--refine", "0"}, 1, "refinement: must be in (0, 16]"},
      {{"--contact-cells", "200"}, 1, "contact_cells 200 (h = 0.01581 mm across a_max = 3.162 mm)"},
      {{"--indenter-contact", "sticky"}, 1, "--indenter-contact: unknown value 'sticky'"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args{"rig", "indentation", "--out", out};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const Result r = run_argv(args, dir_ / "log");
    EXPECT_EQ(r.status, c.status) << c.args[0] << " " << c.args[1] << ": " << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args[0] << " " << c.args[1] << ": " << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.args[0] << " " << c.args[1] << " left " << out;
  }
}

/// NAME.json and NAME.msh already in --out are refused (named) unless --overwrite; a data set's own
/// files are never written over, --overwrite or not (issue 26).
TEST_F(CliRig, ExistingFilesAreNotReplacedSilently) {
  const std::vector<std::string> rig{"rig", "unconfined", "--out", dir_.string(), "--name",
                                     "r",   "--cells",    "4",     "--layers",    "2"};
  ASSERT_EQ(run_argv(rig, dir_ / "a.log").status, 0);
  const std::string first = tmlab::testing::read_file(dir_ / "r.json");
  std::vector<std::string> other = rig;
  other.insert(other.end(), {"--E", "5000"});
  Result r = run_argv(other, dir_ / "b.log");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find((dir_ / "r.msh").string() + " already exists"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--overwrite"), std::string::npos) << r.output;
  EXPECT_EQ(tmlab::testing::read_file(dir_ / "r.json"), first);
  other.push_back("--overwrite");
  r = run_argv(other, dir_ / "c.log");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(tmlab::testing::read_file(dir_ / "r.json"), first);

  // --data disc.csv --out <its own folder>: the rig would be disc.json, the data set's metadata.
  const std::string meta = R"({"format": "tmlab-measured/1", "name": "disc", "test": "unconfined_compression",
    "sample": {"shape": "cylinder", "radius_m": 0.01, "height_m": 0.01, "platens": "frictionless"}})";
  const fs::path csv =
      write_data(dir_, "disc", "test_id,time_s,displacement_m,force_N\na,0,0,0\na,1,0.0005,0.1\n", meta);
  for (const bool overwrite : {false, true}) {
    std::vector<std::string> args{"rig", "--data", csv.string(), "--out", dir_.string(), "--cells", "4"};
    if (overwrite) args.push_back("--overwrite");
    r = run_argv(args, dir_ / "d.log");
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_NE(r.output.find((dir_ / "disc.json").string() + " is the input " + csv.parent_path().string()),
              std::string::npos)
        << r.output;
    EXPECT_EQ(tmlab::testing::read_file(dir_ / "disc.json"), meta);
    EXPECT_FALSE(fs::exists(dir_ / "disc.msh"));
  }
}

}  // namespace
