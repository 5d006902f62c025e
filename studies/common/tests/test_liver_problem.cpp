// The liver problem both studies start from (liver_problem.hpp): read from a parameter document, it
// is the mesh, the long-term material, the Prony series in the long-term convention, the density and
// a base holding exactly the selected nodes; bad documents are errors naming the file and key.
#include "core/base/error.hpp"
#include "studies/common/liver_problem.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace tmlab::tm {
namespace {

const std::string kRoot = TMLAB_SOURCE_DIR;

nlohmann::json cube_params() {
  return {{"mesh", "meshes/cube_n4.msh"},
          {"base", {{"box", {{"min", {-1, -1, -1}}, {"max", {2, 2, 0.01}}}}}},
          {"material", {{"E", 4000}, {"nu", 0.45}, {"density", 1060}}},
          {"prony",
           {{"convention", "instantaneous"},
            {"terms", {{{"weight", 0.35}, {"tau", 0.4}}, {{"weight", 0.2}, {"tau", 4.0}}}}}}};
}

TEST(LiverProblem, ReadsMeshMaterialPronyAndBase) {
  const LiverProblem p = liver_problem(cube_params(), "<params>", kRoot);
  EXPECT_EQ(p.mesh_file, kRoot + "/meshes/cube_n4.msh");
  EXPECT_EQ(p.mesh.num_tets(), 384);
  EXPECT_EQ(p.young, 4000.0);
  EXPECT_EQ(p.poisson, 0.45);
  EXPECT_EQ(p.density, 1060.0);
  // Instantaneous weights g = (0.35, 0.2) are alpha_j = g_j / (1 - sum g) in the long-term convention.
  ASSERT_EQ(p.prony.size(), 2u);
  EXPECT_NEAR(p.prony.alpha(0), 0.35 / 0.45, 1e-15);
  EXPECT_NEAR(p.prony.alpha(1), 0.2 / 0.45, 1e-15);
  EXPECT_EQ(p.prony.tau(1), 4.0);
  // The base: every node at z <= 0.01 and no other, all components fixed at zero for all time.
  EXPECT_EQ(p.base.name, "base");
  const std::set<Index> base(p.base.nodes.begin(), p.base.nodes.end());
  for (Index i = 0; i < p.mesh.num_points(); ++i)
    EXPECT_EQ(base.count(i) == 1, p.mesh.points[static_cast<std::size_t>(i)].z() <= 0.01) << i;
  EXPECT_EQ(base.size(), 25u);  // the bottom face of the 4 x 4 x 4 cube
  EXPECT_TRUE(p.base.components[0] && p.base.components[1] && p.base.components[2]);
  EXPECT_EQ(p.base.value.norm(), 0.0);
}

TEST(LiverProblem, BadDocumentsAreNamed) {
  auto message = [](const nlohmann::json& params) {
    try {
      liver_problem(params, "<params>", kRoot);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  nlohmann::json p = cube_params();
  p["mesh"] = "meshes/no_such.msh";
  EXPECT_NE(message(p).find("<params>: key 'mesh': file not found"), std::string::npos) << message(p);
  p = cube_params();
  p["base"] = {{"box", {{"min", {5, 5, 5}}, {"max", {6, 6, 6}}}}};
  EXPECT_NE(message(p).find("'base' selects no nodes"), std::string::npos) << message(p);
  p = cube_params();
  p["prony"]["convention"] = "sideways";
  EXPECT_NE(message(p).find("convention"), std::string::npos) << message(p);
}

}  // namespace
}  // namespace tmlab::tm
