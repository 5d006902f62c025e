// Tests of mesh operations, boundary extraction, group lookup and NodeSelector.
#include "core/base/error.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <filesystem>
#include <string>

namespace tmlab {
namespace {

using nlohmann::json;

Vec3 normal(const Mesh& m, const Tri& f) {
  const Vec3& a = m.points[static_cast<std::size_t>(f[0])];
  return (m.points[static_cast<std::size_t>(f[1])] - a).cross(m.points[static_cast<std::size_t>(f[2])] - a);
}

Vec3 centroid(const Mesh& m, const Tri& f) {
  Vec3 c = Vec3::Zero();
  for (const Index n : f) c += m.points[static_cast<std::size_t>(n)];
  return c / 3.0;
}

/// Divergence theorem with F = x / 3: volume = sum over outward faces of (c . n) / 6 with n = 2 * area * unit
/// normal.
double enclosed_volume(const Mesh& m, const std::vector<Tri>& faces) {
  double v = 0.0;
  for (const Tri& f : faces) v += centroid(m, f).dot(normal(m, f)) / 6.0;
  return v;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(MeshOps, BoundaryFacesOfSingleTetPointOutward) {
  for (const bool inverted : {false, true}) {
    Mesh m;
    m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    m.tets = {inverted ? Tet{0, 2, 1, 3} : Tet{0, 1, 2, 3}};
    m.tet_physical = {0};
    const std::vector<Tri> faces = boundary_faces(m);
    ASSERT_EQ(faces.size(), 4u);
    const Vec3 c(0.25, 0.25, 0.25);
    for (const Tri& f : faces) EXPECT_GT(normal(m, f).dot(centroid(m, f) - c), 0.0);
    EXPECT_NEAR(enclosed_volume(m, faces), 1.0 / 6.0, 1e-15);
  }
}

TEST(MeshOps, BoxBoundaryIsClosedAndOutward) {
  const Mesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 2, 3), 2, 3, 4);
  const std::vector<Tri> faces = boundary_faces(m);
  EXPECT_EQ(faces.size(), 2u * 2u * (2 * 3 + 3 * 4 + 2 * 4));
  EXPECT_NEAR(enclosed_volume(m, faces), 6.0, 1e-12);
  Vec3 sum = Vec3::Zero();
  for (const Tri& f : faces) sum += normal(m, f);
  EXPECT_LT(sum.norm(), 1e-12);
  EXPECT_EQ(boundary_nodes(m).size(), static_cast<std::size_t>(3 * 4 * 5 - 1 * 2 * 3));
}

TEST(MeshOps, ScaleAndTranslate) {
  Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 2, 2, 2);
  scale_mesh(m, 0.5);
  EXPECT_NEAR(analyse_mesh(m).total_volume, 0.125, 1e-15);
  translate_mesh(m, Vec3(1, 2, 3));
  const MeshReport r = analyse_mesh(m);
  EXPECT_TRUE(r.bbox_min.isApprox(Vec3(1, 2, 3)));
  EXPECT_TRUE(r.bbox_max.isApprox(Vec3(1.5, 2.5, 3.5)));
  EXPECT_THROW(scale_mesh(m, 0.0), Error);
  EXPECT_THROW(scale_mesh(m, -2.0), Error);
  EXPECT_THROW(scale_mesh(m, std::nan("")), Error);
  EXPECT_THROW(translate_mesh(m, Vec3(0, std::numeric_limits<double>::infinity(), 0)), Error);
}

TEST(MeshOps, NodesOfGroupByTagAndName) {
  const int n = 3;
  const Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), n, n, n);
  const std::vector<Index> xmin = nodes_of_group(m, 2, kBoxXmin);
  EXPECT_EQ(xmin.size(), static_cast<std::size_t>((n + 1) * (n + 1)));
  for (const Index i : xmin) EXPECT_EQ(m.points[static_cast<std::size_t>(i)].x(), 0.0);
  EXPECT_EQ(nodes_of_group(m, "xmin"), xmin);
  EXPECT_EQ(nodes_of_group(m, "body").size(), static_cast<std::size_t>(m.num_points()));
  const std::string e1 = error_of([&] { nodes_of_group(m, "top"); });
  EXPECT_NE(e1.find("no group \"top\""), std::string::npos) << e1;
  EXPECT_NE(e1.find("\"zmax\""), std::string::npos) << e1;  // lists the available groups
  EXPECT_THROW(nodes_of_group(m, 3, kBoxXmin), Error);      // tag 1 is a surface, not a volume
}

