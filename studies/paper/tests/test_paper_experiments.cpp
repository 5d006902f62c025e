// The paper's liver experiments as case documents: every run of fig5/6/7 built from the shipped
// parameter file is a valid case, and bad parameter files are rejected with the key named.
#include "core/base/error.hpp"
#include "core/config/case_config.hpp"
#include "core/config/config_reader.hpp"
#include "studies/paper/paper_experiments.hpp"

#include <gtest/gtest.h>

#include <set>

namespace tmlab::tm {
namespace {

const std::string kRoot = TMLAB_SOURCE_DIR;
const std::string kParams = kRoot + "/cases/paper/xu2011_liver.json";

TEST(PaperExperiments, EveryRunOfEveryFigureIsAValidCase) {
  nlohmann::json params = ConfigReader::parse_file(kParams);
  for (const char* name : {"fig5", "fig6", "fig7"}) {
    const PaperFigure fig = paper_figure(name, params, kParams);
    ASSERT_FALSE(fig.runs.empty()) << name;
    std::set<std::string> ids;
    for (const auto& run : fig.runs) {
      EXPECT_TRUE(ids.insert(run.id).second) << "duplicate run id " << run.id;
      const CaseConfig c = parse_case(run.case_doc, kParams, {kRoot});
      EXPECT_TRUE(c.material.viscoelastic.enabled);
      EXPECT_EQ(c.material.viscoelastic.weights.size(), 2u);
      EXPECT_EQ(c.solver.type, SolverSpec::Type::Static);
    }
  }
  // fig5: 2 schemes x (node, patch) x 3 forces; fig6: 2 x 3 nodes; fig7: 2 x 3 periods.
  EXPECT_EQ(paper_figure("fig5", params, kParams).runs.size(), 12u);
  EXPECT_EQ(paper_figure("fig6", params, kParams).runs.size(), 6u);
  EXPECT_EQ(paper_figure("fig7", params, kParams).runs.size(), 6u);
  // The xu2011 runs use the paper's recursion, the objective ones the PK2 form.
  const PaperFigure fig6 = paper_figure("fig6", params, kParams);
  EXPECT_EQ(fig6.runs.front().scheme, "xu2011");
  const CaseConfig xu2011 = parse_case(fig6.runs.front().case_doc, kParams, {kRoot});
  EXPECT_EQ(xu2011.material.viscoelastic.history, PronyHistory::NodalForce);
  EXPECT_EQ(xu2011.material.viscoelastic.integration, PronyIntegration::Midpoint);
  // The former name "seed" still reads, and the runs are named and written under "xu2011".
  params["schemes"] = {"seed"};
  const PaperFigure old = paper_figure("fig6", params, kParams);
  ASSERT_EQ(old.runs.size(), 3u);
  EXPECT_EQ(old.runs.front().scheme, "xu2011");
  EXPECT_EQ(old.runs.front().id, fig6.runs.front().id);
  EXPECT_EQ(old.runs.front().case_doc, fig6.runs.front().case_doc);
}

TEST(PaperExperiments, BadParametersAreNamed) {
  nlohmann::json params = ConfigReader::parse_file(kParams);
  EXPECT_THROW(paper_figure("fig9", params, kParams), Error);
  params["fig6"]["dept"] = 0.01;
  try {
    paper_figure("fig6", params, kParams);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'fig6.dept'"), std::string::npos) << e.what();
  }
  params = ConfigReader::parse_file(kParams);
  params["fig7"]["periods"] = {1.0, -2.0};
  EXPECT_THROW(paper_figure("fig7", params, kParams), Error);
  params = ConfigReader::parse_file(kParams);
  params["prony"]["terms"][0]["tau"] = 0.0;  // caught when the run's case is parsed
  const PaperFigure fig = paper_figure("fig6", params, kParams);
  EXPECT_THROW(parse_case(fig.runs.front().case_doc, kParams, {kRoot}), Error);
}

}  // namespace
}  // namespace tmlab::tm
