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

// The contact grading against its definition: exact ends, strictly increasing, cells of exactly
// h_fine within the fine zone (which reaches at least the asked half width on both sides of the
// focus, itself a node), neighbouring cells within the growth ratio, and the count as announced.
void expect_contact_grading(const std::vector<double>& c, double lo, double hi, double focus, double h,
                            double half_width, double growth) {
  ASSERT_GE(c.size(), 2u);
  EXPECT_EQ(c.front(), lo);
  EXPECT_EQ(c.back(), hi);
  EXPECT_NE(std::find(c.begin(), c.end(), focus), c.end());
  for (std::size_t i = 1; i < c.size(); ++i) ASSERT_GT(c[i], c[i - 1]) << i;
  for (std::size_t i = 1; i < c.size(); ++i) {
    const double width = c[i] - c[i - 1];
    const bool fine = std::max(std::abs(c[i] - focus), std::abs(c[i - 1] - focus)) <= half_width + 1e-12;
    if (fine) {
      EXPECT_NEAR(width, h, 1e-12 * h) << "cell " << i;
    }
    EXPECT_GE(width, h * (1.0 - 1e-12)) << "cell " << i;  // never finer than the fine zone here
    if (i + 1 < c.size()) {
      const double next = c[i + 1] - c[i];
      EXPECT_LE(std::max(next / width, width / next), growth * (1.0 + 1e-12))
          << "cells " << i << ", " << i + 1;
    }
  }
}

TEST(ContactGradedCoordinates, FineZoneThenBoundedGrowthToExactEnds) {
  const double h = 0.5, w = 4.0, g = 1.25;
  const std::vector<double> c = contact_graded_coordinates(-20.0, 20.0, 3.0, h, w, g);
  expect_contact_grading(c, -20.0, 20.0, 3.0, h, w, g);
  EXPECT_EQ(static_cast<double>(c.size() - 1), contact_graded_cells(-20.0, 20.0, 3.0, h, w, g));
  // Growth away from the zone: the outermost cells are the widest, and far wider than h.
  EXPECT_GT(c[1] - c[0], 4.0 * h);
  EXPECT_GT(c.back() - c[c.size() - 2], 4.0 * h);
  // The focus at an end (the indented top face): one side only.
  const std::vector<double> z = contact_graded_coordinates(0.0, 20.0, 20.0, h, w, g);
  expect_contact_grading(z, 0.0, 20.0, 20.0, h, w, g);
  EXPECT_NEAR(z.back() - z[z.size() - 2], h, 1e-12);
  // Growth 1: uniform, no wider than h.
  const std::vector<double> u = contact_graded_coordinates(0.0, 1.0, 0.0, 0.3, 0.5, 1.0);
  ASSERT_EQ(u.size(), 5u);  // ceil(1 / 0.3) = 4 cells of 0.25
  for (std::size_t i = 1; i < u.size(); ++i) EXPECT_NEAR(u[i] - u[i - 1], 0.25, 1e-15);
}

TEST(ContactGradedCoordinates, ShortSidesStayFineAndBounded) {
  // A growth zone that would have to shrink its cells widens the fine zone instead; less than one
  // fine cell beyond it makes the side uniform with cells no wider than h.
  for (const double hi : {1.05, 1.3, 1.7, 2.2, 2.9, 3.6}) {
    const std::vector<double> c = contact_graded_coordinates(0.0, hi, 0.0, 0.25, 0.5, 1.3);
    ASSERT_EQ(c.front(), 0.0);
    ASSERT_EQ(c.back(), hi);
    for (std::size_t i = 1; i < c.size(); ++i) {
      ASSERT_GT(c[i], c[i - 1]);
      if (c[i] <= 0.5 + 1e-12) {
        EXPECT_LE(c[i] - c[i - 1], 0.25 * (1 + 1e-12)) << hi << " cell " << i;
      }
      if (i + 1 < c.size()) {
        const double a = c[i] - c[i - 1], b = c[i + 1] - c[i];
        EXPECT_LE(std::max(a / b, b / a), 1.3 * (1 + 1e-12)) << hi << " cells " << i;
      }
    }
  }
}

