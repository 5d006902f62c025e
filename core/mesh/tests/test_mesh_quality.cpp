// Tests of tet volume/quality and analyse_mesh().
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

namespace tmlab {
namespace {

Mesh single_tet(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Mesh m;
  m.points = {a, b, c, d};
  m.point_file_ids = {1, 2, 3, 4};
  m.tets = {Tet{0, 1, 2, 3}};
  m.tet_physical = {0};
  return m;
}

TEST(MeshQuality, RegularTetHasQualityOne) {
  const Vec3 a(1, 1, 1), b(1, -1, -1), c(-1, 1, -1), d(-1, -1, 1);
  const double q = tet_quality(a, b, c, d);
  EXPECT_NEAR(std::abs(q), 1.0, 1e-14);
  EXPECT_NEAR(tet_quality(a, b, d, c), -q, 1e-14);  // swapping two nodes inverts
  EXPECT_NEAR(std::abs(tet_signed_volume(a, b, c, d)), 8.0 / 3.0, 1e-14);
  EXPECT_NEAR(tet_rms_edge(a, b, c, d), std::sqrt(8.0), 1e-14);
}

TEST(MeshQuality, UnitRightTet) {
  const Vec3 o(0, 0, 0), x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  EXPECT_DOUBLE_EQ(tet_signed_volume(o, x, y, z), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(tet_signed_volume(o, y, x, z), -1.0 / 6.0);
  // l_rms^2 = (3*1 + 3*2)/6 = 1.5
  EXPECT_NEAR(tet_quality(o, x, y, z), 6.0 * std::sqrt(2.0) / 6.0 / std::pow(1.5, 1.5), 1e-15);
  EXPECT_EQ(tet_quality(o, o, o, o), 0.0);
}

TEST(MeshQuality, BoxMeshVolumeExactNoInvertedTets) {
  const Mesh mesh = make_box_mesh(Vec3(-1, 0, 2), Vec3(1, 3, 6), 3, 4, 5);
  const MeshReport r = analyse_mesh(mesh);
  EXPECT_EQ(r.num_tets, 6 * 3 * 4 * 5);
  EXPECT_NEAR(r.total_volume, 2.0 * 3.0 * 4.0, 1e-12);
  EXPECT_TRUE(r.inverted.empty());
  EXPECT_TRUE(r.degenerate.empty());
  EXPECT_GT(r.min_volume, 0.0);
  EXPECT_EQ(std::accumulate(r.q_histogram.begin(), r.q_histogram.end(), 0), r.num_tets);
  EXPECT_EQ(r.bbox_min, Vec3(-1, 0, 2));
  EXPECT_EQ(r.bbox_max, Vec3(1, 3, 6));
  EXPECT_EQ(r.num_unused_points, 0);
  EXPECT_EQ(r.num_boundary_faces, 2 * 2 * (3 * 4 + 4 * 5 + 3 * 5));
  EXPECT_GT(r.edge_min, 0.0);
  EXPECT_LE(r.edge_min, r.edge_mean);
  EXPECT_LE(r.edge_mean, r.edge_max);
}

TEST(MeshQuality, CubeCellsGiveCongruentKuhnTets) {
  const MeshReport r = analyse_mesh(make_box_mesh(Vec3::Zero(), Vec3::Ones(), 2, 2, 2));
  // Every Kuhn tet of a cube has edges 1, 1, 1, sqrt2, sqrt2, sqrt3 (times h): l_rms^2 = 5/3,
  // q = 6 sqrt(2) (1/6) / (5/3)^1.5.
  const double q = std::sqrt(2.0) / std::pow(5.0 / 3.0, 1.5);
  EXPECT_NEAR(r.q_min, q, 1e-12);
  EXPECT_NEAR(r.q_max, q, 1e-12);
  // unique edges of a 2x2x2 Kuhn grid: 54 axis-aligned, 36 face diagonals, 8 cell diagonals
  EXPECT_EQ(r.num_edges, 54 + 36 + 8);
}

TEST(MeshQuality, InvertedTetDetectedAndRepaired) {
  Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 2, 2, 2);
  std::swap(mesh.tets[5][0], mesh.tets[5][1]);
  std::swap(mesh.tets[17][2], mesh.tets[17][3]);
  MeshReport r = analyse_mesh(mesh);
  EXPECT_EQ(r.inverted, (std::vector<Index>{5, 17}));
  EXPECT_LT(r.volumes[5], 0.0);
  EXPECT_LT(r.quality[17], 0.0);
  EXPECT_LT(r.total_volume, 1.0);
  EXPECT_EQ(repair_orientation(mesh), 2);
  r = analyse_mesh(mesh);
  EXPECT_TRUE(r.inverted.empty());
  EXPECT_NEAR(r.total_volume, 1.0, 1e-14);
  EXPECT_EQ(repair_orientation(mesh), 0);
}

TEST(MeshQuality, FlatTetIsDegenerate) {
  const Mesh mesh = single_tet(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0));
  const MeshReport r = analyse_mesh(mesh);
  EXPECT_EQ(r.degenerate, (std::vector<Index>{0}));
  EXPECT_NEAR(r.q_min, 0.0, 1e-15);
  EXPECT_EQ(r.q_histogram[0], 1);
}

TEST(MeshQuality, TextAndJsonReports) {
  Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3(2, 1, 1), 2, 1, 1);
  std::swap(mesh.tets[3][0], mesh.tets[3][1]);
  const MeshReport r = analyse_mesh(mesh);
  const std::string text = format_mesh_report(r);
  EXPECT_NE(text.find("tets 12"), std::string::npos) << text;
  EXPECT_NE(text.find("inverted tets (V < 0): 1: tmlab index 3"), std::string::npos) << text;
  EXPECT_NE(text.find("\"xmin\""), std::string::npos) << text;
  const nlohmann::json j = mesh_report_json(r);
  EXPECT_EQ(j.at("num_tets").get<int>(), 12);
  EXPECT_EQ(j.at("inverted"), nlohmann::json::array({3}));
  EXPECT_EQ(j.at("quality").at("histogram").size(), 10u);
  EXPECT_DOUBLE_EQ(j.at("bbox").at("extent")[0].get<double>(), 2.0);
  EXPECT_EQ(j.at("groups").size(), 7u);
  EXPECT_TRUE(j.at("inverted_file_ids").empty());  // a generated mesh has no file ids

  // From a file, the file's element ids are named too.
  mesh.tet_file_ids.resize(mesh.tets.size());
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) mesh.tet_file_ids[t] = 100 + long(t);
  const MeshReport rf = analyse_mesh(mesh);
  EXPECT_NE(format_mesh_report(rf).find("inverted tets (V < 0): 1: tmlab index 3; Gmsh element 103"),
            std::string::npos)
      << format_mesh_report(rf);
  EXPECT_EQ(mesh_report_json(rf).at("inverted_file_ids"), nlohmann::json::array({103}));
  EXPECT_EQ(mesh.tet_name(3), "tetrahedron 3 (Gmsh element 103)");
}

TEST(MeshQuality, EmptyMesh) {
  const MeshReport r = analyse_mesh(Mesh{});
  EXPECT_EQ(r.num_tets, 0);
  EXPECT_EQ(r.q_min_tet, -1);
  EXPECT_EQ(r.total_volume, 0.0);
  EXPECT_FALSE(format_mesh_report(r).empty());
}

}  // namespace
}  // namespace tmlab
