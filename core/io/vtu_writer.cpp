// VtuWriter and PvdWriter: see vtu_writer.hpp.
#include "core/io/vtu_writer.hpp"

#include "core/base/error.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/xml_text.hpp"

#include <algorithm>
#include <cstring>
#include <type_traits>

#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "VtuWriter writes byte_order=\"LittleEndian\" binary data; port it for big-endian hosts"
#endif

namespace tmlab {

namespace {

constexpr int kVtkTetra = 10;
constexpr int kVtkQuadraticTetra = 24;

/// Appends one DataArray element with `count` values of type T.
template <typename T>
void data_array(std::string& out, const char* vtk_type, const std::string& name, int components,
                const T* values, std::size_t count, VtuEncoding encoding) {
  out += "        <DataArray type=\"";
  out += vtk_type;
  out += "\"";
  if (!name.empty()) out += " Name=\"" + xml_escape(name) + "\"";
  if (components != 1) out += " NumberOfComponents=\"" + std::to_string(components) + "\"";
  if (encoding == VtuEncoding::Base64) {
    out += " format=\"binary\">\n          ";
    // Uncompressed binary: one base64 block of [UInt64 byte count][raw bytes].
    const std::uint64_t bytes = count * sizeof(T);
    std::string raw(sizeof(bytes) + bytes, '\0');
    std::memcpy(raw.data(), &bytes, sizeof(bytes));
    if (bytes > 0) std::memcpy(raw.data() + sizeof(bytes), values, bytes);
    out += base64_encode(raw.data(), raw.size());
  } else {
    out += " format=\"ascii\">\n          ";
    const std::size_t per_line = components == 1 ? 6 : static_cast<std::size_t>(components);
    for (std::size_t i = 0; i < count; ++i) {
      if (i > 0) out += (i % per_line == 0) ? "\n          " : " ";
      if constexpr (std::is_floating_point_v<T>) {
        out += format_double(values[i]);
      } else {
        out += std::to_string(static_cast<long long>(values[i]));
      }
    }
  }
  out += "\n        </DataArray>\n";
}

}  // namespace

// --- VtuWriter -----------------------------------------------------------------------------------

VtuWriter::VtuWriter(const Mesh& mesh) : mesh_(&mesh) {}

VtuWriter::VtuWriter(const Mesh& nodes, const QuadraticMesh& quadratic)
    : mesh_(&nodes), quadratic_(&quadratic) {
  if (nodes.points.size() != quadratic.points.size() || nodes.tets.size() != quadratic.tets.size())
    throw Error("vtu: the node mesh does not match the quadratic mesh (" +
                std::to_string(nodes.points.size()) + " points, " + std::to_string(nodes.tets.size()) +
                " tets against " + std::to_string(quadratic.points.size()) + ", " +
                std::to_string(quadratic.tets.size()) + ")");
}

void VtuWriter::set_positions(const std::vector<Vec3>& positions) {
  if (positions.size() != mesh_->points.size()) {
    throw Error("VTU output: " + std::to_string(positions.size()) + " positions for a mesh of " +
                std::to_string(mesh_->points.size()) + " points");
  }
  positions_.resize(3 * positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    for (int c = 0; c < 3; ++c) positions_[3 * i + c] = positions[i][c];
  }
}

void VtuWriter::set_displacement(const std::vector<Vec3>& displacement) {
  if (displacement.size() != mesh_->points.size()) {
    throw Error("VTU output: " + std::to_string(displacement.size()) + " displacements for a mesh of " +
                std::to_string(mesh_->points.size()) + " points");
  }
  std::vector<Vec3> x(displacement.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = mesh_->points[i] + displacement[i];
  set_positions(x);
}

void VtuWriter::check_new(const std::vector<Field>& fields, const std::string& name, std::size_t count,
                          std::size_t expected, const char* what) const {
  if (name.empty()) throw Error(std::string("VTU output: ") + what + " field needs a name");
  if (count != expected) {
    throw Error("VTU output: " + std::string(what) + " field '" + name + "' has " + std::to_string(count) +
                " entries, the mesh needs " + std::to_string(expected));
  }
  for (const Field& f : fields) {
    if (f.name == name) throw Error("VTU output: duplicate " + std::string(what) + " field '" + name + "'");
  }
}

void VtuWriter::add_point_scalar(const std::string& name, const std::vector<double>& values) {
  check_new(point_fields_, name, values.size(), mesh_->points.size(), "point");
  point_fields_.push_back(Field{name, 1, values});
}

void VtuWriter::add_point_vector(const std::string& name, const std::vector<Vec3>& values) {
  check_new(point_fields_, name, values.size(), mesh_->points.size(), "point");
  Field f{name, 3, std::vector<double>(3 * values.size())};
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (int c = 0; c < 3; ++c) f.values[3 * i + c] = values[i][c];
  }
  point_fields_.push_back(std::move(f));
}

void VtuWriter::add_cell_scalar(const std::string& name, const std::vector<double>& values) {
  check_new(cell_fields_, name, values.size(), mesh_->tets.size(), "cell");
  cell_fields_.push_back(Field{name, 1, values});
}

void VtuWriter::add_cell_tensor(const std::string& name, const std::vector<Eigen::Matrix3d>& values) {
  check_new(cell_fields_, name, values.size(), mesh_->tets.size(), "cell");
  Field f{name, 9, std::vector<double>(9 * values.size())};
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) f.values[9 * i + 3 * r + c] = values[i](r, c);
    }
  }
  cell_fields_.push_back(std::move(f));
}

