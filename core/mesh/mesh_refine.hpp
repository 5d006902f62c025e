// Uniform ("red") refinement of a tet mesh: every tet split into 8 by its edge midpoints (Bey 1995,
// "Tetrahedral grid refinement", Computing 55): the 4 corner tets and the inner octahedron cut
// along its shortest diagonal into 4. Halves every edge, so the representative size
// h = (V / tets)^(1/3) halves exactly: the refinement of a case's mesh in a convergence study
// (`tmlab converge CASE`, convergence/; docs/convergence.md).
#pragma once

#include "core/mesh/mesh.hpp"

namespace tmlab {

/// The mesh refined once. Every edge gets one new point at its midpoint, shared by every tet and
/// triangle that has the edge, so a conforming mesh stays conforming. Each child tet keeps its
/// parent's physical tag and the sign of its parent's volume (a positively oriented mesh stays
/// positive); each boundary triangle is split into 4 with its tag, oriented as its parent; point
/// elements and the physical groups are kept. The first num_points() points are the parent's, in
/// order, with their file ids; the new points get file ids after the largest. The children's file
/// element ids are empty (the refined mesh is generated) and `source` is empty. Throws
/// tmlab::Error when the refined mesh would exceed the index range.
Mesh refine_uniform(const Mesh& mesh);

}  // namespace tmlab
