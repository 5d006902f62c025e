// The option-table mechanism: parsing against a table, ranges, defaults, options given twice,
// run-time defaults, the help block and the manifest values.
#include "apps/tmlab/options/option_help.hpp"
#include "apps/tmlab/options/option_table.hpp"
#include "apps/tmlab/options/parsed_options.hpp"

#include <gtest/gtest.h>

namespace tmlab::cli {
namespace {

CommandSpec sample() {
  return {"sample",
          {"FILE [options]"},
          "a sample command",
          {whole("--starts", "N", 1, 100, "starts").def("8").role(kResult),
           decimal("--tol", "R", open_closed(0.0, 1.0), "tolerance").role(kManifest),
           choice("--cost", {"least_squares", "l1"}, "the misfit").def("least_squares").role(kFingerprint),
           text("--fix", "NAME=VALUE", "fixed").repeat().role(kResult),
           whole_list("--cells", "N1,N2", 2, 64, "cells"),
           text_list("--laws", "L1,L2", "laws").role(kManifest), flag("--quick", "quick").role(kResult),
           text("--out", "DIR", "where"), numbers("--at", "CX,CY", 2, "where")}};
}

std::string usage_error(const std::vector<std::string>& args) {
  try {
    parse(sample(), args);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(OptionTable, ParsesTypedValuesAndDefaults) {
  const ParsedOptions p = parse(sample(), {"a.csv", "--starts", "12", "--tol", "0.5", "--fix", "E=1", "--fix",
                                           "nu=0.3", "--cells", "4,,9", "--quick"});
  EXPECT_EQ(p.positional, std::vector<std::string>{"a.csv"});
  EXPECT_EQ(p.whole("--starts"), 12);
  EXPECT_EQ(p.decimal("--tol"), 0.5);
  EXPECT_EQ(p.text("--cost"), "least_squares");  // the default
  EXPECT_FALSE(p.given("--cost"));
  EXPECT_EQ(p.all("--fix"), (std::vector<std::string>{"E=1", "nu=0.3"}));
  EXPECT_EQ(p.whole_list("--cells"), (std::vector<long long>{4, 9}));
  EXPECT_TRUE(p.flag("--quick"));
  EXPECT_EQ(p.text("--out"), "");
  const ParsedOptions d = parse(sample(), {});
  EXPECT_EQ(d.whole("--starts"), 8);
  EXPECT_THROW(d.decimal("--tol"), std::logic_error);  // no value and no default
}

TEST(OptionTable, RefusesNamingTheOption) {
  EXPECT_EQ(usage_error({"--colour", "red"}), "unknown option --colour");
  EXPECT_EQ(usage_error({"--starts"}), "option --starts needs a value");
  EXPECT_NE(usage_error({"--out", ""}).find("--out has an empty value: a result needs a folder"),
            std::string::npos);
  EXPECT_EQ(usage_error({"--starts", "2", "--starts", "3"}),
            "option --starts is given 2 times ('2' and '3'): give it once");
  EXPECT_EQ(usage_error({"--quick", "--quick"}), "option --quick is given 2 times: give it once");
  EXPECT_NE(usage_error({"--starts", "0"}).find("--starts needs a whole number"), std::string::npos);
  EXPECT_NE(usage_error({"--starts", "0x10"}).find("--starts needs a whole number"), std::string::npos);
  EXPECT_EQ(usage_error({"--tol", "0"}), "--tol must be in (0, 1] (got '0')");
  EXPECT_NE(usage_error({"--tol", ".5"}).find("--tol needs a number"), std::string::npos);
  EXPECT_EQ(usage_error({"--cost", "l2"}), "--cost must be least_squares or l1 (got 'l2')");
  EXPECT_NE(usage_error({"--cells", "4,99"}).find("--cells needs a whole number"), std::string::npos);
  EXPECT_EQ(usage_error({"--cells", ","}), "--cells needs a comma-separated list of whole numbers");
  EXPECT_EQ(usage_error({"--laws", ",,"}), "--laws needs a comma-separated list");
}

TEST(OptionTable, FixedCountNumbersAndAssignIfGiven) {
  const ParsedOptions p = parse(sample(), {"--at", "-1,2.5", "--tol", "0.5"});
  EXPECT_EQ(p.numbers("--at"), (std::vector<double>{-1.0, 2.5}));
  EXPECT_EQ(usage_error({"--at", "1"}), "--at needs 2 comma-separated numbers");
  EXPECT_NE(usage_error({"--at", "1,"}).find("--at needs a number"), std::string::npos);
  EXPECT_NE(usage_error({"--at", "nan,0"}).find("--at needs a number"), std::string::npos);
  double tol = 7.0, absent = 7.0;
  int starts = 3;
  p.assign_if_given("--tol", tol);
  EXPECT_THROW(p.assign_if_given("--at", absent), std::logic_error);  // the wrong kind is a bug
  EXPECT_EQ(tol, 0.5);
  EXPECT_EQ(absent, 7.0);
  p.assign_if_given("--starts", starts);  // not given: unchanged, though it has a default
  EXPECT_EQ(starts, 3);
}

TEST(OptionTable, ReadingAnUndeclaredOptionIsABug) {
  const ParsedOptions p = parse(sample(), {});
  EXPECT_THROW(p.given("--colour"), std::logic_error);
  EXPECT_THROW(p.whole("--cost"), std::logic_error);  // declared, but not a whole number
  EXPECT_THROW(p.flag("--starts"), std::logic_error);
}

TEST(OptionTable, RunTimeDefaultsAreChecked) {
  ParsedOptions p = parse(sample(), {});
  p.set_default("--tol", "0.25");
  EXPECT_EQ(p.decimal("--tol"), 0.25);
  EXPECT_THROW(p.set_default("--tol", "2"), UsageError);
  const ParsedOptions q = parse(sample(), {"--tol", "0.5"});
  ParsedOptions r = q;
  r.set_default("--tol", "0.25");
  EXPECT_EQ(r.decimal("--tol"), 0.5);                               // a given value wins
  EXPECT_THROW(whole("--n", "N", 1, 3, "n").def("4"), UsageError);  // a default out of its own range
}

TEST(OptionTable, ConfigHoldsTheOptionsOfEachRole) {
  const ParsedOptions p = parse(sample(), {"--tol", "0.5", "--fix", "E=1", "--laws", "a,b"});
  const nlohmann::json m = p.config(kManifest);
  EXPECT_EQ(m, (nlohmann::json{
                   {"starts", 8}, {"tol", 0.5}, {"fix", {"E=1"}}, {"laws", {"a", "b"}}, {"quick", false}}));
  const nlohmann::json f = p.config(kFingerprint);
  EXPECT_EQ(f,
            (nlohmann::json{{"starts", 8}, {"cost", "least_squares"}, {"fix", {"E=1"}}, {"quick", false}}));
  EXPECT_TRUE(parse(sample(), {}).config(kManifest)["tol"].is_null());  // neither given nor a default
}

TEST(OptionTable, HelpListsEveryOptionWithRangeAndDefault) {
  const std::string h = command_help(sample());
  EXPECT_EQ(h.rfind("  sample FILE [options]     a sample command\n", 0), 0u) << h;
  EXPECT_NE(h.find("      --starts N            starts (1..100, default 8)\n"), std::string::npos) << h;
  EXPECT_NE(h.find("      --tol R               tolerance (in (0, 1])\n"), std::string::npos) << h;
  EXPECT_NE(
      h.find(
          "      --cost least_squares|l1\n                            the misfit (default least_squares)\n"),
      std::string::npos)
      << h;
  EXPECT_NE(h.find("--fix NAME=VALUE      fixed (repeatable)"), std::string::npos) << h;
  for (const OptionSpec& o : sample().options)
    EXPECT_NE(h.find("      " + o.name), std::string::npos) << o.name;
}

TEST(OptionTable, Intervals) {
  EXPECT_TRUE(open(0, 1).contains(0.5));
  EXPECT_FALSE(open(0, 1).contains(0.0));
  EXPECT_TRUE(closed(0, 1).contains(1.0));
  EXPECT_FALSE(open_closed(0, 60).contains(0.0));
  EXPECT_TRUE(open_closed(0, 60).contains(60.0));
  EXPECT_EQ(positive().text(), "> 0");
  EXPECT_EQ(Interval{}.text(), "");
  EXPECT_EQ(open(0, 1e-6).text(), "(0, 1e-06)");
}

}  // namespace
}  // namespace tmlab::cli
