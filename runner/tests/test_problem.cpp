// Problem: what a case builds (mesh and its size, conditions, probes, system) and the errors that
// stop a run before any result directory exists, each naming the case file and the key.
#include "core/base/error.hpp"
#include "runner/problem.hpp"
#include "runner/tests/runner_test_case.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::tm::runner {
namespace {

using json = nlohmann::json;

class ProblemTest : public RunnerTestCase {
 protected:
  std::string refusal(const json& j) {
    const CaseConfig cfg = config(j);
    try {
      const Problem p(cfg);
    } catch (const Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "the problem was built";
    return "";
  }
};

TEST_F(ProblemTest, BuildsTheCase) {
  const CaseConfig cfg = config(uniaxial(0.001));
  const Problem p(cfg);
  EXPECT_EQ(p.mesh.num_points(), 64);  // 4 x 4 x 4 nodes
  EXPECT_NEAR(p.size, std::sqrt(3.0) * kL, 1e-15);
  ASSERT_EQ(p.conditions.size(), 4u);
  EXPECT_EQ(p.conditions[3].name, "pull");
  EXPECT_EQ(p.conditions[3].nodes.size(), 16u);
  ASSERT_EQ(p.probe_nodes.size(), 1u);
  EXPECT_EQ(p.mesh.points[p.probe_nodes[0]], Vec3(kL, kL, kL));
  EXPECT_EQ(p.system.num_dofs(), 3 * 64);
  EXPECT_EQ(p.visco, nullptr);
  EXPECT_NEAR(p.node_mass.sum(), 1000.0 * kL * kL * kL, 1e-15);
}

TEST_F(ProblemTest, AnEmptySelectionIsAnError) {
  json j = uniaxial(0.001);
  j["boundary"][3]["nodes"]["plane"]["value"] = 0.5;  // no node there
  const std::string e = refusal(j);
  EXPECT_NE(e.find("boundary[3] 'pull' selects no nodes"), std::string::npos) << e;
}

TEST_F(ProblemTest, AStaticRunNeedsConstraints) {
  json j = uniaxial(0.001);
  j.erase("boundary");
  j["loads"] = json::parse(R"([{"type": "gravity", "acceleration": [0, 0, -9.81]}])");
  const std::string e = refusal(j);
  EXPECT_NE(e.find("a static run needs boundary conditions"), std::string::npos) << e;
}

TEST_F(ProblemTest, ALoadOnNoFaceIsAnError) {
  json j = uniaxial(0.001);
  j["loads"] = json::parse(R"([{"type": "pressure", "pressure": 100,
                                "faces": {"plane": {"axis": "z", "value": 0.5}}}])");
  const std::string e = refusal(j);
  EXPECT_NE(e.find("loads[0]"), std::string::npos) << e;
  EXPECT_NE(e.find("selects no boundary faces"), std::string::npos) << e;
}

}  // namespace
}  // namespace tmlab::tm::runner
