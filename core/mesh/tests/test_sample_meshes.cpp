// Tests of the rig sample meshes: graded coordinates, the graded block and the cylinder.
#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"
#include "core/mesh/sample_meshes.hpp"
#include "core/testing/small_meshes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace tmlab {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace
namespace {

double triangle_area(const Mesh& m, const Tri& f) {
  return 0.5 * (m.points[f[1]] - m.points[f[0]]).cross(m.points[f[2]] - m.points[f[0]]).norm();
}

double group_area(const Mesh& m, int tag) {
  double a = 0.0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    if (m.triangle_physical[t] == tag) a += triangle_area(m, m.triangles[t]);
  }
  return a;
}

TEST(GradedCoordinates, UniformWithPowerOne) {
  const std::vector<double> c = graded_coordinates(0.0, 1.0, 4, 0.0, 1.0);
  ASSERT_EQ(c.size(), 5u);
  for (int i = 0; i <= 4; ++i) EXPECT_NEAR(c[static_cast<std::size_t>(i)], i / 4.0, 1e-15);
}

TEST(GradedCoordinates, FinestAtTheFocusAndIncreasing) {
  const std::vector<double> c = graded_coordinates(-2.0, 2.0, 10, 0.5, 2.0);
  ASSERT_EQ(c.size(), 11u);
  EXPECT_EQ(c.front(), -2.0);
  EXPECT_EQ(c.back(), 2.0);
  EXPECT_NE(std::find(c.begin(), c.end(), 0.5), c.end());
  double smallest = 1e9;
  std::size_t where = 0;
  for (std::size_t i = 1; i < c.size(); ++i) {
    ASSERT_GT(c[i], c[i - 1]) << i;
    if (c[i] - c[i - 1] < smallest) {
      smallest = c[i] - c[i - 1];
      where = i;
    }
  }
  // The smallest cell touches the focus.
  EXPECT_TRUE(c[where] == 0.5 || c[where - 1] == 0.5);
}

TEST(GradedCoordinates, RefusesBadArguments) {
  EXPECT_THROW(graded_coordinates(0.0, 1.0, 0, 0.0, 1.0), Error);
  EXPECT_THROW(graded_coordinates(1.0, 1.0, 3, 1.0, 1.0), Error);
  EXPECT_THROW(graded_coordinates(0.0, 1.0, 3, 2.0, 1.0), Error);
  EXPECT_THROW(graded_coordinates(0.0, 1.0, 3, 0.5, 0.5), Error);
  EXPECT_THROW(graded_coordinates(0.0, 1.0, 1, 0.5, 1.0), Error);
}

TEST(BlockMesh, GradedBlockIsValidAndRefinedUnderTheIndenter) {
  BlockSpec s;
  s.nx = s.ny = 8;
  s.nz = 4;
  s.grading = 2.0;
  const Mesh m = make_block_mesh(s);
  const MeshReport r = analyse_mesh(m);
  EXPECT_TRUE(r.inverted.empty());
  EXPECT_NEAR(r.total_volume, s.size_x * s.size_y * s.size_z, 1e-15);
  // The node nearest the top centre sits exactly on it, and cells shrink towards it.
  EXPECT_NE(std::find(m.points.begin(), m.points.end(), Vec3(0, 0, s.size_z)), m.points.end());
  bool bottom = false, top = false;
  for (const PhysicalGroup& g : m.groups) {
    bottom = bottom || (g.name == "bottom" && g.tag == kBoxZmin);
    top = top || (g.name == "top" && g.tag == kBoxZmax);
  }
  EXPECT_TRUE(bottom && top);
  EXPECT_NEAR(group_area(m, kBoxZmax), s.size_x * s.size_y, 1e-15);
}

