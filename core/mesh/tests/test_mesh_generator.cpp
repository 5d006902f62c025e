// Tests of make_box_mesh() and write_gmsh22().
#include "core/base/error.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"
#include "core/mesh/quadratic_mesh.hpp"
#include "core/testing/small_meshes.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace tmlab {
namespace {

TEST(BoxMesh, CountsAndNumbering) {
  const int nx = 2, ny = 3, nz = 4;
  const Mesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(2, 3, 4), nx, ny, nz);
  EXPECT_EQ(m.num_points(), 3 * 4 * 5);
  EXPECT_EQ(m.num_tets(), 6 * nx * ny * nz);
  EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(4 * (nx * ny + ny * nz + nx * nz)));
  EXPECT_EQ(m.point_file_ids.size(), m.points.size());
  EXPECT_TRUE(m.source.empty());
  // x fastest: index = i + (nx+1) * (j + (ny+1) * k)
  EXPECT_EQ(m.points[1], Vec3(1, 0, 0));
  EXPECT_EQ(m.points[3], Vec3(0, 1, 0));
  EXPECT_EQ(m.points[12], Vec3(0, 0, 1));
  EXPECT_EQ(m.points.back(), Vec3(2, 3, 4));
}

TEST(BoxMesh, AllTetsPositiveAndConforming) {
  const Mesh m = make_box_mesh(Vec3(-1, -1, -1), Vec3(1, 1, 1), 3, 3, 3);
  for (Index t = 0; t < m.num_tets(); ++t) EXPECT_GT(tet_signed_volume(m, t), 0.0) << t;
  // Each face is shared by at most two tets; boundary faces exactly cover the six box faces.
  const std::map<Tri, int> uses = testing::face_uses(m);
  int boundary = 0;
  for (const auto& entry : uses) {
    EXPECT_LE(entry.second, 2);
    boundary += entry.second == 1 ? 1 : 0;
  }
  EXPECT_EQ(boundary, 6 * 2 * 3 * 3);
  EXPECT_NEAR(analyse_mesh(m).total_volume, 8.0, 1e-13);
}

TEST(BoxMesh, FaceGroupsNamedAndOutward) {
  const int n = 2;
  const Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), n, n, n);
  const char* names[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  ASSERT_EQ(m.groups.size(), 7u);
  for (int tag = 1; tag <= 6; ++tag) {
    EXPECT_EQ(m.groups[static_cast<std::size_t>(tag - 1)].dim, 2);
    EXPECT_EQ(m.groups[static_cast<std::size_t>(tag - 1)].tag, tag);
    EXPECT_EQ(m.groups[static_cast<std::size_t>(tag - 1)].name, names[tag - 1]);
    const int axis = (tag - 1) / 2;
    const double sign = (tag - 1) % 2 == 0 ? -1.0 : 1.0;
    int count = 0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      if (m.triangle_physical[t] != tag) continue;
      ++count;
      const Tri& f = m.triangles[t];
      const Vec3& a = m.points[static_cast<std::size_t>(f[0])];
      const Vec3 nrm =
          (m.points[static_cast<std::size_t>(f[1])] - a).cross(m.points[static_cast<std::size_t>(f[2])] - a);
      EXPECT_GT(sign * nrm[axis], 0.0);
      for (const Index v : f) EXPECT_EQ(m.points[static_cast<std::size_t>(v)][axis], sign < 0 ? 0.0 : 1.0);
    }
    EXPECT_EQ(count, 2 * n * n);
  }
  EXPECT_EQ(m.groups[6].dim, 3);
  EXPECT_EQ(m.groups[6].tag, kBoxBody);
  EXPECT_EQ(m.groups[6].name, "body");
  EXPECT_TRUE(std::all_of(m.tet_physical.begin(), m.tet_physical.end(), [](int p) { return p == kBoxBody; }));
}

TEST(BoxMesh, DeterministicAndExactCorners) {
  const Vec3 lo(0.1, -0.3, 0.7), hi(0.4, 0.2, 0.9);
  const Mesh a = make_box_mesh(lo, hi, 3, 5, 7);
  const Mesh b = make_box_mesh(lo, hi, 3, 5, 7);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.triangles, b.triangles);
  const MeshReport r = analyse_mesh(a);
  EXPECT_EQ(r.bbox_min, lo);
  EXPECT_EQ(r.bbox_max, hi);
}

TEST(BoxMesh, RejectsBadArguments) {
  EXPECT_THROW(make_box_mesh(Vec3::Zero(), Vec3::Ones(), 0, 1, 1), Error);
  EXPECT_THROW(make_box_mesh(Vec3::Zero(), Vec3::Ones(), 1, -1, 1), Error);
  EXPECT_THROW(make_box_mesh(Vec3::Zero(), Vec3(1, 0, 1), 1, 1, 1), Error);
  EXPECT_THROW(make_box_mesh(Vec3::Ones(), Vec3::Zero(), 1, 1, 1), Error);
}

