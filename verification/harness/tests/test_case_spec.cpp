// Case files (case_spec.hpp): a good verify.json is read completely; a bad one is an error naming
// verify.json and the key; the catalogue is every case directory, sorted; labels are looked up.
#include "verification/harness/case_spec.hpp"
#include "verification/harness/tests/harness_test_support.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace tmlab::verify::test {
namespace {

namespace fs = std::filesystem;

TEST(VerificationCaseSpec, ReadsAGoodCase) {
  TempDir tmp;
  write(tmp.path() / "c1" / "verify.json", kGoodCase);
  write(tmp.path() / "c1" / "README.md", "# c1\n");
  const auto c = load_case(tmp.path() / "c1");
  EXPECT_EQ(c.name, "c1");
  EXPECT_EQ(c.kind, "test.power_law");
  ASSERT_EQ(c.checks.size(), 1u);
  EXPECT_EQ(c.checks[0].limit, 1e-3);
  ASSERT_EQ(c.convergence.size(), 1u);
  EXPECT_EQ(c.convergence[0].fit_points, 3);
}

TEST(VerificationCaseSpec, RejectsBadCasesNamingTheKey) {
  TempDir tmp;
  const auto expect_error = [&](const std::string& text, const std::string& fragment, bool readme = true) {
    fs::remove_all(tmp.path() / "bad");
    write(tmp.path() / "bad" / "verify.json", text);
    if (readme) write(tmp.path() / "bad" / "README.md", "x");
    try {
      load_case(tmp.path() / "bad");
      ADD_FAILURE() << "no error for: " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("verify.json"), std::string::npos) << e.what();
    }
  };
  std::string s = kGoodCase;
  expect_error(std::string(s).replace(s.find("\"rationale\": \"because\""), 22, "\"why\": 1"), "checks[0]");
  expect_error(std::string(s).replace(s.find("\"suite\": \"fast\""), 15, "\"suite\": \"nightly\""), "suite");
  expect_error(std::string(s).replace(s.find("\"max\": 1e-3"), 11, "\"max\": 1e-3, \"min\": 0"),
               "exactly one");
  expect_error(std::string(s).replace(s.find("\"labels\""), 8, "\"lables\""), "lables");
  expect_error(std::string(s).replace(s.find("\"finest_max\": 1e-3"), 18, "\"finest_max\": -1"),
               "finest_max");
  expect_error("{\"title\": ", "verify.json");
  // README.md is required
  fs::remove_all(tmp.path() / "bad");
  write(tmp.path() / "bad" / "verify.json", kGoodCase);
  EXPECT_THROW(load_case(tmp.path() / "bad"), Error);
}

TEST(VerificationCaseSpec, ReadsEveryFieldAndDefaults) {
  TempDir tmp;
  write(tmp.path() / "c1" / "verify.json", kGoodCase);
  write(tmp.path() / "c1" / "README.md", "# c1\n");
  const auto c = load_case(tmp.path() / "c1");
  EXPECT_EQ(c.dir, tmp.path() / "c1");
  EXPECT_EQ(c.spec_file(), tmp.path() / "c1" / "verify.json");
  EXPECT_EQ(c.title, "t");
  EXPECT_EQ(c.what, "w");
  EXPECT_EQ(c.reference, "r");
  EXPECT_EQ(c.suite, "fast");
  EXPECT_EQ(c.parameters.at("order").get<double>(), 2.0);
  EXPECT_EQ(c.checks[0].metric, "e");
  EXPECT_EQ(c.checks[0].bound, MetricCheck::Bound::Max);
  EXPECT_EQ(c.checks[0].rationale, "because");
  EXPECT_EQ(c.convergence[0].series, "s");
  EXPECT_EQ(c.convergence[0].expected_order, 2.0);
  EXPECT_EQ(c.convergence[0].order_tolerance, 0.1);
  EXPECT_EQ(c.convergence[0].finest_max, 1e-3);
  EXPECT_TRUE(c.report.empty());
  EXPECT_TRUE(c.has_label("kernel"));
  EXPECT_FALSE(c.has_label("kern"));
  // A lower bound, and "report" metrics.
  std::string s = kGoodCase;
  s.replace(s.find("\"max\": 1e-3"), 11, "\"min\": 0.5");
  s.replace(s.find("\"kind\""), 6, "\"report\": [\"x\"], \"kind\"");
  write(tmp.path() / "c2" / "verify.json", s);
  write(tmp.path() / "c2" / "README.md", "# c2\n");
  const auto c2 = load_case(tmp.path() / "c2");
  EXPECT_EQ(c2.checks[0].bound, MetricCheck::Bound::Min);
  EXPECT_EQ(c2.checks[0].limit, 0.5);
  ASSERT_EQ(c2.report.size(), 1u);
  EXPECT_EQ(c2.report[0], "x");
}

TEST(VerificationCaseSpec, ACaseNeedsAJudgementAndGoodLabels) {
  TempDir tmp;
  write(tmp.path() / "bad" / "README.md", "x");
  std::string s = kGoodCase;
  const auto checks = s.find("\"checks\"");
  write(tmp.path() / "bad" / "verify.json", s.substr(0, checks) + "\"parameters2\": 0}");
  EXPECT_THROW(load_case(tmp.path() / "bad"), Error);  // unknown key
  const std::string no_judgement =
      s.substr(0, s.find(",\n  \"checks\"")) + "\n}";  // neither checks nor convergence
  write(tmp.path() / "bad" / "verify.json", no_judgement);
  try {
    load_case(tmp.path() / "bad");
    ADD_FAILURE() << "a case without checks or convergence was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("at least one entry"), std::string::npos) << e.what();
  }
  write(tmp.path() / "bad" / "verify.json",
        std::string(s).replace(s.find("[\"kernel\"]"), 10, "[\"Kernel Tests\"]"));
  EXPECT_THROW(load_case(tmp.path() / "bad"), Error);
}

TEST(VerificationCatalogue, IsEveryCaseDirectorySortedByName) {
  TempDir tmp;
  for (const char* n : {"b-case", "a-case", "c-case"}) {
    write(tmp.path() / "cases" / n / "verify.json", kGoodCase);
    write(tmp.path() / "cases" / n / "README.md", "x");
  }
  write(tmp.path() / "cases" / "not-a-case.txt", "files beside the cases are ignored");
  const auto cat = load_catalogue(tmp.path() / "cases");
  ASSERT_EQ(cat.size(), 3u);
  EXPECT_EQ(cat[0].name, "a-case");
  EXPECT_EQ(cat[1].name, "b-case");
  EXPECT_EQ(cat[2].name, "c-case");
  // A directory without verify.json, and a missing catalogue, are errors.
  fs::create_directories(tmp.path() / "cases" / "d-empty");
  EXPECT_THROW(load_catalogue(tmp.path() / "cases"), Error);
  EXPECT_THROW(load_catalogue(tmp.path() / "nowhere"), Error);
}

}  // namespace
}  // namespace tmlab::verify::test
