// tmlab::H5File: see hdf5_file.hpp.
#include "core/io/hdf5_file.hpp"

#include "core/base/error.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <numeric>
#include <type_traits>

namespace tmlab {

static_assert(std::is_same_v<hid_t, std::int64_t>, "H5File stores hid_t as int64_t (HDF5 >= 1.10)");

namespace {

/// Switches HDF5's automatic error printing off for its lifetime (restoring the previous handler
/// afterwards) and clears the error stack so a failure's stack holds only this call's frames.
class QuietErrors {
 public:
  QuietErrors() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    H5Eclear2(H5E_DEFAULT);
  }
  ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

herr_t collect_error(unsigned /*n*/, const H5E_error2_t* err, void* client) {
  auto* out = static_cast<std::vector<std::string>*>(client);
  if (err->desc != nullptr && err->desc[0] != '\0') out->push_back(err->desc);
  return 0;
}

/// One line, at most ~240 characters.
std::string squash(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    if (c == ' ' && !out.empty() && out.back() == ' ') continue;
    out += c;
  }
  if (out.size() > 240) out = out.substr(0, 237) + "...";
  return out;
}

/// The error for a failed HDF5 call: "file: object: what [HDF5: ...]".
Error h5_error(const std::string& file, const std::string& object, const std::string& what) {
  std::vector<std::string> frames;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, &collect_error, &frames);
  H5Eclear2(H5E_DEFAULT);
  std::string msg = file;
  if (!object.empty()) msg += ": " + object;
  msg += ": " + what;
  // A system error (a full disk above all) first, in words, before HDF5's long frames are cut.
  for (const std::string& f : frames) {
    const auto at = f.find("errno = ");
    if (at == std::string::npos) continue;
    const int code = std::atoi(f.c_str() + at + 8);
    if (code > 0) msg += ": " + std::string(std::strerror(code));
    break;
  }
  // The innermost frame is the most specific reason (e.g. "errno = 2, ... No such file").
  if (frames.size() == 1) msg += " (HDF5: " + squash(frames.front()) + ")";
  if (frames.size() > 1) msg += " (HDF5: " + squash(frames.front() + ": " + frames.back()) + ")";
  return Error(msg);
}

/// Owns one hid_t and closes it with the matching H5?close function.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  Closer closer_;
};

template <typename T>
struct H5Traits;
template <>
struct H5Traits<double> {
  static hid_t mem() { return H5T_NATIVE_DOUBLE; }
  static hid_t file() { return H5T_IEEE_F64LE; }
};
template <>
struct H5Traits<std::int32_t> {
  static hid_t mem() { return H5T_NATIVE_INT32; }
  static hid_t file() { return H5T_STD_I32LE; }
};
template <>
struct H5Traits<std::int64_t> {
  static hid_t mem() { return H5T_NATIVE_INT64; }
  static hid_t file() { return H5T_STD_I64LE; }
};

/// "/a/b/c" for "a/b/c", "/a/b/c/" or "//a//b/c".
std::string normalize(const std::string& path) {
  std::string out;
  bool slash = false;
  for (char c : path) {
    if (c == '/') {
      slash = true;
      continue;
    }
    if (slash || out.empty()) out += '/';
    slash = false;
    out += c;
  }
  return out.empty() ? "/" : out;
}

std::string parent_of(const std::string& norm) {
  const auto pos = norm.rfind('/');
  return pos == 0 ? "/" : norm.substr(0, pos);
}

std::size_t product(const H5File::Dims& dims) {
  return std::accumulate(dims.begin(), dims.end(), std::size_t{1}, std::multiplies<>());
}

std::string dims_text(const H5File::Dims& dims) {
  std::string s = "(";
  for (std::size_t i = 0; i < dims.size(); ++i) s += (i ? ", " : "") + std::to_string(dims[i]);
  return s + ")";
}

}  // namespace

// --- lifetime ------------------------------------------------------------------------------------

bool H5File::skip_library_cleanup_at_exit() { return H5dont_atexit() >= 0; }

H5File H5File::create(const std::string& path) {
  QuietErrors quiet;
  const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (id < 0) throw h5_error(path, "", "cannot create HDF5 file");
  return H5File(id, path);
}

H5File H5File::open_read(const std::string& path) {
  if (!std::filesystem::exists(path)) throw Error(path + ": no such file");
  QuietErrors quiet;
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) throw h5_error(path, "", "cannot open HDF5 file for reading");
  return H5File(id, path);
}

