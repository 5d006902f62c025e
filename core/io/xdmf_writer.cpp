// XdmfTimeSeries: see xdmf_writer.hpp.
#include "core/io/xdmf_writer.hpp"

#include "core/base/error.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/xml_text.hpp"

#include <cstdio>

namespace tmlab {

namespace {

std::filesystem::path h5_path_for(const std::filesystem::path& xdmf) {
  std::filesystem::path p = xdmf;
  p.replace_extension(".h5");
  if (p == xdmf) p += ".h5";
  return p;
}

std::string step_group(std::size_t index) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "/steps/%06zu", index);
  return buf;
}

/// <DataItem> for an HDF5 dataset.
std::string data_item(const std::string& h5_name, const std::string& dataset, std::size_t rows, int cols,
                      bool is_int, const std::string& indent) {
  std::string dims = std::to_string(rows);
  if (cols != 1) dims += " " + std::to_string(cols);
  return indent + "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + (is_int ? "Int" : "Float") +
         "\" Precision=\"" + (is_int ? "4" : "8") + "\" Format=\"HDF\">" + xml_escape(h5_name) + ":" +
         xml_escape(dataset) + "</DataItem>\n";
}

}  // namespace

XdmfTimeSeries::XdmfTimeSeries(std::filesystem::path xdmf_path, const Mesh& mesh)
    : xdmf_path_(std::move(xdmf_path)),
      h5_path_(h5_path_for(xdmf_path_)),
      mesh_(&mesh),
      h5_(H5File::create(h5_path_.string())) {
  const std::size_t np = mesh.points.size();
  const std::size_t nc = mesh.tets.size();
  std::vector<double> xyz(3 * np);
  for (std::size_t i = 0; i < np; ++i) {
    for (int c = 0; c < 3; ++c) xyz[3 * i + c] = mesh.points[i][c];
  }
  std::vector<std::int32_t> topo(4 * nc);
  for (std::size_t e = 0; e < nc; ++e) {
    for (int k = 0; k < 4; ++k) topo[4 * e + k] = mesh.tets[e][k];
  }
  h5_.write("/mesh/geometry", xyz, {np, 3});
  h5_.write("/mesh/topology", topo, {nc, 4});
  if (!mesh.tet_physical.empty()) {
    if (mesh.tet_physical.size() != nc) {
      throw Error(xdmf_path_.string() + ": mesh has " + std::to_string(mesh.tet_physical.size()) +
                  " physical tags for " + std::to_string(nc) + " tets");
    }
    h5_.write("/mesh/physical", std::vector<std::int32_t>(mesh.tet_physical.begin(), mesh.tet_physical.end()),
              {nc});
    has_physical_ = true;
  }
  h5_.create_group("/steps");
  h5_.set_attribute("/", "writer", "tmlab XdmfTimeSeries");
}

XdmfTimeSeries::~XdmfTimeSeries() {
  try {
    close();
  } catch (...) {
    // Destructors must not throw; close() explicitly to see the error.
  }
}

XdmfTimeSeries::Step& XdmfTimeSeries::current(const std::string& what) {
  if (closed_) throw Error(xdmf_path_.string() + ": " + what + " after close()");
  if (steps_.empty()) throw Error(xdmf_path_.string() + ": " + what + " before begin_step()");
  return steps_.back();
}

void XdmfTimeSeries::begin_step(double time) {
  if (closed_) throw Error(xdmf_path_.string() + ": begin_step after close()");
  Step s;
  s.time = time;
  s.group = step_group(steps_.size());
  h5_.create_group(s.group);
  h5_.set_attribute(s.group, "time", time);
  h5_.append("/time", time);
  steps_.push_back(std::move(s));
}

void XdmfTimeSeries::set_positions(const std::vector<Vec3>& positions) {
  Step& s = current("set_positions");
  if (positions.size() != mesh_->points.size()) {
    throw Error(xdmf_path_.string() + ": " + std::to_string(positions.size()) + " positions for a mesh of " +
                std::to_string(mesh_->points.size()) + " points");
  }
  std::vector<double> xyz(3 * positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    for (int c = 0; c < 3; ++c) xyz[3 * i + c] = positions[i][c];
  }
  h5_.write(s.group + "/geometry", xyz, {positions.size(), 3});
  s.deformed = true;
}

