// Mesh: the counts and Mesh::tet_name, the way every message names a tetrahedron (tmlab's 0-based
// index, and the file's element id when the mesh came from a file).
#include "core/mesh/mesh.hpp"
#include "core/mesh/mesh_generator.hpp"

#include <gtest/gtest.h>

#include <string>

namespace tmlab {
namespace {

TEST(Mesh, CountsFollowTheVectors) {
  Mesh m;
  EXPECT_EQ(m.num_points(), 0);
  EXPECT_EQ(m.num_tets(), 0);
  m.points = {Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  m.tets = {{0, 1, 2, 3}, {0, 2, 1, 3}};
  EXPECT_EQ(m.num_points(), 4);
  EXPECT_EQ(m.num_tets(), 2);
}

TEST(Mesh, TetNameOfAGeneratedMeshIsTheIndexOnly) {
  const Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 1, 1, 1);
  ASSERT_TRUE(m.tet_file_ids.empty());
  EXPECT_EQ(m.tet_name(0), "tetrahedron 0");
  EXPECT_EQ(m.tet_name(5), "tetrahedron 5");
}

TEST(Mesh, TetNameAddsTheFileElementId) {
  Mesh m;
  m.points = {Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), Vec3::Ones()};
  m.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  m.tet_file_ids = {345, 7};
  EXPECT_EQ(m.tet_name(0), "tetrahedron 0 (Gmsh element 345)");
  EXPECT_EQ(m.tet_name(1), "tetrahedron 1 (Gmsh element 7)");
  // An index outside the ids (a caller's bug or a generated tet appended later) still names the
  // index instead of reading past the vector.
  EXPECT_EQ(m.tet_name(2), "tetrahedron 2");
  EXPECT_EQ(m.tet_name(-1), "tetrahedron -1");
}

}  // namespace
}  // namespace tmlab