H5File::H5File(H5File&& other) noexcept : id_(other.id_), path_(std::move(other.path_)) { other.id_ = -1; }

H5File& H5File::operator=(H5File&& other) noexcept {
  if (this != &other) {
    if (id_ >= 0) {
      QuietErrors quiet;
      H5Fclose(id_);
    }
    id_ = other.id_;
    path_ = std::move(other.path_);
    other.id_ = -1;
  }
  return *this;
}

H5File::~H5File() {
  if (id_ >= 0) {
    QuietErrors quiet;
    H5Fclose(id_);
  }
}

void H5File::close() {
  if (id_ < 0) return;
  QuietErrors quiet;
  const hid_t id = id_;
  id_ = -1;
  if (H5Fclose(id) < 0) throw h5_error(path_, "", "cannot close HDF5 file");
}

void H5File::flush() {
  require_open("");
  QuietErrors quiet;
  if (H5Fflush(id_, H5F_SCOPE_LOCAL) < 0) throw h5_error(path_, "", "cannot flush HDF5 file");
}

void H5File::require_open(const std::string& object) const {
  if (id_ < 0) throw Error(path_ + (object.empty() ? "" : ": " + object) + ": HDF5 file is not open");
}

// --- groups --------------------------------------------------------------------------------------

bool H5File::exists(const std::string& object) const {
  require_open(object);
  QuietErrors quiet;
  const std::string norm = normalize(object);
  if (norm == "/") return true;
  // H5Lexists fails (rather than returning false) when an intermediate group is missing, so walk.
  std::size_t pos = 0;
  while (pos != std::string::npos) {
    pos = norm.find('/', pos + 1);
    const std::string prefix = norm.substr(0, pos);
    const htri_t e = H5Lexists(id_, prefix.c_str(), H5P_DEFAULT);
    if (e <= 0) return false;  // < 0: a prefix is not a group (e.g. a dataset)
  }
  const htri_t o = H5Oexists_by_name(id_, norm.c_str(), H5P_DEFAULT);
  return o > 0;
}

std::vector<std::string> H5File::list(const std::string& group) const {
  require_open(group);
  const std::string norm = normalize(group);
  if (!exists(norm)) throw Error(path_ + ": " + norm + ": no such group");
  QuietErrors quiet;
  Handle g(H5Gopen2(id_, norm.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.ok()) throw h5_error(path_, norm, "cannot open group");
  H5G_info_t info;
  if (H5Gget_info(g.get(), &info) < 0) throw h5_error(path_, norm, "cannot query group");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t n =
        H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (n < 0) throw h5_error(path_, norm, "cannot read member name");
    std::string name(static_cast<std::size_t>(n) + 1, '\0');
    H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(n));
    names.push_back(std::move(name));
  }
  std::sort(names.begin(), names.end());
  return names;
}

void H5File::create_group(const std::string& group) {
  require_open(group);
  const std::string norm = normalize(group);
  if (exists(norm)) {
    QuietErrors quiet;
    Handle g(H5Gopen2(id_, norm.c_str(), H5P_DEFAULT), H5Gclose);
    if (!g.ok()) throw Error(path_ + ": " + norm + ": exists and is not a group");
    return;
  }
  QuietErrors quiet;
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.get(), 1);
  Handle g(H5Gcreate2(id_, norm.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!g.ok()) throw h5_error(path_, norm, "cannot create group");
}

// --- fixed-size datasets -------------------------------------------------------------------------

