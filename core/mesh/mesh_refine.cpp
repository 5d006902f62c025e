#include "core/mesh/mesh_refine.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_quality.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <utility>

namespace tmlab {

namespace {

/// The midpoints of the mesh's edges: one new point per edge, created on first use.
class Midpoints {
 public:
  explicit Midpoints(Mesh& out) : out_(out) {
    for (const long id : out.point_file_ids) next_id_ = std::max(next_id_, id + 1);
  }

  Index of(Index a, Index b) {
    if (a > b) std::swap(a, b);
    const std::uint64_t key =
        (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
    const auto [it, inserted] = index_.try_emplace(key, out_.num_points());
    if (inserted) {
      out_.points.push_back(
          0.5 * (out_.points[static_cast<std::size_t>(a)] + out_.points[static_cast<std::size_t>(b)]));
      if (!out_.point_file_ids.empty()) out_.point_file_ids.push_back(next_id_++);
    }
    return it->second;
  }

 private:
  Mesh& out_;
  std::unordered_map<std::uint64_t, Index> index_;
  long next_id_ = 1;
};

/// Appends tet t with the orientation sign of `parent_volume` (two nodes swapped when it differs).
void push_tet(Mesh& out, Tet t, double parent_volume, int tag) {
  const double v = tet_signed_volume(
      out.points[static_cast<std::size_t>(t[0])], out.points[static_cast<std::size_t>(t[1])],
      out.points[static_cast<std::size_t>(t[2])], out.points[static_cast<std::size_t>(t[3])]);
  if ((v < 0.0) != (parent_volume < 0.0)) std::swap(t[2], t[3]);
  out.tets.push_back(t);
  out.tet_physical.push_back(tag);
}

}  // namespace

Mesh refine_uniform(const Mesh& mesh) {
  // Points: the parents' plus one per edge (fewer than 6 per tet and 3 per triangle).
  const double bound = static_cast<double>(mesh.points.size()) + 6.0 * static_cast<double>(mesh.tets.size()) +
                       3.0 * static_cast<double>(mesh.triangles.size());
  if (bound > static_cast<double>(std::numeric_limits<Index>::max()) ||
      8.0 * static_cast<double>(mesh.tets.size()) > static_cast<double>(std::numeric_limits<Index>::max()))
    throw Error("refine_uniform: the refined mesh of " + std::to_string(mesh.tets.size()) +
                " tets would exceed the mesh index range");
  Mesh out;
  out.points = mesh.points;
  out.point_file_ids = mesh.point_file_ids;
  out.vertices = mesh.vertices;
  out.vertex_physical = mesh.vertex_physical;
  out.groups = mesh.groups;
  out.tets.reserve(8 * mesh.tets.size());
  out.tet_physical.reserve(8 * mesh.tets.size());
  out.triangles.reserve(4 * mesh.triangles.size());
  out.triangle_physical.reserve(4 * mesh.triangles.size());
  Midpoints mid(out);

  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const Tet& t = mesh.tets[e];
    const int tag = e < mesh.tet_physical.size() ? mesh.tet_physical[e] : 0;
    const double v = tet_signed_volume(mesh, static_cast<Index>(e));
    // m[a][b]: the midpoint of the edge (t[a], t[b]).
    Index m[4][4] = {};
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) m[a][b] = m[b][a] = mid.of(t[a], t[b]);
    // The corner tets.
    push_tet(out, {t[0], m[0][1], m[0][2], m[0][3]}, v, tag);
    push_tet(out, {m[0][1], t[1], m[1][2], m[1][3]}, v, tag);
    push_tet(out, {m[0][2], m[1][2], t[2], m[2][3]}, v, tag);
    push_tet(out, {m[0][3], m[1][3], m[2][3], t[3]}, v, tag);
    // The octahedron: cut along its shortest diagonal (m_ab, m_cd) of the three that join the
    // midpoints of opposite edges; the other four midpoints form the ring m_ac, m_ad, m_bd, m_bc
    // around it (consecutive ones share a corner of the parent).
    constexpr int kDiagonals[3][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}};
    int best = 0;
    double best_length = std::numeric_limits<double>::infinity();
    for (int d = 0; d < 3; ++d) {
      const auto& [a, b, c, dd] = kDiagonals[d];
      const double length =
          (out.points[static_cast<std::size_t>(m[a][b])] - out.points[static_cast<std::size_t>(m[c][dd])])
              .squaredNorm();
      if (length < best_length) {
        best_length = length;
        best = d;
      }
    }
    const auto& [a, b, c, d] = kDiagonals[best];
    const Index p = m[a][b], q = m[c][d];
    const Index ring[4] = {m[a][c], m[a][d], m[b][d], m[b][c]};
    for (int k = 0; k < 4; ++k) push_tet(out, {p, q, ring[k], ring[(k + 1) % 4]}, v, tag);
  }

  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Tri& t = mesh.triangles[f];
    const int tag = f < mesh.triangle_physical.size() ? mesh.triangle_physical[f] : 0;
    const Index m01 = mid.of(t[0], t[1]), m12 = mid.of(t[1], t[2]), m20 = mid.of(t[2], t[0]);
    // Same cyclic order as the parent: the children face the same way.
    for (const Tri& c : {Tri{t[0], m01, m20}, Tri{m01, t[1], m12}, Tri{m20, m12, t[2]}, Tri{m01, m12, m20}}) {
      out.triangles.push_back(c);
      out.triangle_physical.push_back(tag);
    }
  }
  return out;
}

}  // namespace tmlab