TEST(NodeSelector, ParsesEveryKind) {
  NodeSelector s = NodeSelector::from_json(json::parse(R"({"group": "top"})"));
  EXPECT_EQ(s.kind, NodeSelector::Kind::Group);
  EXPECT_EQ(s.group_name, "top");
  s = NodeSelector::from_json(json::parse(R"({"group": 3, "dim": 2})"));
  EXPECT_EQ(s.group_tag, 3);
  EXPECT_EQ(s.group_dim, 2);
  s = NodeSelector::from_json(json::parse(R"({"box": {"min": [0, 0, 0], "max": [1, 2, 3]}})"));
  EXPECT_EQ(s.kind, NodeSelector::Kind::Box);
  EXPECT_EQ(s.box_max, Vec3(1, 2, 3));
  s = NodeSelector::from_json(json::parse(R"({"plane": {"axis": "y", "value": 0.5}})"));
  EXPECT_EQ(s.kind, NodeSelector::Kind::Plane);
  EXPECT_EQ(s.axis, 1);
  EXPECT_EQ(s.value, 0.5);
  EXPECT_EQ(s.tol, 1e-9);
  s = NodeSelector::from_json(json::parse(R"({"sphere": {"center": [0, 0, 1], "radius": 0.25}})"));
  EXPECT_EQ(s.kind, NodeSelector::Kind::Sphere);
  EXPECT_EQ(s.radius, 0.25);
  s = NodeSelector::from_json(json::parse(R"({"nodes": [4, 1, 7]})"));
  EXPECT_EQ(s.kind, NodeSelector::Kind::Nodes);
  EXPECT_EQ(s.nodes, (std::vector<Index>{4, 1, 7}));
}

TEST(NodeSelector, JsonRoundTrip) {
  for (const char* text :
       {R"({"group": "top"})", R"({"group": 3, "dim": 2})",
        R"({"box": {"min": [0.0, 0.0, 0.0], "max": [1.0, 2.0, 3.0]}})",
        R"({"plane": {"axis": "z", "value": 0.0, "tol": 1e-06}})",
        R"({"sphere": {"center": [0.0, 0.0, 1.0], "radius": 0.25}})", R"({"nodes": [4, 1, 7]})"}) {
    const json j = json::parse(text);
    EXPECT_EQ(NodeSelector::from_json(j).to_json(), j) << text;
  }
}

struct BadSelector {
  const char* json_text;
  const char* reason;
};

class NodeSelectorErrors : public testing::TestWithParam<BadSelector> {};

TEST_P(NodeSelectorErrors, RejectedWithClearMessage) {
  const std::string msg = error_of(
      [&] { NodeSelector::from_json(json::parse(GetParam().json_text), "case.json: loads[0].where"); });
  EXPECT_EQ(msg.rfind("case.json: loads[0].where", 0), 0u) << msg;
  EXPECT_NE(msg.find(GetParam().reason), std::string::npos) << msg;
}

INSTANTIATE_TEST_SUITE_P(
    Table, NodeSelectorErrors,
    testing::Values(
        BadSelector{R"({"boxx": {}})", "unknown key \"boxx\""},
        BadSelector{R"({"plane": {"axis": "z", "value": 0, "tolerance": 1}})", "unknown key \"tolerance\""},
        BadSelector{R"({"box": {"min": [0,0,0], "max": [1,1,1]}, "sphere": {}})", "exactly one of"},
        BadSelector{R"({})", "exactly one of"}, BadSelector{R"([1, 2])", "expected a JSON object"},
        BadSelector{R"({"plane": {"axis": "w", "value": 0}})", "plane.axis"},
        BadSelector{R"({"plane": {"axis": "x"}})", "missing key \"value\""},
        BadSelector{R"({"plane": {"axis": "x", "value": 0, "tol": -1}})", "plane.tol"},
        BadSelector{R"({"box": {"min": [0,0], "max": [1,1,1]}})", "box.min"},
        BadSelector{R"({"box": {"min": [2,0,0], "max": [1,1,1]}})", "min exceeds max"},
        BadSelector{R"({"box": {"min": [0,"a",0], "max": [1,1,1]}})", "box.min[1]"},
        BadSelector{R"({"sphere": {"center": [0,0,0], "radius": -1}})", "sphere.radius"},
        BadSelector{R"({"nodes": [1, -2]})", "nodes[1]"}, BadSelector{R"({"nodes": 3})", "expected an array"},
        BadSelector{R"({"group": 0})", "group"}, BadSelector{R"({"group": ""})", "empty group name"},
        BadSelector{R"({"group": "top", "dim": 1})", "dim"},
        BadSelector{R"({"nodes": [1], "dim": 2})", "only allowed with \"group\""}));

