// Tests of the quadratic (10-node) mesh built from a linear one.
#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/quadratic_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace tmlab {
namespace {

TEST(QuadraticMesh, CountsMatchEulerOnABox) {
  // A Kuhn box of n^3 cells: (n+1)^3 vertices; its edges are the grid edges 3 n (n+1)^2, the face
  // diagonals 3 n^2 (n+1) and one body diagonal per cell, n^3.
  for (int n : {1, 2, 3}) {
    const Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), n, n, n);
    const QuadraticMesh q = make_quadratic(m);
    const Index expected = 3 * n * (n + 1) * (n + 1) + 3 * n * n * (n + 1) + n * n * n;
    EXPECT_EQ(q.num_edges(), expected) << n;
    EXPECT_EQ(q.num_points(), m.num_points() + expected);
    EXPECT_EQ(q.num_tets(), m.num_tets());
  }
}

TEST(QuadraticMesh, VerticesKeptAndMidsideNodesAtEdgeMidpoints) {
  const Mesh m = make_box_mesh(Vec3(-1, 0, 2), Vec3(1, 3, 4), 2, 3, 2);
  const QuadraticMesh q = make_quadratic(m);
  for (Index p = 0; p < m.num_points(); ++p) EXPECT_EQ(q.points[std::size_t(p)], m.points[std::size_t(p)]);
  std::set<Index> used;
  for (Index t = 0; t < q.num_tets(); ++t) {
    const Tet10& e = q.tets[std::size_t(t)];
    for (int k = 0; k < 4; ++k) EXPECT_EQ(e[std::size_t(k)], m.tets[std::size_t(t)][std::size_t(k)]);
    for (int k = 0; k < 6; ++k) {
      const Index a = e[std::size_t(kTet10Edges[std::size_t(k)][0])],
                  b = e[std::size_t(kTet10Edges[std::size_t(k)][1])];
      const Index mid = e[std::size_t(4 + k)];
      EXPECT_TRUE(q.is_midside(mid));
      EXPECT_EQ(q.midside_node(a, b), mid);
      EXPECT_EQ(q.midside_node(b, a), mid);
      EXPECT_EQ(q.points[std::size_t(mid)], 0.5 * (q.points[std::size_t(a)] + q.points[std::size_t(b)]));
      used.insert(mid);
    }
  }
  // Every midside node belongs to some tet (no orphan) and conformity: shared edges share one node.
  EXPECT_EQ(static_cast<Index>(used.size()), q.num_edges());
  EXPECT_EQ(q.midside_node(0, 0), -1);
}

TEST(QuadraticMesh, DeterministicAndNonEdgesAreAbsent) {
  const Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 2, 2, 2);
  const QuadraticMesh a = make_quadratic(m), b = make_quadratic(m);
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.points, b.points);
  // Opposite corners of the box are not joined by an edge of a 2x2x2 Kuhn box.
  const Index far = m.num_points() - 1;
  EXPECT_EQ(a.midside_node(0, far), -1);
}

TEST(QuadraticMesh, FaceNodesOfABoundaryFaceLieOnIt) {
  const Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 3, 2, 2);
  const QuadraticMesh q = make_quadratic(m);
  std::vector<Tri> bottom;
  for (std::size_t f = 0; f < m.triangles.size(); ++f)
    if (m.triangle_physical[f] == kBoxZmin) bottom.push_back(m.triangles[f]);
  ASSERT_FALSE(bottom.empty());
  const std::vector<Index> nodes = q.face_nodes(bottom);
  // (3+1)(2+1) vertices and the grid edges 3*3 + 4*2 and one diagonal per cell 6 on z = 0.
  EXPECT_EQ(nodes.size(), std::size_t(12 + 17 + 6));
  for (const Index n : nodes) EXPECT_EQ(q.points[std::size_t(n)].z(), 0.0);
  // Selecting the same vertices by position and adding the edges between them gives the same set
  // on a planar convex face.
  std::vector<Index> vertices;
  for (Index p = 0; p < m.num_points(); ++p)
    if (m.points[std::size_t(p)].z() == 0.0) vertices.push_back(p);
  EXPECT_EQ(q.with_midside_nodes(vertices), nodes);
  const Tri6 t6 = q.triangle(bottom.front());
  EXPECT_EQ(t6[3], q.midside_node(bottom.front()[0], bottom.front()[1]));
}

TEST(QuadraticMesh, InterpolationIsExactForLinearFields) {
  const Mesh m = make_box_mesh(Vec3::Zero(), Vec3(2, 1, 1), 2, 2, 2);
  const QuadraticMesh q = make_quadratic(m);
  std::vector<double> v;
  for (const Vec3& p : m.points) v.push_back(1.0 + 2.0 * p.x() - p.y() + 0.5 * p.z());
  const std::vector<double> w = interpolate_to_quadratic(q, v, 1);
  for (Index p = 0; p < q.num_points(); ++p) {
    const Vec3& x = q.points[std::size_t(p)];
    EXPECT_NEAR(w[std::size_t(p)], 1.0 + 2.0 * x.x() - x.y() + 0.5 * x.z(), 1e-15);
  }
  EXPECT_THROW(interpolate_to_quadratic(q, v, 2), Error);
}

TEST(QuadraticMesh, BadInputIsRefused) {
  Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 1, 1, 1);
  // Points 1 (x), 2 (y) and 4 (z) of the unit Kuhn cell are joined only through the diagonals from 0.
  EXPECT_THROW(make_quadratic(m).triangle({1, 2, 4}), Error);
  EXPECT_THROW(make_quadratic(m).with_midside_nodes({m.num_points()}), Error);
  m.tets[0][2] = 99;
  EXPECT_THROW(make_quadratic(m), Error);
}

}  // namespace
}  // namespace tmlab
