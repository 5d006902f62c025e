// Geometric checks of a tet mesh: signed volumes, shape quality, inverted and degenerate elements,
// edge lengths and bounding box, gathered in a MeshReport that prints as text or JSON.
#pragma once

#include "core/mesh/mesh.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

namespace tmlab {

/// Signed volume det[b-a, c-a, d-a] / 6; positive when (b-a, c-a, d-a) is right-handed.
double tet_signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Signed volume of tet t of the mesh.
double tet_signed_volume(const Mesh& mesh, Index t);

/// Root mean square of the six edge lengths.
double tet_rms_edge(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Shape quality q = 6 sqrt(2) V / l_rms^3: 1 for the regular tet, 0 for a flat one, negative when
/// inverted; 0 when all four points coincide.
double tet_quality(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Relative volume below which a tet counts as degenerate: |V| < kDegenerateRelVolume * l_rms^3.
inline constexpr double kDegenerateRelVolume = 1e-12;

/// Summary of a mesh's geometry and element quality (see analyse_mesh()).
struct MeshReport {
  std::string source;  ///< Mesh::source
  Index num_points = 0;
  Index num_tets = 0;
  Index num_triangles = 0;       ///< triangles stored in the file
  Index num_vertices = 0;        ///< point elements stored in the file
  Index num_unused_points = 0;   ///< points referenced by no tet
  Index num_boundary_faces = 0;  ///< tet faces used by exactly one tet
  std::vector<PhysicalGroup> groups;

  Vec3 bbox_min = Vec3::Zero();  ///< over all points
  Vec3 bbox_max = Vec3::Zero();

  std::vector<double> volumes;  ///< signed volume per tet
  std::vector<double> quality;  ///< q per tet (negative for inverted tets)
  double total_volume = 0.0;    ///< sum of signed volumes
  double min_volume = 0.0;
  double max_volume = 0.0;

  double q_min = 0.0;
  double q_max = 0.0;
  double q_mean = 0.0;
  Index q_min_tet = -1;  ///< index of the worst tet (-1 without tets)
  std::array<Index, 10>
      q_histogram{};  ///< bin k counts q in [k/10, (k+1)/10); q <= 0 in bin 0, q >= 1 in bin 9

  std::vector<Index> inverted;    ///< tets with V < 0
  std::vector<Index> degenerate;  ///< tets with |V| < kDegenerateRelVolume * l_rms^3
  /// The source file's element ids of the tets (Mesh::tet_file_ids; empty for generated meshes):
  /// messages and the report name Gmsh element ids next to tmlab's 0-based indices.
  std::vector<long> tet_file_ids;

  Index num_edges = 0;  ///< unique tet edges
  double edge_min = 0.0;
  double edge_max = 0.0;
  double edge_mean = 0.0;
};

/// Computes the report. Requires valid node indices in every tet (as read_gmsh guarantees).
MeshReport analyse_mesh(const Mesh& mesh);

/// Multi-line human-readable summary (counts, bbox, volumes, q statistics and histogram, bad tets).
std::string format_mesh_report(const MeshReport& report);

/// The report as JSON: the summary values, the histogram and the inverted/degenerate index lists
/// (per-tet volumes and qualities are left out to keep it small).
nlohmann::json mesh_report_json(const MeshReport& report);

}  // namespace tmlab
