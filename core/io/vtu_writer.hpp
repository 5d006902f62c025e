// VTK XML output for ParaView: VtuWriter writes one tet mesh (rest or deformed configuration) with
// point and cell fields as a .vtu UnstructuredGrid; PvdWriter writes the .pvd collection that turns
// a sequence of .vtu files into a time series. Both write to "<file>.tmp" and rename, so a crash
// never leaves a truncated file under the final name.
#pragma once

#include "core/mesh/mesh.hpp"
#include "core/mesh/quadratic_mesh.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace tmlab {

/// How DataArray contents are stored: readable text, or base64-encoded raw little-endian binary
/// inline in the XML (format="binary", a UInt64 byte-count header, no compression): about 3x
/// smaller than ASCII and exact.
enum class VtuEncoding { Ascii, Base64 };

/// Builds and writes one .vtu file. Keeps a reference to the mesh, which must outlive the writer.
/// Field values are copied in; names must be unique within point data and within cell data.
class VtuWriter {
 public:
  explicit VtuWriter(const Mesh& mesh);
  /// Quadratic tets (VTK_QUADRATIC_TETRA, 24; the QuadraticMesh's node order is VTK's): `nodes` has
  /// the quadratic mesh's points and one tet (its vertex tet) per 10-node tet, for the point and
  /// cell counts; the cells are `quadratic`'s. Both must outlive the writer.
  VtuWriter(const Mesh& nodes, const QuadraticMesh& quadratic);

  /// Writes the mesh at these positions (one per mesh point) instead of the rest positions.
  void set_positions(const std::vector<Vec3>& positions);
  /// Writes the mesh at rest positions + displacement (one per mesh point).
  void set_displacement(const std::vector<Vec3>& displacement);

  /// One value per mesh point.
  void add_point_scalar(const std::string& name, const std::vector<double>& values);
  /// One 3-vector per mesh point (ParaView shows it as a vector: glyphs, "Warp By Vector").
  void add_point_vector(const std::string& name, const std::vector<Vec3>& values);
  /// One value per tet.
  void add_cell_scalar(const std::string& name, const std::vector<double>& values);
  /// One 3x3 tensor per tet, stored as 9 components in row-major order (xx xy xz yx ... zz).
  void add_cell_tensor(const std::string& name, const std::vector<Eigen::Matrix3d>& values);

  /// The complete XML document.
  std::string to_string(VtuEncoding encoding = VtuEncoding::Base64) const;
  /// Writes the document to `path` (via a temporary file and rename). Throws tmlab::Error.
  void write(const std::filesystem::path& path, VtuEncoding encoding = VtuEncoding::Base64) const;

 private:
  struct Field {
    std::string name;
    int components = 1;
    std::vector<double> values;
  };
  void check_new(const std::vector<Field>& fields, const std::string& name, std::size_t count,
                 std::size_t expected, const char* what) const;

  const Mesh* mesh_;
  const QuadraticMesh* quadratic_ = nullptr;
  std::vector<double> positions_;  ///< 3 per point; empty = rest positions
  std::vector<Field> point_fields_;
  std::vector<Field> cell_fields_;
};

/// A ParaView .pvd collection: (time, file) pairs. File names are stored relative to the .pvd's
/// directory when they lie below it, so the result directory can be moved.
class PvdWriter {
 public:
  explicit PvdWriter(std::filesystem::path pvd_path);

  /// Records one time step. Times need not be increasing (ParaView sorts them).
  void add(double time, const std::filesystem::path& file);
  /// Writes (or rewrites) the .pvd with every step added so far. Calling this after each add()
  /// keeps a valid, viewable collection on disk during a long run.
  void write() const;

  const std::filesystem::path& path() const { return path_; }
  std::size_t size() const { return entries_.size(); }

 private:
  std::filesystem::path path_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace tmlab
