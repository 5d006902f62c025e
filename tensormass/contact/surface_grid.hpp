// The contact surface of a tet mesh and a uniform grid over its nodes for candidate search.
//
// ContactSurface: the boundary faces (faces used by one tet, core/mesh/mesh_ops.hpp), their nodes,
// and each node's tributary area in the reference configuration (a third of the area of every
// boundary triangle it belongs to), which turns nodal contact forces into pressures and active
// nodes into a contact area. The contact area of a node against a body with normal n counts each
// adjacent face's third projected on n, A_f/3 max(0, -N_f . n) (N_f the outward face normal): a
// node on the edge of a block pressed by a platen then counts its top faces, not its side faces.
//
// SurfaceGrid: a uniform grid of cubic cells over the current positions of the boundary nodes,
// stored as a counting sort (cell offsets + node list), so a query touches only the cells a box
// overlaps. The cell size is fixed when the grid is built (from the mean boundary edge length, grown
// if needed to keep the cell count below a few per node); refit() re-bins the nodes at their new
// positions in O(n) with the same cell size, re-fitting the grid's box to the deformed surface.
// Queries return the boundary nodes inside a box, which callers filter with the exact gap.
#pragma once

#include "core/mesh/mesh.hpp"
#include "tensormass/kernels/elastic_model.hpp"

#include <Eigen/Geometry>

#include <array>
#include <vector>

namespace tmlab::tm {

struct ContactSurface {
  std::vector<Tri> faces;              ///< boundary faces, outward
  std::vector<Index> nodes;            ///< sorted boundary nodes (mesh indices)
  std::vector<double> area;            ///< tributary area per boundary node (reference), m^2
  std::vector<Index> local;            ///< mesh node -> position in `nodes`, -1 for interior nodes
  double mean_edge = 0.0;              ///< mean boundary edge length (reference), m
  std::vector<Vec3> face_normal;       ///< unit outward normal per face (reference)
  std::vector<double> face_area;       ///< area per face (reference), m^2
  std::vector<Index> node_face_start;  ///< faces of surface node k: node_faces[start[k] .. start[k+1])
  std::vector<Index> node_faces;

  /// Tributary area of surface node k projected on a body normal n: sum A_f/3 max(0, -N_f . n).
  double contact_area(Index k, const Vec3& n) const;

  /// Extracts the boundary of `mesh`; throws tmlab::Error when the mesh has no boundary face.
  static ContactSurface extract(const Mesh& mesh);
  Index size() const { return static_cast<Index>(nodes.size()); }
};

class SurfaceGrid {
 public:
  SurfaceGrid() = default;
  /// Builds the grid over the positions X + u of the surface nodes (u node-major, may be empty
  /// for the rest positions). `cell` <= 0 picks twice the mean boundary edge length.
  SurfaceGrid(const Mesh& mesh, const ContactSurface& surface, const VecX& u, double cell = 0.0);

  /// Re-bins the surface nodes at X + u (same cell size; the grid box follows the nodes).
  void refit(const Mesh& mesh, const ContactSurface& surface, const VecX& u);

  /// The same over arbitrary points (the contact points of a quadratic surface): `mean_edge` sizes
  /// the cells as the surface's mean boundary edge does above; query() returns indices into x.
  SurfaceGrid(const std::vector<Vec3>& x, double mean_edge, double cell = 0.0);
  void refit(const std::vector<Vec3>& x);

  /// Surface-local indices (into ContactSurface::nodes) of the nodes whose current position lies in
  /// [lo, hi] (bounds may be infinite), in increasing order.
  std::vector<Index> query(const Vec3& lo, const Vec3& hi) const;

  double cell_size() const { return cell_; }
  std::array<int, 3> dims() const { return dims_; }

 private:
  double cell_ = 0.0;
  Vec3 origin_ = Vec3::Zero();
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<Vec3> pos_;          ///< current position per surface node
  std::vector<Index> cell_start_;  ///< size cells + 1
  std::vector<Index> entries_;     ///< surface-local node indices sorted by cell
  std::vector<Index> cell_of_;     ///< scratch: cell per node
};

}  // namespace tmlab::tm
