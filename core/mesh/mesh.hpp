// The linear-tetrahedron mesh shared by every tmlab module, with the physical groups of the file it
// came from. Indices are 0-based and contiguous; the file's own node ids are kept for messages.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tmlab {

using Index = std::int32_t;
using Vec3 = Eigen::Vector3d;
using Tet = std::array<Index, 4>;
using Tri = std::array<Index, 3>;

/// A Gmsh physical group: dimension (0 point, 2 surface, 3 volume), tag and optional name.
struct PhysicalGroup {
  int dim = 0;
  int tag = 0;
  std::string name;
};

struct Mesh {
  std::vector<Vec3> points;            ///< rest positions, metres
  std::vector<long> point_file_ids;    ///< node id in the source file (for error messages)
  std::vector<Tet> tets;               ///< linear tets, positively oriented after check/repair
  std::vector<long> tet_file_ids;      ///< element id in the source file (empty when generated)
  std::vector<int> tet_physical;       ///< physical tag per tet (0 when none)
  std::vector<Tri> triangles;          ///< surface triangles given in the file (not derived)
  std::vector<int> triangle_physical;  ///< physical tag per triangle (0 when none)
  std::vector<Index> vertices;         ///< 0-d point elements given in the file
  std::vector<int> vertex_physical;    ///< physical tag per point element
  std::vector<PhysicalGroup> groups;   ///< from $PhysicalNames, plus unnamed tags seen in elements
  std::string source;                  ///< file the mesh was read from ("" when generated)

  Index num_points() const { return static_cast<Index>(points.size()); }
  Index num_tets() const { return static_cast<Index>(tets.size()); }
  /// How messages name tet t: "tetrahedron 12 (Gmsh element 345)" when the mesh came from a file,
  /// "tetrahedron 12" otherwise (t is tmlab's 0-based index, the id is the file's).
  std::string tet_name(Index t) const;
};

}  // namespace tmlab