TEST(NodeSelector, SelectsNodesOnBoxMesh) {
  const int n = 4;
  const Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), n, n, n);
  const auto sel = [&](const char* text) {
    return select_nodes(m, NodeSelector::from_json(json::parse(text)));
  };
  const std::vector<Index> zmin = sel(R"({"plane": {"axis": "z", "value": 0.0}})");
  EXPECT_EQ(zmin.size(), 25u);
  EXPECT_EQ(zmin, sel(R"({"group": "zmin"})"));
  EXPECT_EQ(zmin, sel(R"({"group": 5})"));
  EXPECT_EQ(zmin, sel(R"({"box": {"min": [-1, -1, -1], "max": [2, 2, 0]}})"));
  EXPECT_EQ(sel(R"({"plane": {"axis": "x", "value": 0.5}})").size(), 25u);
  EXPECT_TRUE(sel(R"({"plane": {"axis": "x", "value": 0.6, "tol": 1e-3}})").empty());
  EXPECT_EQ(sel(R"({"plane": {"axis": "x", "value": 0.6, "tol": 0.1}})").size(), 25u);
  // Sphere of radius 0.3 about the centre: the centre and its 6 axis neighbours at distance 0.25.
  EXPECT_EQ(sel(R"({"sphere": {"center": [0.5, 0.5, 0.5], "radius": 0.3}})").size(), 7u);
  EXPECT_EQ(sel(R"({"box": {"min": [0, 0, 0], "max": [0.25, 0.25, 0.25]}})").size(), 8u);
  EXPECT_EQ(sel(R"({"nodes": [7, 3, 3]})"), (std::vector<Index>{3, 7}));
  const std::string e = error_of([&] { sel(R"({"nodes": [125]})"); });
  EXPECT_NE(e.find("node index 125 out of range"), std::string::npos) << e;
  EXPECT_NE(error_of([&] { sel(R"({"group": "nope"})"); }).find("no group \"nope\""), std::string::npos);
}

TEST(NodeSelector, AmbiguousTagNeedsDim) {
  Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 1, 1, 1);
  for (int& p : m.tet_physical) p = kBoxXmin;  // tag 1 now names a surface and a volume
  m.groups.push_back({3, kBoxXmin, ""});
  const std::string e =
      error_of([&] { select_nodes(m, NodeSelector::from_json(json::parse(R"({"group": 1})"))); });
  EXPECT_NE(e.find("add \"dim\""), std::string::npos) << e;
  EXPECT_EQ(select_nodes(m, NodeSelector::from_json(json::parse(R"({"group": 1, "dim": 2})"))).size(), 4u);
  EXPECT_EQ(select_nodes(m, NodeSelector::from_json(json::parse(R"({"group": 1, "dim": 3})"))).size(), 8u);
}

TEST(NodeSelector, SelectsOutwardFaces) {
  const int n = 3;
  const Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), n, n, n);
  const auto faces = [&](const char* text) {
    return select_faces(m, NodeSelector::from_json(json::parse(text)));
  };
  const std::vector<Tri> top = faces(R"({"group": "zmax"})");
  ASSERT_EQ(top.size(), static_cast<std::size_t>(2 * n * n));
  for (const Tri& f : top) {
    const Vec3 nrm = normal(m, f);
    EXPECT_GT(nrm.z(), 0.0);
    EXPECT_NEAR(nrm.head<2>().norm(), 0.0, 1e-15);
  }
  const std::vector<Tri> top_plane = faces(R"({"plane": {"axis": "z", "value": 1.0}})");
  EXPECT_EQ(top_plane.size(), top.size());
  for (const Tri& f : top_plane) EXPECT_GT(normal(m, f).z(), 0.0);
  const std::vector<Tri> xmin = faces(R"({"box": {"min": [-1, -1, -1], "max": [0, 1, 1]}})");
  ASSERT_EQ(xmin.size(), static_cast<std::size_t>(2 * n * n));
  for (const Tri& f : xmin) EXPECT_LT(normal(m, f).x(), 0.0);
  EXPECT_TRUE(faces(R"({"sphere": {"center": [0.5, 0.5, 0.5], "radius": 0.4}})").empty());
  // A volume group gives the whole closed boundary.
  EXPECT_EQ(faces(R"({"group": "body"})").size(), boundary_faces(m).size());
}

TEST(NodeSelector, FileTrianglesOfBlockIndentationAreOrientedOutward) {
  const std::string path = std::string(TMLAB_SOURCE_DIR) + "/meshes/block_indentation.msh";
  ASSERT_TRUE(std::filesystem::exists(path)) << "missing " << path;
  const Mesh m = read_gmsh(path);
  const std::vector<Tri> top = select_faces(m, NodeSelector::from_json(json::parse(R"({"group": "top"})")));
  const std::vector<Tri> bottom = select_faces(m, NodeSelector::from_json(json::parse(R"({"group": 2})")));
  EXPECT_EQ(top.size() + bottom.size(), m.triangles.size());
  double top_area = 0.0;
  for (const Tri& f : top) {
    EXPECT_GT(normal(m, f).z(), 0.0);
    top_area += 0.5 * normal(m, f).norm();
  }
  for (const Tri& f : bottom) EXPECT_LT(normal(m, f).z(), 0.0);
  EXPECT_NEAR(top_area, 0.04 * 0.04, 1e-12);
  const std::vector<Index> top_nodes = nodes_of_group(m, "top");
  EXPECT_EQ(top_nodes, select_nodes(m, NodeSelector::from_json(json::parse(
                                           R"({"plane": {"axis": "z", "value": 0.02, "tol": 1e-9}})"))));
}

}  // namespace
}  // namespace tmlab
