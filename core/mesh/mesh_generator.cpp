// Structured box meshes and the Gmsh 2.2 writer.
#include "core/mesh/mesh_generator.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"

#include <array>
#include <cassert>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <utility>

namespace tmlab {

Mesh make_box_mesh(const Vec3& lo, const Vec3& hi, int nx, int ny, int nz) {
  if (nx < 1 || ny < 1 || nz < 1) {
    throw Error("make_box_mesh: cell counts must be >= 1, got " + std::to_string(nx) + " x " +
                std::to_string(ny) + " x " + std::to_string(nz));
  }
  if (!lo.allFinite() || !hi.allFinite() || !(hi.array() > lo.array()).all()) {
    throw Error("make_box_mesh: need finite corners with hi > lo on every axis");
  }
  const std::array<int, 3> n{nx, ny, nz};
  BoxGrid grid;
  for (int a = 0; a < 3; ++a) {
    const int na = n[static_cast<std::size_t>(a)];
    std::vector<double>& c = grid[static_cast<std::size_t>(a)];
    c.resize(static_cast<std::size_t>(na) + 1);
    // Exact end values, linear in between.
    for (int i = 0; i <= na; ++i) {
      const double t = static_cast<double>(i) / na;
      c[static_cast<std::size_t>(i)] = i == na ? hi[a] : lo[a] + t * (hi[a] - lo[a]);
    }
  }
  return make_box_mesh(grid);
}

Mesh make_box_mesh(const BoxGrid& grid) {
  for (int a = 0; a < 3; ++a) {
    const std::vector<double>& c = grid[static_cast<std::size_t>(a)];
    if (c.size() < 2) throw Error("make_box_mesh: each axis needs at least two grid coordinates");
    for (std::size_t i = 0; i < c.size(); ++i) {
      if (!std::isfinite(c[i]) || (i > 0 && !(c[i] > c[i - 1]))) {
        throw Error("make_box_mesh: grid coordinates of axis " + std::to_string(a) +
                    " must be finite and strictly increasing (at index " + std::to_string(i) + ")");
      }
    }
  }
  const int nx = static_cast<int>(grid[0].size()) - 1;
  const int ny = static_cast<int>(grid[1].size()) - 1;
  const int nz = static_cast<int>(grid[2].size()) - 1;
  const long long npts = static_cast<long long>(nx + 1) * (ny + 1) * (nz + 1);
  if (npts > std::numeric_limits<Index>::max() / 2 ||
      6LL * nx * ny * nz > std::numeric_limits<Index>::max() / 2) {
    throw Error("make_box_mesh: too many cells");
  }
  const std::array<int, 3> n{nx, ny, nz};
  const auto id = [&](int i, int j, int k) { return static_cast<Index>(i + (nx + 1) * (j + (ny + 1) * k)); };

  Mesh mesh;
  mesh.points.reserve(static_cast<std::size_t>(npts));
  for (int k = 0; k <= nz; ++k) {
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i <= nx; ++i) {
        mesh.points.emplace_back(grid[0][static_cast<std::size_t>(i)], grid[1][static_cast<std::size_t>(j)],
                                 grid[2][static_cast<std::size_t>(k)]);
        mesh.point_file_ids.push_back(static_cast<long>(mesh.points.size()));
      }
    }
  }

  // The six axis permutations and their signs; a path low corner -> +e_p0 -> +e_p1 -> high corner.
  constexpr int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  constexpr bool kOdd[6] = {false, true, true, false, false, true};
  mesh.tets.reserve(6 * static_cast<std::size_t>(nx) * ny * nz);
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        for (int p = 0; p < 6; ++p) {
          std::array<int, 3> c{i, j, k};
          const Index v0 = id(c[0], c[1], c[2]);
          ++c[static_cast<std::size_t>(kPerm[p][0])];
          const Index v1 = id(c[0], c[1], c[2]);
          ++c[static_cast<std::size_t>(kPerm[p][1])];
          const Index v2 = id(c[0], c[1], c[2]);
          const Index v3 = id(i + 1, j + 1, k + 1);
          mesh.tets.push_back(kOdd[p] ? Tet{v0, v1, v3, v2} : Tet{v0, v1, v2, v3});
          mesh.tet_physical.push_back(kBoxBody);
        }
      }
    }
  }

  // Boundary triangles, grouped by face tag.
  const std::vector<Tri> faces = boundary_faces(mesh);
  const auto ijk_of = [&](Index v) {
    const int i = v % (nx + 1);
    const int j = (v / (nx + 1)) % (ny + 1);
    const int k = v / ((nx + 1) * (ny + 1));
    return std::array<int, 3>{i, j, k};
  };
  for (int tag = kBoxXmin; tag <= kBoxZmax; ++tag) {
    const int axis = (tag - 1) / 2;
    const int value = (tag - 1) % 2 == 0 ? 0 : n[static_cast<std::size_t>(axis)];
    for (const Tri& f : faces) {
      bool on = true;
      for (const Index v : f) on = on && ijk_of(v)[static_cast<std::size_t>(axis)] == value;
      if (on) {
        mesh.triangles.push_back(f);
        mesh.triangle_physical.push_back(tag);
      }
    }
  }
  assert(mesh.triangles.size() == faces.size());
  const char* names[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  for (int tag = kBoxXmin; tag <= kBoxZmax; ++tag) mesh.groups.push_back({2, tag, names[tag - 1]});
  mesh.groups.push_back({3, kBoxBody, "body"});
  return mesh;
}

