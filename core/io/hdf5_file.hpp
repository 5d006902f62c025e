// tmlab::H5File: a small RAII wrapper over the HDF5 C API for result files (fields, time series,
// attributes). It hides hid_t bookkeeping, creates intermediate groups ("/steps/000012/u"), and turns
// every HDF5 failure into a tmlab::Error that names the file and the object; HDF5's own error
// printing is switched off for the duration of each call and its error stack is folded into the
// message instead.
//
// Works with the OpenMPI flavour of libhdf5 in a serial program: files are opened with the default
// (sec2) file-access property list, which never touches MPI, so no MPI_Init is needed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tmlab {

/// Element type of a dataset, as seen by the caller.
enum class H5Type { Float64, Int32, Int64, Other };

/// An open HDF5 file. Move-only; closes the file when destroyed (without throwing).
class H5File {
 public:
  using Dims = std::vector<std::size_t>;

  /// Call first thing in main(), before any HDF5 call: HDF5's own clean-up at exit would try again
  /// to flush a file whose write failed (a full disk) and loop ("infinite loop closing library") or
  /// crash after the command has reported the error. Every H5File is closed by its owner, so nothing
  /// needs that clean-up. Returns false when HDF5 was already in use (then it has no effect).
  static bool skip_library_cleanup_at_exit();

  /// Creates (truncating any existing file) `path` for reading and writing.
  static H5File create(const std::string& path);
  /// Opens an existing file read-only.
  static H5File open_read(const std::string& path);

  H5File(H5File&& other) noexcept;
  H5File& operator=(H5File&& other) noexcept;
  H5File(const H5File&) = delete;
  H5File& operator=(const H5File&) = delete;
  ~H5File();

  /// Flushes and closes the file; throws tmlab::Error on failure. Idempotent.
  void close();
  /// Flushes buffered data to disk (the file stays open).
  void flush();
  bool is_open() const { return id_ >= 0; }
  const std::string& path() const { return path_; }

  /// True when `object` (absolute path, e.g. "/steps/000012/u") names a group or dataset.
  bool exists(const std::string& object) const;
  /// Names of the direct members of a group, sorted by name.
  std::vector<std::string> list(const std::string& group) const;
  /// Creates a group and any missing parent groups; no-op when it exists.
  void create_group(const std::string& group);

  /// Writes a dataset of shape `dims` (row-major, product(dims) == data.size()), creating missing
  /// parent groups. An existing dataset of that name is replaced.
  void write(const std::string& dataset, const std::vector<double>& data, const Dims& dims);
  void write(const std::string& dataset, const std::vector<std::int32_t>& data, const Dims& dims);
  void write(const std::string& dataset, const std::vector<std::int64_t>& data, const Dims& dims);

  /// Shape of an existing dataset.
  Dims dims(const std::string& dataset) const;
  /// Element type of an existing dataset.
  H5Type type(const std::string& dataset) const;
  /// Reads a whole dataset, converting to the requested type (HDF5 converts numeric types).
  std::vector<double> read_double(const std::string& dataset, Dims* dims = nullptr) const;
  std::vector<std::int32_t> read_int32(const std::string& dataset, Dims* dims = nullptr) const;
  std::vector<std::int64_t> read_int64(const std::string& dataset, Dims* dims = nullptr) const;

  /// Appends one value to an extendible 1-D float64 dataset, creating it (empty, chunked) first.
  void append(const std::string& dataset, double value);
  /// Appends one row to an extendible 2-D float64 dataset of shape (n, row.size()), creating it
  /// first. Every row must have the width of the first one.
  void append_row(const std::string& dataset, const std::vector<double>& row);

  /// Attributes on a group or dataset (use "/" for the file). An existing attribute is replaced.
  void set_attribute(const std::string& object, const std::string& name, const std::string& value);
  void set_attribute(const std::string& object, const std::string& name, const char* value);
  void set_attribute(const std::string& object, const std::string& name, double value);
  void set_attribute(const std::string& object, const std::string& name, std::int64_t value);
  void set_attribute(const std::string& object, const std::string& name, int value);
  bool has_attribute(const std::string& object, const std::string& name) const;
  std::string string_attribute(const std::string& object, const std::string& name) const;
  double double_attribute(const std::string& object, const std::string& name) const;
  std::int64_t int_attribute(const std::string& object, const std::string& name) const;

 private:
  H5File(std::int64_t id, std::string path) : id_(id), path_(std::move(path)) {}
  void require_open(const std::string& object) const;
  template <typename T>
  void write_impl(const std::string& dataset, const T* data, const Dims& dims);
  template <typename T>
  std::vector<T> read_impl(const std::string& dataset, Dims* dims) const;
  template <typename T>
  void append_impl(const std::string& dataset, const T* row, std::size_t width, bool two_d);
  template <typename T>
  void set_numeric_attribute(const std::string& object, const std::string& name, T value);
  template <typename T>
  T numeric_attribute(const std::string& object, const std::string& name) const;

  std::int64_t id_ = -1;  ///< hid_t of the file (-1 when closed); hid_t is int64_t in HDF5 >= 1.10
  std::string path_;
};

}  // namespace tmlab
