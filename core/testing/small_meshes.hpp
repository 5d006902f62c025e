// Test helpers: tiny hand-made meshes whose every number a test can state (link tmlab::mesh).
#pragma once

#include "core/mesh/mesh.hpp"

namespace tmlab::testing {

/// Two tets sharing the face (1, 2, 3); five points, physical tags 7 and 8.
inline Mesh two_tets() {
  Mesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  m.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  m.tet_physical = {7, 8};
  return m;
}

}  // namespace tmlab::testing
