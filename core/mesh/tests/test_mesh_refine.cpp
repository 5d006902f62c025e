// Tests of refine_uniform (core/mesh/mesh_refine.hpp): volumes preserved (exactly on dyadic
// coordinates, to round-off otherwise), orientation kept, conforming, every tag kept, boundary
// triangles split into the refined mesh's boundary faces, edges halved.
#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"
#include "core/mesh/mesh_refine.hpp"
#include "core/testing/small_meshes.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>

namespace tmlab {
namespace {

double volume(const Mesh& m) {
  double v = 0.0;
  for (Index t = 0; t < m.num_tets(); ++t) v += tet_signed_volume(m, t);
  return v;
}

Tri sorted(Tri f) {
  std::sort(f.begin(), f.end());
  return f;
}

/// Every child's volume summed over its parent's 8 children (children t = 8 e .. 8 e + 7).
void expect_children_volumes(const Mesh& parent, const Mesh& child, double rel_tol) {
  ASSERT_EQ(child.num_tets(), 8 * parent.num_tets());
  for (Index e = 0; e < parent.num_tets(); ++e) {
    const double v = tet_signed_volume(parent, e);
    double sum = 0.0;
    for (Index c = 8 * e; c < 8 * e + 8; ++c) {
      const double vc = tet_signed_volume(child, c);
      EXPECT_EQ(vc > 0.0, v > 0.0) << "child " << c << " of tet " << e << " changed orientation";
      sum += vc;
    }
    if (rel_tol == 0.0)
      EXPECT_EQ(sum, v) << "tet " << e;
    else
      EXPECT_NEAR(sum, v, rel_tol * std::abs(v)) << "tet " << e;
  }
}

/// Conforming: no face used by more than two tets, and the faces used once are exactly the
/// boundary triangles when every boundary face is a triangle of the mesh.
void expect_conforming(const Mesh& m) {
  for (const auto& [face, uses] : testing::face_uses(m))
    EXPECT_LE(uses, 2) << face[0] << " " << face[1] << " " << face[2];
}

TEST(MeshRefine, OneTetSplitsIntoEightOfAnEighthWithTenPoints) {
  Mesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.tets = {{0, 1, 2, 3}};
  m.tet_physical = {5};
  const Mesh r = refine_uniform(m);
  EXPECT_EQ(r.num_points(), 10);  // 4 corners + 6 edges
  expect_children_volumes(m, r, 0.0);
  // The four corner tets are the parent scaled by 1/2 about its corners: volume 1/48 each.
  for (Index c = 0; c < 4; ++c) EXPECT_EQ(tet_signed_volume(r, c), 1.0 / 48.0);
  for (const int tag : r.tet_physical) EXPECT_EQ(tag, 5);
  expect_conforming(r);
  // The first points are the parent's, in order; the others are edge midpoints.
  for (Index p = 0; p < 4; ++p)
    EXPECT_EQ(r.points[static_cast<std::size_t>(p)], m.points[static_cast<std::size_t>(p)]);
  for (Index p = 4; p < 10; ++p) {
    const Vec3& x = r.points[static_cast<std::size_t>(p)];
    int halves = 0;
    for (int a = 0; a < 3; ++a) halves += x[a] == 0.5 ? 1 : 0;
    EXPECT_TRUE(halves == 1 || halves == 2) << x.transpose();
  }
}

TEST(MeshRefine, BoxMeshKeepsVolumeTagsAndBoundaryExactly) {
  const Mesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 2, 1), 2, 2, 1);
  const Mesh r = refine_uniform(m);
  expect_children_volumes(m, r, 0.0);  // dyadic coordinates: each parent's children sum exactly
  EXPECT_NEAR(volume(r), 2.0, 1e-14);  // 96 volumes with a division by 6 each: to round-off
  expect_conforming(r);
  // The points are the vertices plus one per edge of the parent mesh: V + E.
  std::set<std::pair<Index, Index>> edges;
  for (const Tet& t : m.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        edges.insert(std::minmax(t[static_cast<std::size_t>(a)], t[static_cast<std::size_t>(b)]));
  EXPECT_EQ(static_cast<std::size_t>(r.num_points()), m.points.size() + edges.size());
  // Tags: 8 children per tet and 4 per triangle with the parent's tag; groups and names kept.
  ASSERT_EQ(r.triangles.size(), 4 * m.triangles.size());
  for (std::size_t t = 0; t < m.tets.size(); ++t)
    for (std::size_t c = 0; c < 8; ++c) EXPECT_EQ(r.tet_physical[8 * t + c], m.tet_physical[t]);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (std::size_t c = 0; c < 4; ++c) EXPECT_EQ(r.triangle_physical[4 * t + c], m.triangle_physical[t]);
  ASSERT_EQ(r.groups.size(), m.groups.size());
  for (std::size_t g = 0; g < m.groups.size(); ++g) EXPECT_EQ(r.groups[g].name, m.groups[g].name);
  // The split triangles are exactly the refined mesh's boundary faces, facing the same way.
  std::map<Tri, Tri> boundary;
  for (const Tri& f : boundary_faces(r)) boundary[sorted(f)] = f;
  ASSERT_EQ(boundary.size(), r.triangles.size());
  for (const Tri& f : r.triangles) {
    const auto it = boundary.find(sorted(f));
    ASSERT_NE(it, boundary.end());
    const auto normal = [&r](const Tri& t) {
      const Vec3& a = r.points[static_cast<std::size_t>(t[0])];
      return Vec3(
          (r.points[static_cast<std::size_t>(t[1])] - a).cross(r.points[static_cast<std::size_t>(t[2])] - a));
    };
    EXPECT_GT(normal(f).dot(normal(it->second)), 0.0);
  }
  // The selectors by group find the refined faces: the group's nodes include the new midpoints.
  EXPECT_GT(nodes_of_group(r, "zmax").size(), nodes_of_group(m, "zmax").size());
  // Every edge halves: the representative size (V / tets)^(1/3) halves exactly.
  EXPECT_NEAR(std::cbrt(volume(m) / m.num_tets()) / std::cbrt(volume(r) / r.num_tets()), 2.0, 1e-14);
}

TEST(MeshRefine, JitteredMeshKeepsVolumesToRoundOffAndTwiceRefinedConforms) {
  Mesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), 3, 3, 3);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.08, 0.08);
  for (Vec3& p : m.points) p += Vec3(jitter(rng), jitter(rng), jitter(rng));
  const Mesh r = refine_uniform(m);
  expect_children_volumes(m, r, 1e-13);
  const Mesh rr = refine_uniform(r);
  expect_children_volumes(r, rr, 1e-13);
  EXPECT_EQ(rr.num_tets(), 64 * m.num_tets());
  EXPECT_NEAR(volume(rr), volume(m), 1e-13 * volume(m));
  expect_conforming(rr);
  // Faces used once = the split boundary triangles (27 cells -> 108 boundary triangles -> x16).
  int once = 0;
  for (const auto& [face, uses] : testing::face_uses(rr)) once += uses == 1 ? 1 : 0;
  EXPECT_EQ(static_cast<std::size_t>(once), rr.triangles.size());
  EXPECT_EQ(rr.triangles.size(), 16 * m.triangles.size());
}

