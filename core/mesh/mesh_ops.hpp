// Operations on a tet mesh: orientation repair, scaling and translation, boundary extraction,
// physical-group lookup, and NodeSelector, the JSON-described node/face selection used by boundary
// conditions and loads.
#pragma once

#include "core/mesh/mesh.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tmlab {

/// Swaps the last two nodes of every tet with negative signed volume; returns how many were swapped.
/// Triangles are not touched.
int repair_orientation(Mesh& mesh);

/// Multiplies every coordinate by `factor` (> 0, finite; otherwise tmlab::Error).
void scale_mesh(Mesh& mesh, double factor);

/// Adds `offset` to every point (finite; otherwise tmlab::Error).
void translate_mesh(Mesh& mesh, const Vec3& offset);

/// Tet faces used by exactly one tet, oriented with the normal (b-a)x(c-a) pointing out of the tet
/// they belong to (taking the tet's actual orientation into account). Ordered by (tet, local face).
std::vector<Tri> boundary_faces(const Mesh& mesh);

/// Sorted indices of the nodes of boundary_faces().
std::vector<Index> boundary_nodes(const Mesh& mesh);

/// Sorted, unique nodes of the elements of dimension `dim` (0 points, 2 triangles, 3 tets) with
/// physical tag `tag`. Throws tmlab::Error listing the mesh's groups if there is no such group.
std::vector<Index> nodes_of_group(const Mesh& mesh, int dim, int tag);

/// Same, by group name (all dimensions carrying that name). Throws tmlab::Error if none does.
std::vector<Index> nodes_of_group(const Mesh& mesh, const std::string& name);

/// A set of nodes described in JSON, one of:
///   {"group": "name"} or {"group": tag} (optionally with "dim": 0|2|3 to disambiguate a tag),
///   {"box": {"min": [x,y,z], "max": [x,y,z]}}            nodes with min <= x <= max (all axes),
///   {"plane": {"axis": "x"|"y"|"z", "value": v, "tol": t}}  nodes with |x_axis - v| <= t (tol default 1e-9),
///   {"sphere": {"center": [x,y,z], "radius": r}}          nodes with |x - center| <= r,
///   {"nodes": [i, ...]}                                   0-based node indices.
struct NodeSelector {
  enum class Kind { Group, Box, Plane, Sphere, Nodes };
  Kind kind = Kind::Nodes;

  std::string group_name;  ///< Group: name, empty when selecting by tag
  int group_tag = 0;       ///< Group: tag when group_name is empty
  int group_dim = -1;      ///< Group: dimension, -1 = any (a tag must then be unambiguous)

  Vec3 box_min = Vec3::Zero();  ///< Box
  Vec3 box_max = Vec3::Zero();

  int axis = 0;        ///< Plane: 0 x, 1 y, 2 z
  double value = 0.0;  ///< Plane: coordinate
  double tol = 1e-9;   ///< Plane: absolute tolerance

  Vec3 center = Vec3::Zero();  ///< Sphere
  double radius = 0.0;

  std::vector<Index> nodes;  ///< Nodes

  /// Parses and validates a selector. Unknown keys, missing keys, wrong types and impossible values
  /// throw tmlab::Error("<where>: reason"), naming the key.
  static NodeSelector from_json(const nlohmann::json& j, const std::string& where = "node selector");

  /// The nodes (or boundary faces) on the plane x_axis = value, within tol.
  static NodeSelector plane(int axis, double value, double tol = 1e-9) {
    NodeSelector s;
    s.kind = Kind::Plane;
    s.axis = axis;
    s.value = value;
    s.tol = tol;
    return s;
  }

  /// The JSON form accepted by from_json().
  nlohmann::json to_json() const;
};

/// The mesh node closest to p (the first one on ties); 0 for an empty mesh.
Index nearest_node(const Mesh& mesh, const Vec3& p);

/// Sorted indices of the nodes the selector picks (possibly empty; callers decide whether an empty
/// set is an error). Group lookups and out-of-range node indices throw tmlab::Error.
std::vector<Index> select_nodes(const Mesh& mesh, const NodeSelector& selector);

/// Outward boundary faces for surface loads: for a group selector naming a surface group that has
/// triangles in the file, those triangles (oriented like the matching boundary face when they lie
/// on the boundary); otherwise the boundary faces all of whose nodes select_nodes() picks.
std::vector<Tri> select_faces(const Mesh& mesh, const NodeSelector& selector);

}  // namespace tmlab
