// The quadratic (10-node) tetrahedral mesh of a linear one: every tet edge gets a node at its
// midpoint (straight-sided P2 elements on the linear geometry, as deal.II's FE_SimplexP(2) on a
// linear mapping). The fast model's P2 element (tensormass/kernels) and its face contact run on it.
//
// Numbering. Points 0 .. num_vertices-1 are the linear mesh's points, in its order (so a vertex keeps
// its index, its file id and every selector that picks it); edge e's midside node is point
// num_vertices + e. Edges are numbered in order of first appearance, tet by tet, in the local edge
// order below: deterministic.
//
// Local node order of a 10-node tet: VTK's quadratic tetra (VTK_QUADRATIC_TETRA = 24), which the
// VTU writer uses as is: vertices 0-3 of the linear tet, then the midside nodes of the edges
// (0,1), (1,2), (0,2), (0,3), (1,3), (2,3) (kTet10Edges). Gmsh's 10-node tet (type 11) swaps the
// last two (its node 8 is on edge (2,3), node 9 on (1,3)).
// Local node order of a 6-node triangle: vertices 0-2, then the midside nodes of (0,1), (1,2), (0,2)
// (VTK_QUADRATIC_TRIANGLE = 22).
#pragma once

#include "core/mesh/mesh.hpp"

#include <array>
#include <vector>

namespace tmlab {

using Tet10 = std::array<Index, 10>;
using Tri6 = std::array<Index, 6>;
using Edge = std::array<Index, 2>;

/// The edges (local vertex pairs) whose midside nodes are local nodes 4..9 of a Tet10.
inline constexpr std::array<std::array<int, 2>, 6> kTet10Edges{
    {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}}};
/// The edges whose midside nodes are local nodes 3..5 of a Tri6.
inline constexpr std::array<std::array<int, 2>, 3> kTri6Edges{{{0, 1}, {1, 2}, {0, 2}}};

struct QuadraticMesh {
  Index num_vertices = 0;    ///< points 0 .. num_vertices-1 are the linear mesh's points
  std::vector<Vec3> points;  ///< vertices, then the midpoint of each edge
  std::vector<Tet10> tets;   ///< tet t of the linear mesh with its six midside nodes
  std::vector<Edge> edges;  ///< edge e joins vertices edges[e][0] < edges[e][1]; its node is num_vertices + e
  std::vector<Index> edge_ptr;  ///< CSR by lower vertex: edges of vertex a are [edge_ptr[a], edge_ptr[a+1])
                                ///< in edge_order, sorted by upper vertex (edge lookup)
  std::vector<Index> edge_order;

  Index num_points() const { return static_cast<Index>(points.size()); }
  Index num_tets() const { return static_cast<Index>(tets.size()); }
  Index num_edges() const { return static_cast<Index>(edges.size()); }
  bool is_midside(Index p) const { return p >= num_vertices; }
  /// The midside node of the edge joining vertices a and b (either order); -1 when they share no edge.
  Index midside_node(Index a, Index b) const;
  /// The 6-node triangle on the linear triangle f (its vertices must share edges of the mesh; throws
  /// tmlab::Error naming the triangle's vertices otherwise).
  Tri6 triangle(const Tri& f) const;
  /// The vertices in `vertices` and the midside nodes of the edges of `faces` (a face selection's node
  /// set: a Dirichlet condition on a surface fixes its edge nodes too), sorted, unique.
  std::vector<Index> face_nodes(const std::vector<Tri>& faces) const;
  /// The given vertices plus the midside node of every edge whose two ends are both among them,
  /// sorted, unique (a node set given by vertices: e.g. a geometric selection).
  std::vector<Index> with_midside_nodes(const std::vector<Index>& vertices) const;
};

/// The quadratic mesh of `linear` (its tets must be positively oriented: check/repair first). Throws
/// tmlab::Error when a tet names a point out of range.
QuadraticMesh make_quadratic(const Mesh& linear);

/// A point field of the linear mesh (one value per vertex, `width` values each) extended to the
/// quadratic mesh by linear interpolation along each edge (the midside value is the mean of its ends).
std::vector<double> interpolate_to_quadratic(const QuadraticMesh& qm,
                                             const std::vector<double>& vertex_values, int width);

}  // namespace tmlab