TEST(MeshRefine, NegativelyOrientedParentKeepsItsSignAndFileIdsStayUnique) {
  Mesh m = testing::two_tets();
  std::swap(m.tets[1][2], m.tets[1][3]);  // the second tet negatively oriented
  m.point_file_ids = {10, 20, 30, 40, 50};
  const double v0 = tet_signed_volume(m, 0), v1 = tet_signed_volume(m, 1);
  ASSERT_NE(v0 > 0.0, v1 > 0.0) << "the helper mesh has one tet of each orientation";
  const Mesh r = refine_uniform(m);
  expect_children_volumes(m, r, 1e-15);
  expect_conforming(r);
  // The shared face's 3 edges get one midpoint each: 5 + 6 + 6 - 3 points.
  EXPECT_EQ(r.num_points(), 14);
  ASSERT_EQ(r.point_file_ids.size(), r.points.size());
  std::set<long> ids(r.point_file_ids.begin(), r.point_file_ids.end());
  EXPECT_EQ(ids.size(), r.points.size());
  EXPECT_EQ(*ids.begin(), 10);
  EXPECT_GT(*ids.rbegin(), 50);
  EXPECT_TRUE(r.tet_file_ids.empty());
  EXPECT_EQ(r.tet_physical, std::vector<int>({7, 7, 7, 7, 7, 7, 7, 7, 8, 8, 8, 8, 8, 8, 8, 8}));
}

TEST(MeshRefine, TheOctahedronIsCutAlongItsShortestDiagonal) {
  // A tet stretched along x: the edges (0,1) and (2,3) are far apart in y, z, and the diagonal
  // joining the midpoints of (0,2) and (1,3) is the shortest of the three.
  Mesh m;
  m.points = {{0, 0, 0}, {4, 1, 0}, {4, 0, 0}, {0, 1, 1}};
  m.tets = {{0, 1, 2, 3}};
  if (tet_signed_volume(m, 0) < 0.0) std::swap(m.tets[0][2], m.tets[0][3]);
  const Tet& t = m.tets[0];
  const auto midpoint = [&m](Index a, Index b) {
    return Vec3(0.5 * (m.points[static_cast<std::size_t>(a)] + m.points[static_cast<std::size_t>(b)]));
  };
  const std::pair<Index, Index> pairs[3][2] = {
      {{t[0], t[1]}, {t[2], t[3]}}, {{t[0], t[2]}, {t[1], t[3]}}, {{t[0], t[3]}, {t[1], t[2]}}};
  int shortest = 0;
  double best = 1e300;
  for (int d = 0; d < 3; ++d) {
    const double len =
        (midpoint(pairs[d][0].first, pairs[d][0].second) - midpoint(pairs[d][1].first, pairs[d][1].second))
            .norm();
    if (len < best) {
      best = len;
      shortest = d;
    }
  }
  const Mesh r = refine_uniform(m);
  // The inner tets (children 4..7) all contain both ends of the chosen diagonal.
  const Vec3 p = midpoint(pairs[shortest][0].first, pairs[shortest][0].second);
  const Vec3 q = midpoint(pairs[shortest][1].first, pairs[shortest][1].second);
  for (Index c = 4; c < 8; ++c) {
    bool has_p = false, has_q = false;
    for (const Index n : r.tets[static_cast<std::size_t>(c)]) {
      has_p = has_p || r.points[static_cast<std::size_t>(n)] == p;
      has_q = has_q || r.points[static_cast<std::size_t>(n)] == q;
    }
    EXPECT_TRUE(has_p && has_q) << "inner tet " << c;
  }
  expect_children_volumes(m, r, 1e-15);
}

}  // namespace
}  // namespace tmlab
