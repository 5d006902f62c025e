// VtuWriter / PvdWriter: well-formed XML, right counts, base64 blocks that decode to the data.
#include "core/base/error.hpp"
#include "core/io/vtu_writer.hpp"

#include "core/io/tests/xml_mini.hpp"
#include "core/testing/small_meshes.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <sstream>

namespace fs = std::filesystem;
using tmlab::test::base64_decode;
using tmlab::test::parse_xml;
using tmlab::test::XmlNode;
using tmlab::testing::read_file;
using tmlab::testing::two_tets;

namespace {

/// Decodes a binary DataArray: checks the UInt64 byte-count header and returns the payload as T.
template <typename T>
std::vector<T> decode_array(const XmlNode& da) {
  EXPECT_EQ(da.attr("format"), "binary");
  const auto bytes = base64_decode(da.text);
  std::uint64_t n = 0;
  EXPECT_GE(bytes.size(), sizeof(n));
  std::memcpy(&n, bytes.data(), sizeof(n));
  EXPECT_EQ(n, bytes.size() - sizeof(n));
  std::vector<T> out(n / sizeof(T));
  if (n > 0) std::memcpy(out.data(), bytes.data() + sizeof(n), n);
  return out;
}

std::vector<double> parse_ascii(const XmlNode& da) {
  EXPECT_EQ(da.attr("format"), "ascii");
  std::istringstream in(da.text);
  std::vector<double> v;
  double x;
  while (in >> x) v.push_back(x);
  return v;
}

const XmlNode* array_named(const XmlNode& root, const std::string& name) {
  for (const XmlNode* da : root.all("DataArray")) {
    if (da->attrs.count("Name") && da->attr("Name") == name) return da;
  }
  ADD_FAILURE() << "no DataArray " << name;
  return nullptr;
}

class VtuWriterTest : public tmlab::testing::TempDirTest {};

TEST_F(VtuWriterTest, Base64FileHasCountsAndDecodesToData) {
  const tmlab::Mesh mesh = two_tets();
  tmlab::VtuWriter w(mesh);
  const std::vector<tmlab::Vec3> u = {{0.1, 0, 0}, {0, 0.2, 0}, {0, 0, 0.3}, {0, 0, 0}, {-1, -1, -1}};
  w.set_displacement(u);
  w.add_point_scalar("pressure", {1, 2, 3, 4, 5});
  w.add_point_vector("u", u);
  w.add_cell_scalar("J", {0.9, 1.1});
  Eigen::Matrix3d s0;
  s0 << 1, 2, 3, 4, 5, 6, 7, 8, 9;
  w.add_cell_tensor("stress <Pa>", {s0, -s0});
  const fs::path file = dir_ / "step.vtu";
  w.write(file);
  EXPECT_FALSE(fs::exists(dir_ / "step.vtu.tmp"));

  const auto root = parse_xml(read_file(file));
  ASSERT_EQ(root->tag, "VTKFile");
  EXPECT_EQ(root->attr("type"), "UnstructuredGrid");
  EXPECT_EQ(root->attr("header_type"), "UInt64");
  const auto pieces = root->all("Piece");
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0]->attr("NumberOfPoints"), "5");
  EXPECT_EQ(pieces[0]->attr("NumberOfCells"), "2");
  EXPECT_EQ(root->all("DataArray").size(), 2u + 2u + 1u + 3u);  // point, cell, Points, Cells

  const auto points = decode_array<double>(*array_named(*root, "Points"));
  ASSERT_EQ(points.size(), 15u);
  EXPECT_DOUBLE_EQ(points[0], 0.1);          // point 0 displaced in x
  EXPECT_DOUBLE_EQ(points[3 * 2 + 2], 0.3);  // point 2 displaced in z
  EXPECT_DOUBLE_EQ(points[3 * 4 + 1], 0.0);  // point 4: (1,1,1) + (-1,-1,-1)
  EXPECT_EQ(decode_array<std::int64_t>(*array_named(*root, "connectivity")),
            (std::vector<std::int64_t>{0, 1, 2, 3, 1, 2, 3, 4}));
  EXPECT_EQ(decode_array<std::int64_t>(*array_named(*root, "offsets")), (std::vector<std::int64_t>{4, 8}));
  EXPECT_EQ(decode_array<std::uint8_t>(*array_named(*root, "types")), (std::vector<std::uint8_t>{10, 10}));
  EXPECT_EQ(decode_array<double>(*array_named(*root, "pressure")), (std::vector<double>{1, 2, 3, 4, 5}));
  EXPECT_EQ(array_named(*root, "u")->attr("NumberOfComponents"), "3");
  const XmlNode* stress = array_named(*root, "stress <Pa>");
  EXPECT_EQ(stress->attr("NumberOfComponents"), "9");
  const auto sv = decode_array<double>(*stress);
  ASSERT_EQ(sv.size(), 18u);
  EXPECT_EQ(sv[1], 2.0);  // row-major: xy
  EXPECT_EQ(sv[3], 4.0);  // yx
  EXPECT_EQ(sv[17], -9.0);
  const auto cell_data = root->all("CellData");
  ASSERT_EQ(cell_data.size(), 1u);
  EXPECT_EQ(cell_data[0]->attr("Tensors"), "stress <Pa>");
}

