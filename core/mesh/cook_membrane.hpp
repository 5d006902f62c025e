// Cook's membrane (Cook 1974; the CoFEA benchmark collection, docs/benchmarks/002-cook-membrane):
// the tapered panel with corners (0, 0), (L, H1), (L, H1 + H2), (0, H1) in the x-y plane (by default
// L = 48 mm, H1 = 44 mm, H2 = 16 mm), extruded by its thickness along z, clamped on its left edge
// x = 0 and loaded by a uniform shear traction on its right edge x = L. A near-incompressible
// bending benchmark: linear tets lock, and the tip deflection converges slowly from below.
//
// The mesh is the unit Kuhn-split box grid (make_box_mesh) mapped bilinearly onto the panel:
//   (s, r, w) in [0, 1]^3 -> (1-s)(1-r) P0 + s (1-r) P1 + s r P2 + (1-s) r P3 + thickness w e_z,
// with the corners P0 = (0, 0), P1 = (L, H1), P2 = (L, H1 + H2), P3 = (0, H1): x = L s,
// y = H1 s (1 - r) + r (H1 + H2 s). The tip (the benchmark's probe) is P2.
// Lines of constant s or r are straight under a bilinear map, so every mapped cell is a planar
// convex quadrilateral (extruded): the tets tile the panel exactly (volume = area x thickness, area =
// L (H1 + H2) / 2) and stay positively oriented.
#pragma once

#include "core/mesh/mesh.hpp"

namespace tmlab {

/// Physical tags of make_cook_membrane_mesh() (the box tags of make_box_mesh, renamed).
enum CookMembraneTag : int {
  kCookClamped = 1,  ///< "clamped": the left edge x = 0 (the box's xmin)
  kCookLoaded = 2,   ///< "loaded": the right edge x = L (xmax)
  kCookBottom = 3,   ///< "bottom": the lower slanted edge (ymin)
  kCookTop = 4,      ///< "top": the upper slanted edge (ymax)
  kCookBack = 5,     ///< "back": z = 0 (zmin)
  kCookFront = 6,    ///< "front": z = thickness (zmax)
  kCookBody = 7,     ///< "body"
};

struct CookMembraneSpec {
  double length = 0.048;     ///< L, m
  double left = 0.044;       ///< H1: height of the clamped edge, and rise of the lower edge, m
  double right = 0.016;      ///< H2: height of the loaded edge, m
  double thickness = 0.005;  ///< m
  int cells = 16;            ///< cells along each in-plane direction
  int layers = 1;            ///< cells through the thickness
};

/// The panel of `spec` (see above). Throws tmlab::Error unless the sizes are positive and finite and
/// cells, layers >= 1.
Mesh make_cook_membrane_mesh(const CookMembraneSpec& spec);

/// The exact volume of the panel: L (H1 + H2) / 2 x thickness.
double cook_membrane_volume(const CookMembraneSpec& spec);

}  // namespace tmlab
