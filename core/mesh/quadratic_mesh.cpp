// The quadratic tet mesh of a linear one: see quadratic_mesh.hpp.
#include "core/mesh/quadratic_mesh.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>

namespace tmlab {

namespace {

/// One key per unordered vertex pair (a < b).
std::uint64_t edge_key(Index a, Index b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

}  // namespace

Index QuadraticMesh::midside_node(Index a, Index b) const {
  if (a > b) std::swap(a, b);
  if (a < 0 || b >= num_vertices || a == b) return -1;
  const auto first = edge_order.begin() + edge_ptr[static_cast<std::size_t>(a)];
  const auto last = edge_order.begin() + edge_ptr[static_cast<std::size_t>(a) + 1];
  const auto it = std::lower_bound(
      first, last, b, [this](Index e, Index upper) { return edges[static_cast<std::size_t>(e)][1] < upper; });
  if (it == last || edges[static_cast<std::size_t>(*it)][1] != b) return -1;
  return num_vertices + *it;
}

Tri6 QuadraticMesh::triangle(const Tri& f) const {
  Tri6 q{f[0], f[1], f[2], -1, -1, -1};
  for (int k = 0; k < 3; ++k) {
    const Index m = midside_node(f[static_cast<std::size_t>(kTri6Edges[static_cast<std::size_t>(k)][0])],
                                 f[static_cast<std::size_t>(kTri6Edges[static_cast<std::size_t>(k)][1])]);
    if (m < 0)
      throw Error("quadratic mesh: the triangle (" + std::to_string(f[0]) + ", " + std::to_string(f[1]) +
                  ", " + std::to_string(f[2]) + ") is not made of edges of the mesh's tets");
    q[static_cast<std::size_t>(3 + k)] = m;
  }
  return q;
}

std::vector<Index> QuadraticMesh::face_nodes(const std::vector<Tri>& faces) const {
  std::vector<Index> nodes;
  nodes.reserve(faces.size() * 6);
  for (const Tri& f : faces) {
    const Tri6 q = triangle(f);
    nodes.insert(nodes.end(), q.begin(), q.end());
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

std::vector<Index> QuadraticMesh::with_midside_nodes(const std::vector<Index>& vertices) const {
  std::vector<char> in(static_cast<std::size_t>(num_vertices), 0);
  std::vector<Index> nodes;
  for (const Index v : vertices) {
    if (v < 0 || v >= num_vertices)
      throw Error("quadratic mesh: vertex " + std::to_string(v) + " out of range (" +
                  std::to_string(num_vertices) + " vertices)");
    in[static_cast<std::size_t>(v)] = 1;
    nodes.push_back(v);
  }
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (in[static_cast<std::size_t>(edges[e][0])] && in[static_cast<std::size_t>(edges[e][1])])
      nodes.push_back(num_vertices + static_cast<Index>(e));
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

QuadraticMesh make_quadratic(const Mesh& linear) {
  QuadraticMesh qm;
  qm.num_vertices = linear.num_points();
  qm.points = linear.points;
  qm.tets.reserve(linear.tets.size());
  std::unordered_map<std::uint64_t, Index> edge_of;
  edge_of.reserve(linear.tets.size() * 2);
  for (Index t = 0; t < linear.num_tets(); ++t) {
    const Tet& tet = linear.tets[static_cast<std::size_t>(t)];
    for (const Index p : tet)
      if (p < 0 || p >= qm.num_vertices)
        throw Error("quadratic mesh: " + linear.tet_name(t) + " names point " + std::to_string(p) + " of " +
                    std::to_string(qm.num_vertices));
    Tet10 q{};
    for (int k = 0; k < 4; ++k) q[static_cast<std::size_t>(k)] = tet[static_cast<std::size_t>(k)];
    for (int k = 0; k < 6; ++k) {
      const Index a = tet[static_cast<std::size_t>(kTet10Edges[static_cast<std::size_t>(k)][0])];
      const Index b = tet[static_cast<std::size_t>(kTet10Edges[static_cast<std::size_t>(k)][1])];
      const auto [it, added] = edge_of.try_emplace(edge_key(a, b), static_cast<Index>(qm.edges.size()));
      if (added) {
        qm.edges.push_back({std::min(a, b), std::max(a, b)});
        qm.points.push_back(
            0.5 * (linear.points[static_cast<std::size_t>(a)] + linear.points[static_cast<std::size_t>(b)]));
      }
      q[static_cast<std::size_t>(4 + k)] = qm.num_vertices + it->second;
    }
    qm.tets.push_back(q);
  }
  // CSR lookup by the lower vertex, sorted by the upper one.
  qm.edge_ptr.assign(static_cast<std::size_t>(qm.num_vertices) + 1, 0);
  for (const Edge& e : qm.edges) ++qm.edge_ptr[static_cast<std::size_t>(e[0]) + 1];
  for (std::size_t a = 0; a < static_cast<std::size_t>(qm.num_vertices); ++a)
    qm.edge_ptr[a + 1] += qm.edge_ptr[a];
  qm.edge_order.resize(qm.edges.size());
  std::vector<Index> fill(qm.edge_ptr.begin(), qm.edge_ptr.end() - 1);
  for (std::size_t e = 0; e < qm.edges.size(); ++e)
    qm.edge_order[static_cast<std::size_t>(fill[static_cast<std::size_t>(qm.edges[e][0])]++)] =
        static_cast<Index>(e);
  for (std::size_t a = 0; a < static_cast<std::size_t>(qm.num_vertices); ++a)
    std::sort(qm.edge_order.begin() + qm.edge_ptr[a], qm.edge_order.begin() + qm.edge_ptr[a + 1],
              [&qm](Index x, Index y) {
                return qm.edges[static_cast<std::size_t>(x)][1] < qm.edges[static_cast<std::size_t>(y)][1];
              });
  return qm;
}

std::vector<double> interpolate_to_quadratic(const QuadraticMesh& qm,
                                             const std::vector<double>& vertex_values, int width) {
  const auto w = static_cast<std::size_t>(width);
  if (width < 1 || vertex_values.size() != static_cast<std::size_t>(qm.num_vertices) * w)
    throw Error("interpolate_to_quadratic: " + std::to_string(vertex_values.size()) + " values for " +
                std::to_string(qm.num_vertices) + " vertices of width " + std::to_string(width));
  std::vector<double> out(static_cast<std::size_t>(qm.num_points()) * w);
  std::copy(vertex_values.begin(), vertex_values.end(), out.begin());
  for (std::size_t e = 0; e < qm.edges.size(); ++e) {
    const std::size_t m = static_cast<std::size_t>(qm.num_vertices) + e;
    for (std::size_t c = 0; c < w; ++c)
      out[m * w + c] = 0.5 * (vertex_values[static_cast<std::size_t>(qm.edges[e][0]) * w + c] +
                              vertex_values[static_cast<std::size_t>(qm.edges[e][1]) * w + c]);
  }
  return out;
}

}  // namespace tmlab