std::string VtuWriter::to_string(VtuEncoding encoding) const {
  const Mesh& m = *mesh_;
  const std::size_t np = m.points.size();
  const std::size_t nc = m.tets.size();
  std::vector<double> xyz = positions_;
  if (xyz.empty()) {
    xyz.resize(3 * np);
    for (std::size_t i = 0; i < np; ++i) {
      for (int c = 0; c < 3; ++c) xyz[3 * i + c] = m.points[i][c];
    }
  }
  const std::size_t nv = quadratic_ ? 10 : 4;
  std::vector<std::int64_t> connectivity(nv * nc);
  std::vector<std::int64_t> offsets(nc);
  for (std::size_t e = 0; e < nc; ++e) {
    for (std::size_t k = 0; k < nv; ++k)
      connectivity[nv * e + k] = quadratic_ ? quadratic_->tets[e][k] : m.tets[e][k];
    offsets[e] = static_cast<std::int64_t>(nv * (e + 1));
  }
  const std::vector<std::uint8_t> types(
      nc, static_cast<std::uint8_t>(quadratic_ ? kVtkQuadraticTetra : kVtkTetra));

  std::string out;
  out.reserve(64 * (np + nc) + 1024);
  out += "<?xml version=\"1.0\"?>\n";
  out +=
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n";
  out += "  <UnstructuredGrid>\n";
  out += "    <Piece NumberOfPoints=\"" + std::to_string(np) + "\" NumberOfCells=\"" + std::to_string(nc) +
         "\">\n";

  const auto write_fields = [&](const char* tag, const std::vector<Field>& fields) {
    if (fields.empty()) return;
    out += std::string("      <") + tag;
    // Mark the first scalar/vector/tensor as active so ParaView colours by something sensible.
    for (const auto& [attr, comps] :
         {std::pair{"Scalars", 1}, std::pair{"Vectors", 3}, std::pair{"Tensors", 9}}) {
      const auto it =
          std::find_if(fields.begin(), fields.end(), [&](const Field& f) { return f.components == comps; });
      if (it != fields.end()) out += std::string(" ") + attr + "=\"" + xml_escape(it->name) + "\"";
    }
    out += ">\n";
    for (const Field& f : fields) {
      data_array(out, "Float64", f.name, f.components, f.values.data(), f.values.size(), encoding);
    }
    out += std::string("      </") + tag + ">\n";
  };
  write_fields("PointData", point_fields_);
  write_fields("CellData", cell_fields_);

  out += "      <Points>\n";
  data_array(out, "Float64", "Points", 3, xyz.data(), xyz.size(), encoding);
  out += "      </Points>\n";
  out += "      <Cells>\n";
  data_array(out, "Int64", "connectivity", 1, connectivity.data(), connectivity.size(), encoding);
  data_array(out, "Int64", "offsets", 1, offsets.data(), offsets.size(), encoding);
  data_array(out, "UInt8", "types", 1, types.data(), types.size(), encoding);
  out += "      </Cells>\n";
  out += "    </Piece>\n";
  out += "  </UnstructuredGrid>\n";
  out += "</VTKFile>\n";
  return out;
}

void VtuWriter::write(const std::filesystem::path& path, VtuEncoding encoding) const {
  write_file_atomically(path, to_string(encoding));
}

// --- PvdWriter -----------------------------------------------------------------------------------

PvdWriter::PvdWriter(std::filesystem::path pvd_path) : path_(std::move(pvd_path)) {}

void PvdWriter::add(double time, const std::filesystem::path& file) {
  std::filesystem::path stored = file;
  if (file.is_absolute()) {
    const std::filesystem::path base = std::filesystem::absolute(path_).parent_path();
    const std::filesystem::path rel = file.lexically_relative(base);
    if (!rel.empty() && *rel.begin() != "..") stored = rel;
  }
  entries_.emplace_back(time, stored.generic_string());
}

void PvdWriter::write() const {
  std::string out;
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  out += "  <Collection>\n";
  for (const auto& [time, file] : entries_) {
    out += "    <DataSet timestep=\"" + format_double(time) + "\" group=\"\" part=\"0\" file=\"" +
           xml_escape(file) + "\"/>\n";
  }
  out += "  </Collection>\n";
  out += "</VTKFile>\n";
  write_file_atomically(path_, out);
}

}  // namespace tmlab