namespace {

void put_double(std::string& out, double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  assert(res.ec == std::errc());
  out.append(buf, res.ptr);
}

}  // namespace

namespace {

/// write_gmsh22 (quadratic null) and write_gmsh22_quadratic.
void write_gmsh22_file(const Mesh& mesh, const QuadraticMesh* quadratic, const std::string& path) {
  const std::vector<Vec3>& points = quadratic ? quadratic->points : mesh.points;
  [[maybe_unused]] const Index num_points = static_cast<Index>(points.size());  // asserts
  std::string out;
  out.reserve(64 * mesh.points.size() + 48 * (mesh.tets.size() + mesh.triangles.size()));
  out += "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  std::size_t named = 0;
  for (const PhysicalGroup& g : mesh.groups) named += g.name.empty() ? 0 : 1;
  if (named > 0) {
    out += "$PhysicalNames\n" + std::to_string(named) + "\n";
    for (const PhysicalGroup& g : mesh.groups) {
      if (g.name.empty()) continue;
      if (g.name.find('"') != std::string::npos) {
        throw input_error(path, 0, "physical group name contains a double quote: " + g.name);
      }
      out += std::to_string(g.dim) + " " + std::to_string(g.tag) + " \"" + g.name + "\"\n";
    }
    out += "$EndPhysicalNames\n";
  }
  out += "$Nodes\n" + std::to_string(points.size()) + "\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    if (!p.allFinite())
      throw input_error(path, 0, "point " + std::to_string(i) + " has non-finite coordinates");
    out += std::to_string(i + 1);
    for (int a = 0; a < 3; ++a) {
      out += ' ';
      put_double(out, p[a]);
    }
    out += '\n';
  }
  out += "$EndNodes\n$Elements\n" +
         std::to_string(mesh.vertices.size() + mesh.triangles.size() + mesh.tets.size()) + "\n";
  std::size_t eid = 0;
  const auto element = [&](int type, int phys, const Index* nodes, int count) {
    out += std::to_string(++eid) + " " + std::to_string(type) + " 2 " + std::to_string(phys) + " " +
           std::to_string(phys > 0 ? phys : 1);
    for (int k = 0; k < count; ++k) {
      assert(nodes[k] >= 0 && nodes[k] < num_points);
      out += " " + std::to_string(nodes[k] + 1);
    }
    out += '\n';
  };
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    element(15, mesh.vertex_physical[v], &mesh.vertices[v], 1);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (quadratic) {
      // Gmsh's 6-node triangle (type 9): vertices, then edges (0,1), (1,2), (2,0), as Tri6.
      const Tri6 q = quadratic->triangle(mesh.triangles[t]);
      element(9, mesh.triangle_physical[t], q.data(), 6);
    } else {
      element(2, mesh.triangle_physical[t], mesh.triangles[t].data(), 3);
    }
  }
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    if (quadratic) {
      // Gmsh's 10-node tet (type 11): VTK's order with the last two swapped (its node 8 is on
      // edge (2,3), node 9 on (1,3)).
      Tet10 q = quadratic->tets[t];
      std::swap(q[8], q[9]);
      element(11, mesh.tet_physical[t], q.data(), 10);
    } else {
      element(4, mesh.tet_physical[t], mesh.tets[t].data(), 4);
    }
  }
  out += "$EndElements\n";

  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  if (!file) throw input_error(path, 0, "cannot open file for writing");
  file.write(out.data(), static_cast<std::streamsize>(out.size()));
  file.close();
  if (!file) throw input_error(path, 0, "error while writing mesh file");
}

}  // namespace

void write_gmsh22(const Mesh& mesh, const std::string& path) { write_gmsh22_file(mesh, nullptr, path); }

void write_gmsh22_quadratic(const Mesh& mesh, const QuadraticMesh& quadratic, const std::string& path) {
  if (quadratic.num_vertices != mesh.num_points() || quadratic.num_tets() != mesh.num_tets())
    throw input_error(path, 0, "the quadratic mesh was not made from this mesh");
  write_gmsh22_file(mesh, &quadratic, path);
}

}  // namespace tmlab