TEST(WriteGmsh22, RoundTripOfBoxMesh) {
  const Mesh a = make_box_mesh(Vec3(0.1, 0.2, 0.3), Vec3(1.1, 1.7, 0.9), 3, 2, 5);
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "tmlab_mesh_generator";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "box.msh").string();
  write_gmsh22(a, path);
  GmshReadInfo info;
  const Mesh b = read_gmsh(path, &info);
  EXPECT_EQ(info.format_version, "2.2");
  EXPECT_EQ(a.points, b.points);  // exact
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.tet_physical, b.tet_physical);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.triangle_physical, b.triangle_physical);
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (std::size_t g = 0; g < a.groups.size(); ++g) EXPECT_EQ(a.groups[g].name, b.groups[g].name);
  EXPECT_THROW(write_gmsh22(a, (dir / "no_such_dir" / "x.msh").string()), Error);
}

TEST(RepoMeshes, CommittedMeshesReadAndAreSane) {
  const std::string dir = std::string(TMLAB_SOURCE_DIR) + "/meshes/";
  struct Case {
    const char* file;
    Index nodes;
    Index tets;
    double max_extent;  // metres
  };
  const Case cases[] = {{"liver.msh", 740, 2704, 0.22},
                        {"liver_sofa_596t.msh", 181, 596, 0.22},
                        {"block_indentation.msh", 759, 3120, 0.04},
                        {"cylinder_sample.msh", 1142, 4789, 0.05},
                        {"cube_n2.msh", 27, 48, 1.0},
                        {"cube_n4.msh", 125, 384, 1.0},
                        {"cube_n8.msh", 729, 3072, 1.0}};
  for (const Case& c : cases) {
    const std::string path = dir + c.file;
    if (!std::filesystem::exists(path)) {
      ADD_FAILURE() << "missing " << path;
      continue;
    }
    const MeshReport r = analyse_mesh(read_gmsh(path));
    EXPECT_EQ(r.num_points, c.nodes) << c.file;
    EXPECT_EQ(r.num_tets, c.tets) << c.file;
    EXPECT_TRUE(r.inverted.empty()) << c.file;
    EXPECT_NEAR((r.bbox_max - r.bbox_min).maxCoeff(), c.max_extent, 1e-9) << c.file;
    EXPECT_LT(std::filesystem::file_size(path), 1000000u) << c.file;
  }
}

TEST(MeshGenerator, QuadraticGmshFileHasTet10InGmshOrder) {
  // Every tet line is type 11 with Gmsh's node order: nodes 0-7 as VTK, node 8 the midside node of
  // edge (2,3), node 9 of edge (1,3); the nodes are all the quadratic points; the reader refuses it
  // (tmlab reads linear tets only).
  const Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 1, 1, 1);
  const QuadraticMesh qm = make_quadratic(mesh);
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "tmlab_mesh_generator_p2";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "q.msh").string();
  write_gmsh22_quadratic(mesh, qm, path);
  std::ifstream in(path);
  std::string line;
  int tets = 0;
  std::size_t nodes = 0;
  while (std::getline(in, line)) {
    if (line == "$Nodes") {
      std::getline(in, line);
      nodes = std::stoul(line);
    }
    std::istringstream ls(line);
    long id = 0, type = 0, ntags = 0;
    if (!(ls >> id >> type >> ntags) || type != 11 || ntags != 2) continue;
    long tag = 0;
    ls >> tag >> tag;
    std::array<Index, 10> n{};
    for (auto& v : n) {
      long k = 0;
      ls >> k;
      v = static_cast<Index>(k - 1);
    }
    const Tet& t = mesh.tets[static_cast<std::size_t>(tets)];
    for (int a = 0; a < 4; ++a) EXPECT_EQ(n[static_cast<std::size_t>(a)], t[static_cast<std::size_t>(a)]);
    EXPECT_EQ(n[4], qm.midside_node(t[0], t[1]));
    EXPECT_EQ(n[5], qm.midside_node(t[1], t[2]));
    EXPECT_EQ(n[6], qm.midside_node(t[0], t[2]));
    EXPECT_EQ(n[7], qm.midside_node(t[0], t[3]));
    EXPECT_EQ(n[8], qm.midside_node(t[2], t[3]));
    EXPECT_EQ(n[9], qm.midside_node(t[1], t[3]));
    ++tets;
  }
  EXPECT_EQ(tets, mesh.num_tets());
  EXPECT_EQ(nodes, qm.points.size());
  EXPECT_THROW(read_mesh(path), Error);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tmlab