TEST(ContactGradedCoordinates, RefinementDividesEverySpacing) {
  const double h = 0.5, w = 4.0, g = 1.25;
  const std::vector<double> c1 = contact_graded_coordinates(-20.0, 20.0, 3.0, h, w, g);
  const std::vector<double> c2 = contact_graded_coordinates(-20.0, 20.0, 3.0, h, w, g, 2.0);
  // A whole ratio keeps every node (nested) and splits every cell into two.
  ASSERT_EQ(c2.size() - 1, 2 * (c1.size() - 1));
  for (std::size_t i = 0; i < c1.size(); ++i) EXPECT_NEAR(c2[2 * i], c1[i], 1e-12) << i;
  for (std::size_t i = 1; i < c2.size(); ++i) {
    const double parent = c1[(i + 1) / 2] - c1[(i - 1) / 2];
    const double ratio = 2.0 * (c2[i] - c2[i - 1]) / parent;
    EXPECT_GT(ratio, 1.0 / g) << i;
    EXPECT_LT(ratio, g) << i;
  }
  expect_contact_grading(c2, -20.0, 20.0, 3.0, h / 2.0, w, g);
  // 1.5: the fine zone's 8 cells per side become 12 of exactly h / 1.5.
  const std::vector<double> c15 = contact_graded_coordinates(-20.0, 20.0, 3.0, h, w, g, 1.5);
  for (std::size_t i = 1; i < c15.size(); ++i)
    if (std::abs(c15[i] - 3.0) <= w + 1e-12 && std::abs(c15[i - 1] - 3.0) <= w + 1e-12) {
      EXPECT_NEAR(c15[i] - c15[i - 1], h / 1.5, 1e-12) << i;
    }
  EXPECT_EQ(static_cast<double>(c15.size() - 1), contact_graded_cells(-20.0, 20.0, 3.0, h, w, g, 1.5));
}

TEST(ContactGradedCoordinates, TwoSidedIsSymmetricAndFineAtBothEnds) {
  const std::vector<double> c = two_sided_graded_coordinates(0.0, 30.0, 2.5, 3.75, 1.25);
  EXPECT_EQ(c.front(), 0.0);
  EXPECT_EQ(c.back(), 30.0);
  const std::size_t n = c.size() - 1;
  for (std::size_t i = 0; i <= n; ++i) EXPECT_NEAR(c[i], 30.0 - c[n - i], 1e-12) << i;
  EXPECT_NEAR(c[1] - c[0], 2.5, 1e-12);
  EXPECT_NEAR(c[n] - c[n - 1], 2.5, 1e-12);
  for (std::size_t i = 1; i <= n; ++i) ASSERT_GT(c[i], c[i - 1]);
}

TEST(ContactGradedCoordinates, RefusesBadArguments) {
  EXPECT_THROW(contact_graded_coordinates(0.0, 1.0, 0.5, 0.0, 0.2, 1.2), Error);       // h = 0
  EXPECT_THROW(contact_graded_coordinates(0.0, 1.0, 1.5, 0.1, 0.2, 1.2), Error);       // focus outside
  EXPECT_THROW(contact_graded_coordinates(1.0, 1.0, 1.0, 0.1, 0.2, 1.2), Error);       // lo = hi
  EXPECT_THROW(contact_graded_coordinates(0.0, 1.0, 0.5, 0.1, -0.2, 1.2), Error);      // negative zone
  EXPECT_THROW(contact_graded_coordinates(0.0, 1.0, 0.5, 0.1, 0.2, 0.9), Error);       // shrinking
  EXPECT_THROW(contact_graded_coordinates(0.0, 1.0, 0.5, 0.1, 0.2, 1.2, 0.0), Error);  // refinement
  EXPECT_THROW(contact_graded_coordinates(0.0, 1.0, 0.5, 1e-12, 0.2, 1.2), Error);     // 2e11 fine cells
  EXPECT_THROW(contact_graded_coordinates(0.0, 1.0, 0.5, 1e-6, 0.2, 1.2), Error);      // 4e5 > the axis limit
  EXPECT_GT(contact_graded_cells(0.0, 1.0, 0.5, 1e-6, 0.2, 1.2), kMaxGradedCells);     // still counted
}

TEST(CylinderMesh, GradedRingsAndLayers) {
  CylinderSpec s;
  s.radius = 25.0;
  s.height = 30.0;
  s.ring_radii = contact_graded_coordinates(0.0, 25.0, 25.0, 2.5, 3.75, 1.25);
  s.layer_z = two_sided_graded_coordinates(0.0, 30.0, 2.5, 3.75, 1.25);
  s.rings = static_cast<int>(s.ring_radii.size()) - 1;
  s.layers = static_cast<int>(s.layer_z.size()) - 1;
  const Mesh m = make_cylinder_mesh(s);
  EXPECT_TRUE(analyse_mesh(m).inverted.empty());
  double volume = 0.0;
  for (Index e = 0; e < m.num_tets(); ++e) volume += tet_signed_volume(m, e);
  EXPECT_NEAR(volume, cylinder_mesh_volume(s), 1e-10 * volume);
  for (const Vec3& p : m.points) {
    const double r = std::hypot(p.x(), p.y());
    EXPECT_TRUE(std::any_of(s.ring_radii.begin(), s.ring_radii.end(),
                            [&](double ri) { return std::abs(ri - r) < 1e-9 || (ri == 0.0 && r < 1e-9); }) ||
                r < 1e-9);
  }
  CylinderSpec bad = s;
  bad.ring_radii.back() = 24.0;  // does not end at the radius
  EXPECT_THROW(make_cylinder_mesh(bad), Error);
  bad = s;
  bad.layer_z.pop_back();  // one value short
  EXPECT_THROW(make_cylinder_mesh(bad), Error);
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
