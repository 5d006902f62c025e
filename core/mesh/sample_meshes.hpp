// Meshes of the samples that mechanical tests load: a block refined under an indenter and a
// cylinder for compression or tension between platens. The test rigs (calibration/rigs) generate
// their meshes here, so any measured data set can be simulated without a hand-made mesh.
//
// Both generators are deterministic (same arguments, same mesh to the bit) and give positively
// oriented, conforming linear tets whose boundary triangles carry named physical groups.
#pragma once

#include "core/mesh/mesh.hpp"
#include "core/mesh/mesh_generator.hpp"

#include <vector>

namespace tmlab {

/// n + 1 coordinates from lo to hi (exact end values) whose spacing is finest at `focus`
/// (lo <= focus <= hi) and grows away from it: on each side of the focus the coordinate is
/// focus +- L (s)^power for s uniform in [0, 1] (power = 1: uniform; 2: spacing grows linearly).
/// Cells are shared between the two sides in proportion to their lengths (at least one cell on a
/// side of non-zero length). Throws tmlab::Error unless n >= 1, lo < hi, focus in [lo, hi] and
/// 1 <= power <= 4.
std::vector<double> graded_coordinates(double lo, double hi, int n, double focus, double power);

/// Specification of an indentation block: the box [-size_x/2, size_x/2] x [-size_y/2, size_y/2] x
/// [0, size_z] (z up, the indented face on top at z = size_z), refined towards the point (cx, cy)
/// of the top face.
struct BlockSpec {
  double size_x = 0.04, size_y = 0.04, size_z = 0.02;  ///< m
  double cx = 0.0, cy = 0.0;                           ///< where the indenter touches, m
  int nx = 16, ny = 16, nz = 8;                        ///< cells per axis
  double grading = 1.0;                                ///< power of graded_coordinates (1 = uniform)
};

/// The block of `spec`: a graded Kuhn-split box (make_box_mesh(BoxGrid)) with the physical
/// surfaces of make_box_mesh renamed for the rig: "bottom" (z = 0, tag kBoxZmin), "top"
/// (z = size_z, tag kBoxZmax), the four sides keep xmin ... ymax, and the body "body".
Mesh make_block_mesh(const BlockSpec& spec);

/// Physical tags of make_cylinder_mesh().
enum CylinderMeshTag : int {
  kCylinderBottom = 1,
  kCylinderTop = 2,
  kCylinderSide = 3,
  kCylinderBody = 4,
};

/// Specification of a cylinder sample: axis z, base centred at the origin, z in [0, height].
struct CylinderSpec {
  double radius = 0.025, height = 0.03;  ///< m
  int rings = 8;                         ///< radial cell layers (ring k has 6k nodes)
  int layers = 10;                       ///< axial cell layers
};

/// A cylinder meshed as a disk of hexagonal rings (centre node, ring k at radius R k / rings with
/// 6k nodes, consecutive rings joined by a triangle strip), extruded in uniform layers; each
/// triangular prism is split into three tets with every quadrilateral face cut along the diagonal
/// through its lowest-numbered node, which makes neighbouring prisms conform (Dompierre et al.,
/// "How to subdivide pyramids, prisms and hexahedra into tetrahedra", 1999). The side is the
/// inscribed polygon of 6 rings nodes (its volume is slightly below pi R^2 h: see
/// cylinder_mesh_volume()). Groups: "bottom" (z = 0), "top" (z = height), "side", "body".
/// Throws tmlab::Error unless radius, height > 0, rings >= 1 and layers >= 1.
Mesh make_cylinder_mesh(const CylinderSpec& spec);

/// The exact volume of make_cylinder_mesh(spec): the outer ring's polygon area times the height.
double cylinder_mesh_volume(const CylinderSpec& spec);

/// The size of a sample mesh, known before it is generated, so that a caller can refuse one too
/// large to build (rather than meet std::bad_alloc). The counts are doubles: exact below 2^53, and a
/// specification far too large to generate still gets its size.
struct SampleMeshSize {
  double nodes = 0.0, tets = 0.0, boundary_triangles = 0.0;
  /// Peak memory of generating the mesh (points with their file ids, tets with their physical tags,
  /// the boundary-face search of 4 faces per tet, the boundary triangles), bytes.
  double generator_bytes() const;
  /// The size of its Gmsh 2.2 file (write_gmsh22's own estimate per node and element), bytes.
  double gmsh_bytes() const;
};

/// The size of make_block_mesh with nx x ny x nz cells: (nx+1)(ny+1)(nz+1) nodes, 6 nx ny nz tets
/// (Kuhn split), 4 (nx ny + ny nz + nz nx) boundary triangles.
SampleMeshSize block_mesh_size(double nx, double ny, double nz);
/// The size of make_cylinder_mesh with `rings` and `layers`: (1 + 3 rings (rings + 1)) (layers + 1)
/// nodes, 18 rings^2 layers tets, 12 rings^2 + 12 rings layers boundary triangles.
SampleMeshSize cylinder_mesh_size(double rings, double layers);

}  // namespace tmlab
