// Structured tet meshes of a box (for verification and refinement studies) and a Gmsh 2.2 ASCII
// writer so generated or converted meshes can be saved and inspected in Gmsh.
#pragma once

#include "core/mesh/mesh.hpp"
#include "core/mesh/quadratic_mesh.hpp"

#include <array>
#include <string>
#include <vector>

namespace tmlab {

/// Physical tags of make_box_mesh(): the six faces (dim 2) and the body (dim 3).
enum BoxMeshTag : int {
  kBoxXmin = 1,
  kBoxXmax = 2,
  kBoxYmin = 3,
  kBoxYmax = 4,
  kBoxZmin = 5,
  kBoxZmax = 6,
  kBoxBody = 7,
};

/// Box [lo, hi] split into nx * ny * nz hexahedral cells, each cut into 6 positively oriented tets
/// sharing the cell diagonal from its low to its high corner (Kuhn/Freudenthal split; every cell is
/// split the same way, so neighbouring cells conform). Points are numbered with x fastest:
/// index = i + (nx+1) * (j + (ny+1) * k). Boundary triangles (outward) carry physical tags 1..6
/// named xmin, xmax, ymin, ymax, zmin, zmax; tets carry tag 7 named "body". Deterministic.
/// Throws tmlab::Error if a count is < 1 or hi is not strictly above lo on every axis.
Mesh make_box_mesh(const Vec3& lo, const Vec3& hi, int nx, int ny, int nz);

/// The grid coordinates of a box mesh along x, y and z (each strictly increasing, >= 2 values).
using BoxGrid = std::array<std::vector<double>, 3>;
/// The same Kuhn-split box on a tensor-product grid of given coordinates (graded meshes: see
/// core/mesh/sample_meshes.hpp). make_box_mesh(lo, hi, n...) is this grid with uniform spacing.
/// Throws tmlab::Error unless every axis has >= 2 finite, strictly increasing coordinates.
Mesh make_box_mesh(const BoxGrid& grid);

/// Writes the mesh as Gmsh 2.2 ASCII: $PhysicalNames for named groups, nodes numbered 1..N in
/// point order, then point elements (type 15), triangles (2) and tets (4), each with tags
/// (physical, elementary = physical or 1 when untagged). Coordinates are written with the shortest
/// representation that reads back exactly. Throws tmlab::Error if the file cannot be written.
void write_gmsh22(const Mesh& mesh, const std::string& path);

/// The same with the quadratic mesh of `mesh` (make_quadratic): all its points, the file's
/// triangles as 6-node triangles (type 9) and the tets as 10-node tets (type 11) in Gmsh's node
/// order (VTK's with nodes 8 and 9 swapped). tmlab's reader reads linear tets only (the runner adds
/// the midside nodes itself, mesh.element); this file is for other tools.
void write_gmsh22_quadratic(const Mesh& mesh, const QuadraticMesh& quadratic, const std::string& path);

}  // namespace tmlab
