// Every tmlab command's option table (command_specs.hpp): its help block lists every option of it,
// `tmlab help` lists every command, and no command's sources name an option outside its table.
#include "apps/tmlab/command_specs.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace tmlab::cli {
namespace {

namespace fs = std::filesystem;

TEST(CommandSpecs, HelpListsEveryOptionOfEveryCommand) {
  const std::string all = usage_text();
  std::set<std::string> names;
  for (const CommandSpec& c : command_specs()) {
    EXPECT_TRUE(names.insert(c.name).second) << "two tables for " << c.name;
    const std::string h = command_help(c);
    EXPECT_EQ(h.rfind("  " + c.name, 0), 0u) << h;
    EXPECT_NE(all.find(h), std::string::npos) << c.name;
    std::set<std::string> options;
    for (const OptionSpec& o : c.options) {
      EXPECT_TRUE(options.insert(o.name).second) << c.name << " declares " << o.name << " twice";
      EXPECT_EQ(o.name.rfind("--", 0), 0u) << o.name;
      EXPECT_FALSE(o.help.empty()) << c.name << " " << o.name;
      EXPECT_NE(h.find("      " + o.name + (o.value.empty() ? "" : " " + o.value)), std::string::npos)
          << c.name << " help lacks " << o.name << "\n"
          << h;
    }
  }
  for (const char* c :
       {"demo",       "run",           "compare",     "cases",    "mesh info", "mesh check",   "paper",
        "hereditary", "workprecision", "depth-limit", "realtime", "verify",    "data convert", "data show",
        "rig",        "converge",      "fit",         "bench",    "discover",  "version",      "help"})
    EXPECT_EQ(names.count(c), 1u) << c;
  EXPECT_EQ(specs_of("data").size(), 2u);
  EXPECT_EQ(specs_of("fit").size(), 1u);
  EXPECT_TRUE(specs_of("fi").empty());
}

/// The options named in a source file ("--name" anywhere: code, messages, comments).
std::set<std::string> options_named(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  const std::string text = s.str();
  std::set<std::string> out;
  const std::regex option("(^|[^A-Za-z0-9_-])(--[a-zA-Z][a-zA-Z0-9-]*)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), option); it != std::sregex_iterator(); ++it)
    out.insert((*it)[2].str());
  return out;
}

TEST(CommandSpecs, NoCommandReadsAnOptionOutsideItsTable) {
  const fs::path dir = fs::path(TMLAB_SOURCE_DIR) / "apps" / "tmlab";
  // Each command's sources -> the tables of the commands they implement.
  const std::map<std::string, std::vector<std::string>> files = {
      {"cmd_run.cpp", {"demo", "run"}},
      {"cmd_compare.cpp", {"compare"}},
      {"cmd_mesh.cpp", {"cases", "mesh info", "mesh check", "mesh quadratic"}},
      {"cmd_paper.cpp", {"paper"}},
      {"cmd_hereditary.cpp", {"hereditary"}},
      {"cmd_workprecision.cpp", {"workprecision"}},
      {"cmd_depth_limit.cpp", {"depth-limit"}},
      {"cmd_realtime.cpp", {"realtime"}},
      {"cmd_verify.cpp", {"verify"}},
      {"cmd_data.cpp", {"data convert", "data show"}},
      {"cmd_rig.cpp", {"rig"}},
      {"rig_options.cpp", {"rig"}},
      {"cmd_converge.cpp", {"converge"}},
      {"cmd_fit.cpp", {"fit"}},
      {"fit_request.cpp", {"fit"}},
      {"cmd_bench.cpp", {"bench"}},
      {"cmd_discover.cpp", {"discover"}}};
  std::map<std::string, CommandSpec> specs;
  for (CommandSpec& c : command_specs()) specs.emplace(c.name, std::move(c));
  for (const auto& [file, commands] : files) {
    ASSERT_TRUE(fs::is_regular_file(dir / file)) << file;
    // --help: every command's (main.cpp); --prefix: npm's, in realtime's install hint.
    std::set<std::string> declared = {"--help", "--prefix"};
    for (const std::string& c : commands)
      for (const OptionSpec& o : specs.at(c).options) declared.insert(o.name);
    for (const std::string& o : options_named(dir / file))
      EXPECT_EQ(declared.count(o), 1u) << file << " names " << o << ", which is not in its table";
  }
}

TEST(CommandSpecs, ConvergeTakesEveryRigOptionOfTheSampleMeshAndMaterial) {
  // rig_options.cpp reads them for both commands (checked against rig's table above).
  const CommandSpec rig = specs_of("rig").at(0), converge = specs_of("converge").at(0);
  for (const OptionSpec& o : rig.options) {
    if (o.name == "--out" || o.name == "--overwrite" || o.name == "--data" || o.name == "--test") continue;
    EXPECT_NE(converge.find(o.name), nullptr) << o.name;
  }
}

}  // namespace
}  // namespace tmlab::cli
