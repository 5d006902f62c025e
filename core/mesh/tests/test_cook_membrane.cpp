// Tests of Cook's membrane mesh: exact volume and areas of its named faces, positive tets, the
// tagged edges where the benchmark clamps and loads it, and a conforming boundary.
#include "core/base/error.hpp"
#include "core/mesh/cook_membrane.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

namespace tmlab {
namespace {

double group_area(const Mesh& m, int tag) {
  double a = 0.0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    if (m.triangle_physical[t] == tag) {
      const Tri& f = m.triangles[t];
      a += 0.5 * (m.points[f[1]] - m.points[f[0]]).cross(m.points[f[2]] - m.points[f[0]]).norm();
    }
  return a;
}

std::string group_name(const Mesh& m, int tag) {
  for (const PhysicalGroup& g : m.groups)
    if (g.dim == 2 && g.tag == tag) return g.name;
  return "";
}

TEST(CookMembraneMesh, VolumeAndFaceAreasAreExact) {
  for (int cells : {1, 3, 8}) {
    CookMembraneSpec spec;
    spec.cells = cells;
    spec.layers = cells == 8 ? 2 : 1;
    const Mesh m = make_cook_membrane_mesh(spec);
    const double L = 0.048, H1 = 0.044, H2 = 0.016, t = 0.005;
    ASSERT_EQ(m.tets.size(), static_cast<std::size_t>(6 * cells * cells * spec.layers));
    double volume = 0.0, vmin = 1.0;
    for (Index e = 0; e < m.num_tets(); ++e) {
      const double v = tet_signed_volume(m, e);
      volume += v;
      vmin = std::min(vmin, v);
    }
    EXPECT_GT(vmin, 0.0) << cells;
    EXPECT_NEAR(volume / (0.5 * L * (H1 + H2) * t), 1.0, 1e-13) << cells;
    EXPECT_NEAR(cook_membrane_volume(spec) / (0.5 * L * (H1 + H2) * t), 1.0, 1e-15);
    // The clamped and loaded edges (x t), the slanted edges, the two faces of the panel.
    EXPECT_NEAR(group_area(m, kCookClamped) / (H1 * t), 1.0, 1e-13);
    EXPECT_NEAR(group_area(m, kCookLoaded) / (H2 * t), 1.0, 1e-13);
    EXPECT_NEAR(group_area(m, kCookBottom) / (std::hypot(L, H1) * t), 1.0, 1e-13);
    EXPECT_NEAR(group_area(m, kCookTop) / (std::hypot(L, H2) * t), 1.0, 1e-13);
    EXPECT_NEAR(group_area(m, kCookBack) / (0.5 * L * (H1 + H2)), 1.0, 1e-13);
    EXPECT_NEAR(group_area(m, kCookFront) / (0.5 * L * (H1 + H2)), 1.0, 1e-13);
    // The tagged triangles are the whole boundary.
    EXPECT_EQ(boundary_faces(m).size(), m.triangles.size());
  }
}

TEST(CookMembraneMesh, NamedGroupsSitWhereTheBenchmarkNeedsThem) {
  CookMembraneSpec spec;
  spec.cells = 4;
  const Mesh m = make_cook_membrane_mesh(spec);
  EXPECT_EQ(group_name(m, kCookClamped), "clamped");
  EXPECT_EQ(group_name(m, kCookLoaded), "loaded");
  EXPECT_EQ(group_name(m, kCookBottom), "bottom");
  EXPECT_EQ(group_name(m, kCookTop), "top");
  EXPECT_EQ(group_name(m, kCookBack), "back");
  EXPECT_EQ(group_name(m, kCookFront), "front");
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (Index n : m.triangles[t]) {
      const Vec3& p = m.points[static_cast<std::size_t>(n)];
      if (m.triangle_physical[t] == kCookClamped) {
        EXPECT_EQ(p.x(), 0.0);
      }
      if (m.triangle_physical[t] == kCookLoaded) {
        EXPECT_EQ(p.x(), 0.048);
        EXPECT_GE(p.y(), 0.044 - 1e-15);
        EXPECT_LE(p.y(), 0.060 + 1e-15);
      }
      if (m.triangle_physical[t] == kCookBack) {
        EXPECT_EQ(p.z(), 0.0);
      }
      if (m.triangle_physical[t] == kCookFront) {
        EXPECT_EQ(p.z(), 0.005);
      }
    }
  // The tip (L, H1 + H2) is a node.
  const auto tip = std::find_if(m.points.begin(), m.points.end(),
                                [](const Vec3& p) { return (p - Vec3(0.048, 0.060, 0.0)).norm() < 1e-15; });
  EXPECT_NE(tip, m.points.end());
}

TEST(CookMembraneMesh, RefusesBadSizes) {
  CookMembraneSpec spec;
  spec.cells = 0;
  EXPECT_THROW(make_cook_membrane_mesh(spec), Error);
  spec = CookMembraneSpec{};
  spec.thickness = -1.0;
  EXPECT_THROW(make_cook_membrane_mesh(spec), Error);
  spec = CookMembraneSpec{};
  spec.length = std::nan("");
  EXPECT_THROW(make_cook_membrane_mesh(spec), Error);
}

}  // namespace
}  // namespace tmlab
