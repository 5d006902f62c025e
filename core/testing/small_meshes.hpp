// Test helpers: tiny hand-made meshes whose every number a test can state (link tmlab::mesh).
#pragma once

#include "core/mesh/mesh.hpp"

#include <algorithm>
#include <map>

namespace tmlab::testing {

/// Two tets sharing the face (1, 2, 3); five points, physical tags 7 and 8.
inline Mesh two_tets() {
  Mesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  m.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  m.tet_physical = {7, 8};
  return m;
}

/// How many tets use each face (vertices sorted): a conforming mesh uses no face more than twice,
/// and its faces used once are exactly its boundary.
inline std::map<Tri, int> face_uses(const Mesh& m) {
  std::map<Tri, int> uses;
  for (const Tet& t : m.tets) {
    for (int skip = 0; skip < 4; ++skip) {
      Tri f{};
      int k = 0;
      for (int v = 0; v < 4; ++v) {
        if (v != skip) f[static_cast<std::size_t>(k++)] = t[static_cast<std::size_t>(v)];
      }
      std::sort(f.begin(), f.end());
      ++uses[f];
    }
  }
  return uses;
}

}  // namespace tmlab::testing
