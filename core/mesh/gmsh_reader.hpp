// Reading Gmsh ASCII meshes (formats 1, 2.x and 4.1) into a tmlab::Mesh, and read_mesh(), which
// picks the reader from the file extension. Every malformed input throws tmlab::Error whose message
// starts with "file:line:" and says what is wrong; the reader never returns a partly read mesh.
#pragma once

#include "core/mesh/mesh.hpp"

#include <map>
#include <string>

namespace tmlab {

/// What read_gmsh() saw in the file beyond the mesh itself.
struct GmshReadInfo {
  std::string format_version;            ///< "1", "2.2", "4.1", ... as written in the file
  std::map<int, long> skipped_elements;  ///< Gmsh element type -> count of elements not kept
  long skipped_total() const;            ///< sum of skipped_elements
};

/// Reads a Gmsh ASCII mesh file in format 1 ($NOD/$ELM), 2.x or 4.1.
///
/// Kept elements: 4-node tetrahedra (type 4), 3-node triangles (2) and points (15). Lines (1) and
/// quadrangles (3) are skipped and counted in `info`. Other volume elements (hexahedra, prisms,
/// pyramids), second- or higher-order elements and unknown types are rejected, because dropping them
/// would silently change the body. Node ids may be any positive, unique integers; they are mapped
/// to 0-based indices in file order and kept in Mesh::point_file_ids.
///
/// Physical tags: format 1 "reg-phys", format 2 first tag, format 4.1 the physical tags of the
/// element's entity in $Entities (a tet whose entity has several physical tags gets the first one;
/// triangles and points are repeated once per tag, as Gmsh's 2.2 writer does). Mesh::groups holds
/// the $PhysicalNames entries of dimensions 0, 2, 3 plus every unnamed (dim, tag) used by a kept
/// element, sorted by (dim, tag).
///
/// Throws tmlab::Error ("path:line: reason") for: unreadable or binary files, unsupported format
/// versions, missing or misplaced sections and $End markers, counts that disagree with the data,
/// non-numbers, non-finite coordinates, duplicate or undefined node ids, unsupported element types,
/// elements with repeated nodes, duplicate tetrahedra, and files without nodes or elements sections.
Mesh read_gmsh(const std::string& path, GmshReadInfo* info = nullptr);

/// Reads a mesh file, choosing the reader from the extension (case-insensitive): ".msh" -> Gmsh.
/// Any other extension throws tmlab::Error naming the file and the supported extensions.
Mesh read_mesh(const std::string& path);

}  // namespace tmlab
