// XdmfTimeSeries: the XML is well formed and every HDF DataItem names an existing dataset of the
// stated dimensions and type; the fields read back equal what was written.
#include "core/base/error.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/io/xdmf_writer.hpp"

#include "core/io/tests/xml_mini.hpp"
#include "core/testing/small_meshes.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace fs = std::filesystem;
using tmlab::H5File;
using tmlab::test::parse_xml;
using tmlab::test::XmlNode;
using tmlab::testing::read_file;
using tmlab::testing::two_tets;

namespace {

class XdmfWriterTest : public tmlab::testing::TempDirTest {};

/// Every HDF DataItem: "file.h5:/path" exists beside the .xdmf, with the stated shape and type.
void check_references(const fs::path& xdmf, const XmlNode& root) {
  const auto items = root.all("DataItem");
  ASSERT_FALSE(items.empty());
  for (const XmlNode* it : items) {
    ASSERT_EQ(it->attr("Format"), "HDF");
    std::string ref = it->text;
    ref.erase(0, ref.find_first_not_of(" \n"));
    ref.erase(ref.find_last_not_of(" \n") + 1);
    const auto colon = ref.find(':');
    ASSERT_NE(colon, std::string::npos) << ref;
    const fs::path h5 = xdmf.parent_path() / ref.substr(0, colon);
    const std::string dataset = ref.substr(colon + 1);
    ASSERT_TRUE(fs::exists(h5)) << h5;
    const H5File f = H5File::open_read(h5.string());
    ASSERT_TRUE(f.exists(dataset)) << dataset;
    std::string dims;
    for (std::size_t d : f.dims(dataset)) dims += (dims.empty() ? "" : " ") + std::to_string(d);
    EXPECT_EQ(it->attr("Dimensions"), dims) << dataset;
    const bool is_int = it->attr("NumberType") == "Int";
    EXPECT_EQ(f.type(dataset), is_int ? tmlab::H5Type::Int32 : tmlab::H5Type::Float64) << dataset;
    EXPECT_EQ(it->attr("Precision"), is_int ? "4" : "8");
  }
}

TEST_F(XdmfWriterTest, TwoStepsReferenceExistingDatasets) {
  const tmlab::Mesh mesh = two_tets();
  const fs::path xdmf = dir_ / "series.xdmf";
  {
    tmlab::XdmfTimeSeries ts(xdmf, mesh);
    EXPECT_TRUE(fs::exists(dir_ / "series.h5"));  // the HDF5 file beside the .xdmf, same stem
    for (int k = 0; k < 2; ++k) {
      ts.begin_step(0.25 * k);
      std::vector<tmlab::Vec3> u(mesh.points.size(), tmlab::Vec3(0.0, 0.0, 0.1 * k));
      if (k == 1) {
        std::vector<tmlab::Vec3> x = mesh.points;
        for (std::size_t i = 0; i < x.size(); ++i) x[i] += u[i];
        ts.set_positions(x);
      }
      ts.add_point_vector("u", u);
      ts.add_point_scalar("p", {1, 2, 3, 4, double(k)});
      ts.add_cell_scalar("J", {1.0, 1.0 + k});
      ts.add_cell_tensor("sigma", {Eigen::Matrix3d::Identity() * k, Eigen::Matrix3d::Ones()});
      ts.flush();  // the XML on disk is valid after every step
      EXPECT_EQ(parse_xml(read_file(xdmf))->all("Time").size(), std::size_t(k + 1));
    }
    ts.close();
    EXPECT_EQ(parse_xml(read_file(xdmf))->all("Time").size(), 2u);
  }
  EXPECT_FALSE(fs::exists(dir_ / "series.xdmf.tmp"));
  const auto root = parse_xml(read_file(xdmf));
  ASSERT_EQ(root->tag, "Xdmf");
  EXPECT_EQ(root->attr("Version"), "3.0");
  const auto grids = root->all("Grid");
  ASSERT_EQ(grids.size(), 3u);  // the temporal collection and one uniform grid per step
  EXPECT_EQ(grids[0]->attr("CollectionType"), "Temporal");
  const auto times = root->all("Time");
  ASSERT_EQ(times.size(), 2u);
  EXPECT_EQ(std::stod(times[1]->attr("Value")), 0.25);
  EXPECT_EQ(root->all("Topology")[0]->attr("NumberOfElements"), "2");
  EXPECT_EQ(root->all("Attribute").size(), 2u * 5u);  // physical + 4 fields per step
  check_references(xdmf, *root);

  const H5File f = H5File::open_read((dir_ / "series.h5").string());
  EXPECT_EQ(f.read_double("/time"), (std::vector<double>{0.0, 0.25}));
  EXPECT_EQ(f.read_int32("/mesh/topology"), (std::vector<std::int32_t>{0, 1, 2, 3, 1, 2, 3, 4}));
  const auto geo1 = f.read_double("/steps/000001/geometry");
  EXPECT_DOUBLE_EQ(geo1[3 * 4 + 2], 1.1);
  const auto sigma = f.read_double("/steps/000001/sigma");
  ASSERT_EQ(sigma.size(), 18u);
  EXPECT_EQ(sigma[0], 1.0);
  EXPECT_EQ(sigma[1], 0.0);
  EXPECT_FALSE(f.exists("/steps/000000/geometry"));
  // Step 0 uses the rest geometry.
  bool step0_rest = false;
  for (const XmlNode* g : root->all("Geometry")) {
    if (g->children[0]->text.find("/mesh/geometry") != std::string::npos) step0_rest = true;
  }
  EXPECT_TRUE(step0_rest);
}

TEST_F(XdmfWriterTest, DestructorLeavesViewableSeriesOfStepsBegun) {
  const tmlab::Mesh mesh = two_tets();
  const fs::path xdmf = dir_ / "aborted.xdmf";
  try {
    tmlab::XdmfTimeSeries ts(xdmf, mesh);
    ts.begin_step(0.0);
    ts.add_cell_scalar("J", {1, 1});
    throw std::runtime_error("solver diverged");
  } catch (const std::runtime_error&) {
  }
  const auto root = parse_xml(read_file(xdmf));
  EXPECT_EQ(root->all("Time").size(), 1u);
  check_references(xdmf, *root);
}

TEST_F(XdmfWriterTest, RejectsMisuse) {
  const tmlab::Mesh mesh = two_tets();
  tmlab::XdmfTimeSeries ts(dir_ / "m.xdmf", mesh);
  EXPECT_THROW(ts.add_cell_scalar("J", {1, 1}), tmlab::Error);  // before begin_step
  ts.begin_step(0.0);
  EXPECT_THROW(ts.add_cell_scalar("J", {1, 1, 1}), tmlab::Error);
  EXPECT_THROW(ts.add_cell_scalar("a/b", {1, 1}), tmlab::Error);
  EXPECT_THROW(ts.set_positions({{0, 0, 0}}), tmlab::Error);
  ts.add_cell_scalar("J", {1, 1});
  EXPECT_THROW(ts.add_cell_scalar("J", {1, 1}), tmlab::Error);
  ts.close();
  EXPECT_THROW(ts.begin_step(1.0), tmlab::Error);
  EXPECT_THROW(tmlab::XdmfTimeSeries(dir_ / "no" / "dir" / "x.xdmf", mesh), tmlab::Error);
}

}  // namespace