void XdmfTimeSeries::add_field(const std::string& name, Center center, int components,
                               const std::vector<double>& flat) {
  Step& s = current("adding field '" + name + "'");
  if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "geometry") {
    throw Error(xdmf_path_.string() + ": invalid field name '" + name + "' (empty, '/', '.' or 'geometry')");
  }
  for (const FieldRef& f : s.fields) {
    if (f.name == name) throw Error(xdmf_path_.string() + ": duplicate field '" + name + "' in " + s.group);
  }
  const std::size_t rows = center == Center::Node ? mesh_->points.size() : mesh_->tets.size();
  if (flat.size() != rows * static_cast<std::size_t>(components)) {
    throw Error(xdmf_path_.string() + ": field '" + name + "' has " +
                std::to_string(flat.size() / static_cast<std::size_t>(components)) +
                " entries, the mesh needs " + std::to_string(rows));
  }
  H5File::Dims dims = {rows};
  if (components != 1) dims.push_back(static_cast<std::size_t>(components));
  h5_.write(s.group + "/" + name, flat, dims);
  s.fields.push_back(FieldRef{name, center, components});
}

void XdmfTimeSeries::add_point_scalar(const std::string& name, const std::vector<double>& values) {
  add_field(name, Center::Node, 1, values);
}

void XdmfTimeSeries::add_point_vector(const std::string& name, const std::vector<Vec3>& values) {
  std::vector<double> flat(3 * values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (int c = 0; c < 3; ++c) flat[3 * i + c] = values[i][c];
  }
  add_field(name, Center::Node, 3, flat);
}

void XdmfTimeSeries::add_cell_scalar(const std::string& name, const std::vector<double>& values) {
  add_field(name, Center::Cell, 1, values);
}

void XdmfTimeSeries::add_cell_tensor(const std::string& name, const std::vector<Eigen::Matrix3d>& values) {
  std::vector<double> flat(9 * values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) flat[9 * i + 3 * r + c] = values[i](r, c);
    }
  }
  add_field(name, Center::Cell, 9, flat);
}

std::string XdmfTimeSeries::xml() const {
  const std::string h5 = h5_path_.filename().string();
  const std::size_t np = mesh_->points.size();
  const std::size_t nc = mesh_->tets.size();
  std::string out;
  out += "<?xml version=\"1.0\" ?>\n";
  out += "<Xdmf Version=\"3.0\">\n";
  out += "  <Domain>\n";
  out += "    <Grid Name=\"TimeSeries\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const Step& s : steps_) {
    const std::string in = "        ";
    out += "      <Grid Name=\"" + s.group.substr(s.group.rfind('/') + 1) + "\" GridType=\"Uniform\">\n";
    out += in + "<Time Value=\"" + format_double(s.time) + "\"/>\n";
    out += in + "<Topology TopologyType=\"Tetrahedron\" NumberOfElements=\"" + std::to_string(nc) + "\">\n";
    out += data_item(h5, "/mesh/topology", nc, 4, true, in + "  ");
    out += in + "</Topology>\n";
    out += in + "<Geometry GeometryType=\"XYZ\">\n";
    out += data_item(h5, s.deformed ? s.group + "/geometry" : "/mesh/geometry", np, 3, false, in + "  ");
    out += in + "</Geometry>\n";
    if (has_physical_) {
      out += in + "<Attribute Name=\"physical\" AttributeType=\"Scalar\" Center=\"Cell\">\n";
      out += data_item(h5, "/mesh/physical", nc, 1, true, in + "  ");
      out += in + "</Attribute>\n";
    }
    for (const FieldRef& f : s.fields) {
      const char* type = f.components == 1 ? "Scalar" : (f.components == 3 ? "Vector" : "Tensor");
      const bool node = f.center == Center::Node;
      out += in + "<Attribute Name=\"" + xml_escape(f.name) + "\" AttributeType=\"" + type + "\" Center=\"" +
             (node ? "Node" : "Cell") + "\">\n";
      out += data_item(h5, s.group + "/" + f.name, node ? np : nc, f.components, false, in + "  ");
      out += in + "</Attribute>\n";
    }
    out += "      </Grid>\n";
  }
  out += "    </Grid>\n";
  out += "  </Domain>\n";
  out += "</Xdmf>\n";
  return out;
}

void XdmfTimeSeries::flush() {
  if (closed_) return;
  h5_.flush();
  write_file_atomically(xdmf_path_, xml());
}

void XdmfTimeSeries::close() {
  if (closed_) return;
  closed_ = true;
  // Close the data first: the XML then never points at data that is not on disk.
  h5_.close();
  write_file_atomically(xdmf_path_, xml());
}

}  // namespace tmlab