template <typename T>
void H5File::write_impl(const std::string& dataset, const T* data, const Dims& dims) {
  require_open(dataset);
  const std::string norm = normalize(dataset);
  if (norm == "/") throw Error(path_ + ": cannot write a dataset named \"/\"");
  const std::size_t n = product(dims);
  if (n > 0 && data == nullptr) throw Error(path_ + ": " + norm + ": no data for " + dims_text(dims));
  const std::string parent = parent_of(norm);
  create_group(parent);
  if (exists(norm)) {
    QuietErrors quiet;
    if (H5Ldelete(id_, norm.c_str(), H5P_DEFAULT) < 0) throw h5_error(path_, norm, "cannot replace dataset");
  }
  QuietErrors quiet;
  const std::vector<hsize_t> hdims(dims.begin(), dims.end());
  Handle space(dims.empty() ? H5Screate(H5S_SCALAR)
                            : H5Screate_simple(static_cast<int>(hdims.size()), hdims.data(), nullptr),
               H5Sclose);
  if (!space.ok()) throw h5_error(path_, norm, "cannot create dataspace " + dims_text(dims));
  Handle dset(
      H5Dcreate2(id_, norm.c_str(), H5Traits<T>::file(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose);
  if (!dset.ok()) throw h5_error(path_, norm, "cannot create dataset");
  if (n > 0 && H5Dwrite(dset.get(), H5Traits<T>::mem(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    throw h5_error(path_, norm, "cannot write dataset");
  }
}

namespace {
template <typename T>
void check_size(const std::string& file, const std::string& dataset, std::size_t size,
                const H5File::Dims& dims) {
  if (size != product(dims)) {
    throw Error(file + ": " + normalize(dataset) + ": " + std::to_string(size) + " values do not fill dims " +
                dims_text(dims));
  }
}
}  // namespace

void H5File::write(const std::string& dataset, const std::vector<double>& data, const Dims& dims) {
  check_size<double>(path_, dataset, data.size(), dims);
  write_impl(dataset, data.data(), dims);
}
void H5File::write(const std::string& dataset, const std::vector<std::int32_t>& data, const Dims& dims) {
  check_size<std::int32_t>(path_, dataset, data.size(), dims);
  write_impl(dataset, data.data(), dims);
}
void H5File::write(const std::string& dataset, const std::vector<std::int64_t>& data, const Dims& dims) {
  check_size<std::int64_t>(path_, dataset, data.size(), dims);
  write_impl(dataset, data.data(), dims);
}

H5File::Dims H5File::dims(const std::string& dataset) const {
  require_open(dataset);
  const std::string norm = normalize(dataset);
  if (!exists(norm)) throw Error(path_ + ": " + norm + ": no such dataset");
  QuietErrors quiet;
  Handle dset(H5Dopen2(id_, norm.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dset.ok()) throw h5_error(path_, norm, "cannot open dataset");
  Handle space(H5Dget_space(dset.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) throw h5_error(path_, norm, "cannot read dataset shape");
  std::vector<hsize_t> hdims(static_cast<std::size_t>(rank));
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), hdims.data(), nullptr);
  return Dims(hdims.begin(), hdims.end());
}

H5Type H5File::type(const std::string& dataset) const {
  require_open(dataset);
  const std::string norm = normalize(dataset);
  if (!exists(norm)) throw Error(path_ + ": " + norm + ": no such dataset");
  QuietErrors quiet;
  Handle dset(H5Dopen2(id_, norm.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dset.ok()) throw h5_error(path_, norm, "cannot open dataset");
  Handle t(H5Dget_type(dset.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(t.get());
  const std::size_t size = H5Tget_size(t.get());
  if (cls == H5T_FLOAT && size == 8) return H5Type::Float64;
  if (cls == H5T_INTEGER && H5Tget_sign(t.get()) == H5T_SGN_2) {
    if (size == 4) return H5Type::Int32;
    if (size == 8) return H5Type::Int64;
  }
  return H5Type::Other;
}

template <typename T>
std::vector<T> H5File::read_impl(const std::string& dataset, Dims* dims_out) const {
  const Dims d = dims(dataset);  // checks existence
  const std::string norm = normalize(dataset);
  QuietErrors quiet;
  Handle dset(H5Dopen2(id_, norm.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dset.ok()) throw h5_error(path_, norm, "cannot open dataset");
  std::vector<T> data(product(d));
  if (!data.empty() &&
      H5Dread(dset.get(), H5Traits<T>::mem(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()) < 0) {
    throw h5_error(path_, norm, "cannot read dataset");
  }
  if (dims_out) *dims_out = d;
  return data;
}

std::vector<double> H5File::read_double(const std::string& dataset, Dims* dims_out) const {
  return read_impl<double>(dataset, dims_out);
}
std::vector<std::int32_t> H5File::read_int32(const std::string& dataset, Dims* dims_out) const {
  return read_impl<std::int32_t>(dataset, dims_out);
}
std::vector<std::int64_t> H5File::read_int64(const std::string& dataset, Dims* dims_out) const {
  return read_impl<std::int64_t>(dataset, dims_out);
}

// --- extendible datasets -------------------------------------------------------------------------

template <typename T>
void H5File::append_impl(const std::string& dataset, const T* row, std::size_t width, bool two_d) {
  require_open(dataset);
  const std::string norm = normalize(dataset);
  if (two_d && width == 0) throw Error(path_ + ": " + norm + ": cannot append an empty row");
  const hsize_t w = two_d ? width : 1;
  if (!exists(norm)) {
    create_group(parent_of(norm));
    QuietErrors quiet;
    const int rank = two_d ? 2 : 1;
    const hsize_t dims0[2] = {0, w};
    const hsize_t maxdims[2] = {H5S_UNLIMITED, w};
    // Chunks of about 32 KiB: small enough for short series, large enough for long ones.
    const hsize_t chunk[2] = {std::max<hsize_t>(1, 4096 / w), w};
    Handle space(H5Screate_simple(rank, dims0, maxdims), H5Sclose);
    Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    if (!space.ok() || !dcpl.ok() || H5Pset_chunk(dcpl.get(), rank, chunk) < 0) {
      throw h5_error(path_, norm, "cannot set up extendible dataset");
    }
    Handle d(
        H5Dcreate2(id_, norm.c_str(), H5Traits<T>::file(), space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
        H5Dclose);
    if (!d.ok()) throw h5_error(path_, norm, "cannot create extendible dataset");
  }
  const Dims d = dims(norm);
  if (d.size() != (two_d ? 2u : 1u) || (two_d && d[1] != width)) {
    throw Error(path_ + ": " + norm + ": cannot append " +
                (two_d ? "a row of " + std::to_string(width) : "a value") + " to a dataset of shape " +
                dims_text(d));
  }
  QuietErrors quiet;
  Handle dset(H5Dopen2(id_, norm.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dset.ok()) throw h5_error(path_, norm, "cannot open dataset");
  const hsize_t newdims[2] = {d[0] + 1, w};
  if (H5Dset_extent(dset.get(), newdims) < 0) {
    throw h5_error(path_, norm, "cannot extend dataset (is it extendible?)");
  }
  Handle fspace(H5Dget_space(dset.get()), H5Sclose);
  const hsize_t start[2] = {d[0], 0};
  const hsize_t count[2] = {1, w};
  const int rank = two_d ? 2 : 1;
  Handle mspace(H5Screate_simple(rank, count, nullptr), H5Sclose);
  if (H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start, nullptr, count, nullptr) < 0 ||
      H5Dwrite(dset.get(), H5Traits<T>::mem(), mspace.get(), fspace.get(), H5P_DEFAULT, row) < 0) {
    throw h5_error(path_, norm, "cannot write appended row");
  }
}

void H5File::append(const std::string& dataset, double value) { append_impl(dataset, &value, 1, false); }
void H5File::append_row(const std::string& dataset, const std::vector<double>& row) {
  append_impl(dataset, row.data(), row.size(), true);
}

// --- attributes ----------------------------------------------------------------------------------

namespace {
/// Opens `object` for attribute work, or throws naming it.
hid_t open_object(hid_t file, const std::string& fname, const std::string& norm) {
  const hid_t obj = H5Oopen(file, norm.c_str(), H5P_DEFAULT);
  if (obj < 0) throw h5_error(fname, norm, "cannot open object for attributes");
  return obj;
}
}  // namespace

void H5File::set_attribute(const std::string& object, const std::string& name, const std::string& value) {
  require_open(object);
  const std::string norm = normalize(object);
  if (!exists(norm)) throw Error(path_ + ": " + norm + ": no such object for attribute '" + name + "'");
  QuietErrors quiet;
  Handle obj(open_object(id_, path_, norm), H5Oclose);
  if (H5Aexists(obj.get(), name.c_str()) > 0) H5Adelete(obj.get(), name.c_str());
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), value.size() + 1);
  H5Tset_strpad(type.get(), H5T_STR_NULLTERM);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(obj.get(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose);
  if (!attr.ok() || H5Awrite(attr.get(), type.get(), value.c_str()) < 0) {
    throw h5_error(path_, norm, "cannot write attribute '" + name + "'");
  }
}

void H5File::set_attribute(const std::string& object, const std::string& name, const char* value) {
  set_attribute(object, name, std::string(value ? value : ""));
}

template <typename T>
void H5File::set_numeric_attribute(const std::string& object, const std::string& name, T value) {
  require_open(object);
  const std::string norm = normalize(object);
  if (!exists(norm)) throw Error(path_ + ": " + norm + ": no such object for attribute '" + name + "'");
  QuietErrors quiet;
  Handle obj(open_object(id_, path_, norm), H5Oclose);
  if (H5Aexists(obj.get(), name.c_str()) > 0) H5Adelete(obj.get(), name.c_str());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(obj.get(), name.c_str(), H5Traits<T>::file(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose);
  if (!attr.ok() || H5Awrite(attr.get(), H5Traits<T>::mem(), &value) < 0) {
    throw h5_error(path_, norm, "cannot write attribute '" + name + "'");
  }
}

void H5File::set_attribute(const std::string& object, const std::string& name, double value) {
  set_numeric_attribute(object, name, value);
}
void H5File::set_attribute(const std::string& object, const std::string& name, std::int64_t value) {
  set_numeric_attribute(object, name, value);
}
void H5File::set_attribute(const std::string& object, const std::string& name, int value) {
  set_numeric_attribute(object, name, static_cast<std::int64_t>(value));
}

bool H5File::has_attribute(const std::string& object, const std::string& name) const {
  require_open(object);
  const std::string norm = normalize(object);
  if (!exists(norm)) return false;
  QuietErrors quiet;
  Handle obj(open_object(id_, path_, norm), H5Oclose);
  return H5Aexists(obj.get(), name.c_str()) > 0;
}

std::string H5File::string_attribute(const std::string& object, const std::string& name) const {
  if (!has_attribute(object, name)) {
    throw Error(path_ + ": " + normalize(object) + ": no attribute '" + name + "'");
  }
  const std::string norm = normalize(object);
  QuietErrors quiet;
  Handle obj(open_object(id_, path_, norm), H5Oclose);
  Handle attr(H5Aopen(obj.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
  Handle ftype(H5Aget_type(attr.get()), H5Tclose);
  if (!attr.ok() || !ftype.ok() || H5Tget_class(ftype.get()) != H5T_STRING) {
    throw h5_error(path_, norm, "attribute '" + name + "' is not a string");
  }
  if (H5Tis_variable_str(ftype.get()) > 0) {
    Handle mtype(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(mtype.get(), H5T_VARIABLE);
    char* buf = nullptr;
    if (H5Aread(attr.get(), mtype.get(), &buf) < 0)
      throw h5_error(path_, norm, "cannot read attribute '" + name + "'");
    std::string value = buf ? buf : "";
    H5free_memory(buf);
    return value;
  }
  const std::size_t size = H5Tget_size(ftype.get());
  std::string buf(size + 1, '\0');
  Handle mtype(H5Tcopy(ftype.get()), H5Tclose);
  if (H5Aread(attr.get(), mtype.get(), buf.data()) < 0) {
    throw h5_error(path_, norm, "cannot read attribute '" + name + "'");
  }
  buf.resize(buf.find('\0') == std::string::npos ? size : buf.find('\0'));
  return buf;
}

template <typename T>
T H5File::numeric_attribute(const std::string& object, const std::string& name) const {
  if (!has_attribute(object, name)) {
    throw Error(path_ + ": " + normalize(object) + ": no attribute '" + name + "'");
  }
  const std::string norm = normalize(object);
  QuietErrors quiet;
  Handle obj(open_object(id_, path_, norm), H5Oclose);
  Handle attr(H5Aopen(obj.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  Handle ftype(H5Aget_type(attr.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(ftype.get());
  if (!attr.ok() || (cls != H5T_FLOAT && cls != H5T_INTEGER) ||
      H5Sget_simple_extent_npoints(space.get()) != 1) {
    throw h5_error(path_, norm, "attribute '" + name + "' is not a numeric scalar");
  }
  T value{};
  if (H5Aread(attr.get(), H5Traits<T>::mem(), &value) < 0) {
    throw h5_error(path_, norm, "cannot read attribute '" + name + "'");
  }
  return value;
}

double H5File::double_attribute(const std::string& object, const std::string& name) const {
  return numeric_attribute<double>(object, name);
}
std::int64_t H5File::int_attribute(const std::string& object, const std::string& name) const {
  return numeric_attribute<std::int64_t>(object, name);
}

}  // namespace tmlab