TEST(CylinderMesh, ConformingPositiveAndExactVolume) {
  for (const int rings : {1, 2, 5}) {
    CylinderSpec s;
    s.radius = 0.025;
    s.height = 0.03;
    s.rings = rings;
    s.layers = 3;
    const Mesh m = make_cylinder_mesh(s);
    const Index per_layer = 1 + 3 * rings * (rings + 1);
    EXPECT_EQ(m.num_points(), per_layer * 4);
    EXPECT_EQ(m.num_tets(), 3 * 6 * rings * rings * 3);
    for (Index t = 0; t < m.num_tets(); ++t) ASSERT_GT(tet_signed_volume(m, t), 0.0) << t;
    const MeshReport r = analyse_mesh(m);
    EXPECT_NEAR(r.total_volume, cylinder_mesh_volume(s), 1e-12 * cylinder_mesh_volume(s));
    // Conforming: every face used at most twice, and the boundary faces are exactly the tagged
    // triangles whose areas add up to the polygon's top, bottom and side.
    int boundary = 0;
    for (const auto& [face, n] : testing::face_uses(m)) {
      ASSERT_LE(n, 2);
      boundary += n == 1 ? 1 : 0;
    }
    EXPECT_EQ(static_cast<std::size_t>(boundary), m.triangles.size());
    const double n = 6.0 * rings;
    const double polygon = 0.5 * n * s.radius * s.radius * std::sin(2.0 * kPi / n);
    const double perimeter = n * 2.0 * s.radius * std::sin(kPi / n);
    EXPECT_NEAR(group_area(m, kCylinderBottom), polygon, 1e-14);
    EXPECT_NEAR(group_area(m, kCylinderTop), polygon, 1e-14);
    EXPECT_NEAR(group_area(m, kCylinderSide), perimeter * s.height, 1e-14);
  }
}

/// The size known before meshing (what a caller checks against its limit) is the generated mesh's.
TEST(SampleMeshSize, CountsAreTheGeneratedMeshes) {
  for (const auto& [nx, ny, nz] : {std::array<int, 3>{2, 2, 1}, {5, 3, 4}, {8, 8, 2}}) {
    BlockSpec s;
    s.nx = nx;
    s.ny = ny;
    s.nz = nz;
    const Mesh m = make_block_mesh(s);
    const SampleMeshSize z = block_mesh_size(nx, ny, nz);
    EXPECT_EQ(z.nodes, static_cast<double>(m.num_points())) << nx << " " << ny << " " << nz;
    EXPECT_EQ(z.tets, static_cast<double>(m.num_tets()));
    EXPECT_EQ(z.boundary_triangles, static_cast<double>(m.triangles.size()));
  }
  for (const auto& [rings, layers] : {std::array<int, 2>{1, 1}, {3, 2}, {6, 5}}) {
    CylinderSpec s;
    s.rings = rings;
    s.layers = layers;
    const Mesh m = make_cylinder_mesh(s);
    const SampleMeshSize z = cylinder_mesh_size(rings, layers);
    EXPECT_EQ(z.nodes, static_cast<double>(m.num_points())) << rings << " " << layers;
    EXPECT_EQ(z.tets, static_cast<double>(m.num_tets()));
    EXPECT_EQ(z.boundary_triangles, static_cast<double>(m.triangles.size()));
  }
  // Far beyond what could be generated, the size is still known (no overflow): 400^3 cells.
  const SampleMeshSize big = block_mesh_size(400, 400, 400);
  EXPECT_EQ(big.tets, 384e6);
  EXPECT_GT(big.generator_bytes(), 3e10);
  EXPECT_GT(big.gmsh_bytes(), 1.8e10);
}

TEST(CylinderMesh, QualityHoldsAsRingsGrow) {
  CylinderSpec s;
  s.rings = 10;
  s.layers = 12;
  const MeshReport r = analyse_mesh(make_cylinder_mesh(s));
  EXPECT_TRUE(r.inverted.empty());
  EXPECT_GT(*std::min_element(r.quality.begin(), r.quality.end()), 0.2);
}

TEST(CylinderMesh, Deterministic) {
  CylinderSpec s;
  s.rings = 3;
  s.layers = 2;
  const Mesh a = make_cylinder_mesh(s), b = make_cylinder_mesh(s);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.tets, b.tets);
}

TEST(CylinderMesh, RefusesBadArguments) {
  CylinderSpec s;
  s.radius = -1.0;
  EXPECT_THROW(make_cylinder_mesh(s), Error);
  s = CylinderSpec{};
  s.rings = 0;
  EXPECT_THROW(make_cylinder_mesh(s), Error);
  s = CylinderSpec{};
  s.layers = 0;
  EXPECT_THROW(make_cylinder_mesh(s), Error);
}

}  // namespace
}  // namespace tmlab
