// tmlab::XdmfTimeSeries: a time series of fields on one tet mesh as XDMF 3 (ParaView: "Xdmf3
// Reader"). The heavy data goes to one HDF5 file next to the .xdmf:
//   /mesh/geometry   (points x 3, float64)   rest positions
//   /mesh/topology   (tets x 4, int32)       0-based point indices
//   /mesh/physical   (tets, int32)           physical tag per tet (when the mesh has them)
//   /time            (steps, float64)        time of each step
//   /steps/000012/<field>                    per-step fields; "geometry" when positions were set
// and the .xdmf (a temporal collection of uniform grids, one per step) only references datasets in
// it by relative file name, so the pair can be moved together. The XML is written via a temporary
// file and a rename at flush()/close(), so it never references a step whose data is not written.
#pragma once

#include "core/io/hdf5_file.hpp"
#include "core/mesh/mesh.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace tmlab {

class XdmfTimeSeries {
 public:
  /// Creates (truncating) `xdmf_path` and the HDF5 file beside it (same stem, ".h5"), and writes
  /// the mesh. Keeps a reference to `mesh`, which must outlive this object.
  XdmfTimeSeries(std::filesystem::path xdmf_path, const Mesh& mesh);
  /// Closes if still open (errors are swallowed; call close() to see them). The XML then lists
  /// every step begun so far, so the data of an aborted run can still be inspected.
  ~XdmfTimeSeries();
  XdmfTimeSeries(const XdmfTimeSeries&) = delete;
  XdmfTimeSeries& operator=(const XdmfTimeSeries&) = delete;

  /// Starts a new step at `time`; the add_* and set_positions calls that follow belong to it.
  void begin_step(double time);
  /// Deformed positions (one per mesh point) for the current step; otherwise the rest geometry.
  void set_positions(const std::vector<Vec3>& positions);
  /// Fields of the current step. Names must be unique per step, non-empty, without '/'.
  void add_point_scalar(const std::string& name, const std::vector<double>& values);
  void add_point_vector(const std::string& name, const std::vector<Vec3>& values);
  void add_cell_scalar(const std::string& name, const std::vector<double>& values);
  /// One 3x3 tensor per tet, stored as (tets x 9), row-major.
  void add_cell_tensor(const std::string& name, const std::vector<Eigen::Matrix3d>& values);

  /// Flushes the HDF5 file and rewrites the .xdmf with all steps so far (for watching a long run).
  void flush();
  /// flush(), then closes the HDF5 file. Idempotent. Throws tmlab::Error.
  void close();

 private:
  enum class Center { Node, Cell };
  struct FieldRef {
    std::string name;
    Center center;
    int components;  ///< 1 scalar, 3 vector, 9 tensor
  };
  struct Step {
    double time = 0.0;
    std::string group;  ///< "/steps/000012"
    bool deformed = false;
    std::vector<FieldRef> fields;
  };
  Step& current(const std::string& what);
  void add_field(const std::string& name, Center center, int components, const std::vector<double>& flat);
  std::string xml() const;

  std::filesystem::path xdmf_path_;
  std::filesystem::path h5_path_;
  const Mesh* mesh_;
  H5File h5_;
  std::vector<Step> steps_;
  bool has_physical_ = false;
  bool closed_ = false;
};

}  // namespace tmlab
