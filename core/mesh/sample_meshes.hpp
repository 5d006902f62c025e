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

/// Coordinates on [lo, hi] (exact end values, strictly increasing) resolving a contact zone around
/// `focus` (lo <= focus <= hi): on each side of the focus,
/// - a fine zone of m = ceil(fine_half_width / h_fine) uniform cells of exactly h_fine (so it
///   reaches at least fine_half_width from the focus), then
/// - a growth zone to the end, the map t(s) = w + h_fine (e^{a s} - 1) / a for s in [0, n] (w = m
///   h_fine): its spacing dt/ds = h_fine e^{a s} starts at h_fine and grows by the factor e^a <=
///   `growth` per cell; n is the fewest cells the nominal a = ln(growth) needs, and a <= ln(growth)
///   is then solved so that the side ends exactly at the end.
///   When the growth zone would have to shrink its cells (it is shorter than n fine cells), the fine
///   zone takes one more cell; when less than one fine cell is left beyond it, the whole side is
///   uniform with ceil(length / h_fine) cells (no wider than h_fine). growth = 1: uniform sides.
/// `refinement` r samples the same maps r times more densely: round(r m) fine cells and round(r n)
/// growth cells at s = j n / round(r n), so every spacing is the r = 1 spacing divided by r (exact in
/// the fine zone; in the growth zone the spacing function h_fine e^{a s} / r; for whole r the
/// r = 1 nodes are kept: nested meshes), to the rounding of r m and r n otherwise.
/// Throws tmlab::Error unless lo < hi (finite), focus in [lo, hi], h_fine > 0, fine_half_width >= 0,
/// 1 <= growth <= 4, refinement > 0, and the axis has at most kMaxGradedCells cells.
std::vector<double> contact_graded_coordinates(double lo, double hi, double focus, double h_fine,
                                               double fine_half_width, double growth,
                                               double refinement = 1.0);
/// The number of cells contact_graded_coordinates gives (without generating them; a double, so a
/// far too fine axis still has a count; the same argument checks except the cell limit).
double contact_graded_cells(double lo, double hi, double focus, double h_fine, double fine_half_width,
                            double growth, double refinement = 1.0);
/// The most cells contact_graded_coordinates makes on one axis.
inline constexpr double kMaxGradedCells = 1e5;

/// Coordinates on [lo, hi] finest at both ends (the platens, a cylinder's rim seen from both sides
/// of a block): contact_graded_coordinates on [lo, (lo + hi) / 2] with the focus at lo, mirrored
/// about the midpoint (so the grid is symmetric and ends exactly at lo and hi).
std::vector<double> two_sided_graded_coordinates(double lo, double hi, double h_fine, double fine_width,
                                                 double growth, double refinement = 1.0);

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
/// The same block on given grid coordinates (x, y over the block's width, z from 0 to its height;
/// make_box_mesh(BoxGrid)'s checks), with the same group names.
Mesh make_block_mesh(const BoxGrid& grid);

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
  /// Graded meshes: the radii of ring 0 .. rings (0 first, `radius` last, increasing) and the
  /// heights of layer 0 .. layers (0 first, `height` last, increasing); empty = uniform.
  std::vector<double> ring_radii, layer_z;
};

/// A cylinder meshed as a disk of hexagonal rings (centre node, ring k at radius R k / rings, or
/// ring_radii[k], with 6k nodes, consecutive rings joined by a triangle strip), extruded in layers (uniform,
/// or at layer_z); each triangular prism is split into three tets with every quadrilateral face cut along the
/// diagonal through its lowest-numbered node, which makes neighbouring prisms conform (Dompierre et al., "How
/// to subdivide pyramids, prisms and hexahedra into tetrahedra", 1999). The side is the inscribed polygon of
/// 6 rings nodes (its volume is slightly below pi R^2 h: see cylinder_mesh_volume()). Groups: "bottom" (z =
/// 0), "top" (z = height), "side", "body". Throws tmlab::Error unless radius, height > 0, rings >= 1 and
/// layers >= 1, and ring_radii and layer_z are empty or have those sizes, ends and order.
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
