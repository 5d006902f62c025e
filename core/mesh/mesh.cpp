#include "core/mesh/mesh.hpp"

namespace tmlab {

std::string Mesh::tet_name(Index t) const {
  std::string s = "tetrahedron " + std::to_string(t);
  if (t >= 0 && static_cast<std::size_t>(t) < tet_file_ids.size())
    s += " (Gmsh element " + std::to_string(tet_file_ids[static_cast<std::size_t>(t)]) + ")";
  return s;
}

}  // namespace tmlab
