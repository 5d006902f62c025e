// The verification framework: measurements are judged by the case's tolerances (a missing metric
// fails, a wrong order fails, a good finest error with a wrong order fails), fitted orders are exact
// on power laws, and the report files are complete. (Case files: test_case_spec.cpp.)
#include "verification/harness/convergence.hpp"
#include "verification/harness/evaluate.hpp"
#include "verification/harness/report.hpp"
#include "verification/harness/runner.hpp"
#include "verification/harness/tests/harness_test_support.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace tmlab::verify::test {
namespace {

namespace fs = std::filesystem;

TEST(Convergence, FittedOrderIsExactOnAPowerLaw) {
  std::vector<double> h{0.4, 0.2, 0.1, 0.05}, e;
  for (double x : h) e.push_back(3.0 * std::pow(x, 2.5));
  EXPECT_NEAR(fitted_order(h, e), 2.5, 1e-12);
  e[0] = 1.0;  // a pre-asymptotic coarse point: excluded with last = 3
  EXPECT_NEAR(fitted_order(h, e, 3), 2.5, 1e-12);
  EXPECT_GT(std::abs(fitted_order(h, e) - 2.5), 0.1);
  for (double o : pairwise_orders(h, std::vector<double>{1, 0.25, 0.0625, 0.015625}))
    EXPECT_NEAR(o, 2.0, 1e-12);
  EXPECT_THROW(fitted_order({0.1}, {1.0}), Error);
  EXPECT_THROW(fitted_order({0.1, 0.05}, {1.0, 0.0}), Error);
}

VerificationCase power_case() {
  VerificationCase c;
  c.name = "p";
  c.kind = "k";
  c.checks.push_back({"e", MetricCheck::Bound::Max, 1e-3, "why"});
  c.checks.push_back({"d", MetricCheck::Bound::Min, 0.0, "why"});
  c.convergence.push_back({"s", 2.0, 0.1, 0, 1e-3, "why"});
  return c;
}

Measurements power_measurements(double order, double constant) {
  Measurements m;
  m.set("e", 1e-4);
  m.set("d", 0.5);
  Series s;
  for (double h : {0.1, 0.05, 0.025}) {
    s.x.push_back(h);
    s.y.push_back(constant * std::pow(h, order));
  }
  m.series["s"] = s;
  return m;
}

TEST(Evaluate, PassesOnlyWhenEveryCheckHolds) {
  const auto c = power_case();
  EXPECT_EQ(evaluate(c, power_measurements(2.0, 1.0)).status, Status::Pass);
  EXPECT_EQ(evaluate(c, power_measurements(2.0, 1.0)).primary()->kind, "finest");
  // right order, but converging to a wrong answer (finest error too large); the headline is the
  // failed check
  const auto wrong = evaluate(c, power_measurements(2.0, 100.0));
  EXPECT_EQ(wrong.status, Status::Fail);
  EXPECT_EQ(wrong.primary()->kind, "finest");
  EXPECT_FALSE(wrong.primary()->passed);
  // small errors but the wrong order
  const auto order = evaluate(c, power_measurements(1.0, 0.01));
  EXPECT_EQ(order.status, Status::Fail);
  EXPECT_EQ(order.primary()->kind, "order");
  auto m = power_measurements(2.0, 1.0);
  m.metrics.erase("e");  // a missing metric never passes
  const auto r = evaluate(c, m);
  EXPECT_EQ(r.status, Status::Fail);
  EXPECT_FALSE(r.outcomes[0].passed);
  m = power_measurements(2.0, 1.0);
  m.set("d", -1e-9);  // a min bound
  EXPECT_EQ(evaluate(c, m).status, Status::Fail);
  m.set("d", std::nan(""));
  EXPECT_EQ(evaluate(c, m).status, Status::Fail);
}

TEST(Runner, SelectsBySuiteNameAndLabelAndRunsWithErrorsCaught) {
  TempDir tmp;
  for (const char* n : {"a-fast", "b-full"}) {
    std::string s = kGoodCase;
    if (std::string(n) == "b-full") s.replace(s.find("\"suite\": \"fast\""), 15, "\"suite\": \"full\"");
    write(tmp.path() / "cases" / n / "verify.json", s);
    write(tmp.path() / "cases" / n / "README.md", "x");
  }
  const auto cat = load_catalogue(tmp.path() / "cases");
  ASSERT_EQ(cat.size(), 2u);
  EXPECT_EQ(select(cat, {}).size(), 1u);
  EXPECT_EQ(select(cat, {true, {}, {}}).size(), 2u);
  EXPECT_EQ(select(cat, {false, {"b-full"}, {}}).size(), 1u);
  EXPECT_THROW(select(cat, {false, {"nope"}, {}}), Error);
  EXPECT_THROW(select(cat, {false, {}, {"nolabel"}}), Error);

  CheckRegistry reg;
  reg.add("test.power_law", [](const CheckContext& ctx) {
    const double p = ctx.vcase.parameters.at("order").get<double>();
    if (ctx.vcase.name == "b-full") throw Error("deliberate");
    return power_measurements(p, 1.0);
  });
  std::ostringstream log;
  const auto results = run_cases(cat, reg, {tmp.path(), tmp.path() / "work"}, log);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].status, Status::Pass);
  EXPECT_EQ(results[1].status, Status::Error);
  EXPECT_NE(log.str().find("[2/2] b-full"), std::string::npos);

  ReportInput in{cat, results, "tmlab verify --full", false, {}};
  const auto j = verification_json(in);
  EXPECT_EQ(j["passed"], 1);
  EXPECT_EQ(j["errors"], 1);
  EXPECT_EQ(j["cases"][0]["name"], "a-fast");
  EXPECT_NEAR(j["cases"][0]["observed_order"].get<double>(), 2.0, 1e-9);
  EXPECT_EQ(j["cases"][0]["expected_order"], 2.0);
  // The headline of a passing convergence case is its finest error (0.025^2) against finest_max.
  EXPECT_NEAR(j["cases"][0]["error"].get<double>(), 6.25e-4, 1e-15);
  EXPECT_EQ(j["cases"][0]["tolerance"], 1e-3);
  write_report(in, tmp.path() / "out");
  for (const char* f : {"report.md", "report.html", "verification.json", "results-table.md"})
    EXPECT_TRUE(fs::exists(tmp.path() / "out" / f)) << f;

  write(tmp.path() / "doc.md",
        "# x\n<!-- verification-results:begin -->\nold\n<!-- verification-results:end -->\nend\n");
  update_doc_table(tmp.path() / "doc.md", results_table(in));
  std::ifstream f(tmp.path() / "doc.md");
  const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("old"), std::string::npos);
  EXPECT_NE(text.find("| a-fast | PASS"), std::string::npos);
  EXPECT_NE(text.find("end\n"), std::string::npos);
  EXPECT_THROW(update_doc_table(tmp.path() / "out" / "report.md", "x"), Error);
}

}  // namespace
}  // namespace tmlab::verify::test