TEST_F(VtuWriterTest, AsciiAtRestConfiguration) {
  const tmlab::Mesh mesh = two_tets();
  tmlab::VtuWriter w(mesh);
  w.add_cell_scalar("J", {0.1, 1.0 / 3.0});
  const auto root = parse_xml(w.to_string(tmlab::VtuEncoding::Ascii));
  const auto points = parse_ascii(*array_named(*root, "Points"));
  ASSERT_EQ(points.size(), 15u);
  EXPECT_EQ(points[12], 1.0);
  EXPECT_EQ(parse_ascii(*array_named(*root, "connectivity")), (std::vector<double>{0, 1, 2, 3, 1, 2, 3, 4}));
  EXPECT_EQ(parse_ascii(*array_named(*root, "J")),
            (std::vector<double>{0.1, 1.0 / 3.0}));  // exact round trip
  EXPECT_TRUE(root->all("PointData").empty());
}

TEST_F(VtuWriterTest, RejectsWrongSizesAndDuplicates) {
  const tmlab::Mesh mesh = two_tets();
  tmlab::VtuWriter w(mesh);
  EXPECT_THROW(w.add_point_scalar("p", {1, 2}), tmlab::Error);
  EXPECT_THROW(w.add_cell_scalar("J", {1, 2, 3}), tmlab::Error);
  EXPECT_THROW(w.set_positions({{0, 0, 0}}), tmlab::Error);
  w.add_cell_scalar("J", {1, 2});
  EXPECT_THROW(w.add_cell_scalar("J", {1, 2}), tmlab::Error);
  EXPECT_THROW(w.add_cell_scalar("", {1, 2}), tmlab::Error);
  EXPECT_THROW(w.write(dir_ / "no" / "such" / "dir" / "x.vtu"), tmlab::Error);
}

TEST_F(VtuWriterTest, EmptyMeshIsStillValid) {
  const tmlab::Mesh mesh;
  const auto root = parse_xml(tmlab::VtuWriter(mesh).to_string());
  EXPECT_EQ(root->all("Piece")[0]->attr("NumberOfCells"), "0");
  EXPECT_TRUE(decode_array<double>(*array_named(*root, "Points")).empty());
}

TEST_F(VtuWriterTest, PvdListsStepsWithRelativeNames) {
  tmlab::PvdWriter pvd(dir_ / "series.pvd");
  pvd.add(0.0, "step_000000.vtu");
  pvd.add(0.5, dir_ / "steps" / "step_000001.vtu");
  pvd.write();
  EXPECT_EQ(pvd.size(), 2u);
  const auto root = parse_xml(read_file(dir_ / "series.pvd"));
  EXPECT_EQ(root->attr("type"), "Collection");
  const auto sets = root->all("DataSet");
  ASSERT_EQ(sets.size(), 2u);
  EXPECT_EQ(sets[0]->attr("file"), "step_000000.vtu");
  EXPECT_EQ(sets[1]->attr("file"), "steps/step_000001.vtu");
  EXPECT_EQ(std::stod(sets[1]->attr("timestep")), 0.5);
}

}  // namespace
