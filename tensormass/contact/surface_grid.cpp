#include "tensormass/contact/surface_grid.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tmlab::tm {

ContactSurface ContactSurface::extract(const Mesh& mesh) {
  ContactSurface s;
  s.faces = boundary_faces(mesh);
  if (s.faces.empty()) throw Error("contact: the mesh has no boundary face (no tetrahedra?)");
  s.local.assign(static_cast<std::size_t>(mesh.num_points()), -1);
  for (const Tri& f : s.faces)
    for (Index n : f) s.local[static_cast<std::size_t>(n)] = 0;
  for (Index i = 0; i < mesh.num_points(); ++i)
    if (s.local[static_cast<std::size_t>(i)] == 0) {
      s.local[static_cast<std::size_t>(i)] = static_cast<Index>(s.nodes.size());
      s.nodes.push_back(i);
    }
  s.area.assign(s.nodes.size(), 0.0);
  s.node_face_start.assign(s.nodes.size() + 1, 0);
  double edges = 0.0;
  for (const Tri& f : s.faces) {
    const Vec3& a = mesh.points[static_cast<std::size_t>(f[0])];
    const Vec3& b = mesh.points[static_cast<std::size_t>(f[1])];
    const Vec3& c = mesh.points[static_cast<std::size_t>(f[2])];
    const Vec3 cross = (b - a).cross(c - a);
    const double area = 0.5 * cross.norm();
    s.face_area.push_back(area);
    s.face_normal.push_back(area > 0.0 ? Vec3(cross.normalized()) : Vec3::Zero());
    for (Index n : f) {
      const std::size_t k = static_cast<std::size_t>(s.local[static_cast<std::size_t>(n)]);
      s.area[k] += area / 3.0;
      ++s.node_face_start[k + 1];
    }
    edges += (b - a).norm() + (c - b).norm() + (a - c).norm();
  }
  for (std::size_t k = 0; k < s.nodes.size(); ++k) s.node_face_start[k + 1] += s.node_face_start[k];
  s.node_faces.resize(static_cast<std::size_t>(s.node_face_start.back()));
  std::vector<Index> fill(s.node_face_start.begin(), s.node_face_start.end() - 1);
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    for (Index n : s.faces[f]) {
      const std::size_t k = static_cast<std::size_t>(s.local[static_cast<std::size_t>(n)]);
      s.node_faces[static_cast<std::size_t>(fill[k]++)] = static_cast<Index>(f);
    }
  s.mean_edge = edges / (3.0 * static_cast<double>(s.faces.size()));
  return s;
}

double ContactSurface::contact_area(Index k, const Vec3& n) const {
  double a = 0.0;
  for (Index i = node_face_start[static_cast<std::size_t>(k)];
       i < node_face_start[static_cast<std::size_t>(k) + 1]; ++i) {
    const std::size_t f = static_cast<std::size_t>(node_faces[static_cast<std::size_t>(i)]);
    a += face_area[f] / 3.0 * std::max(0.0, -face_normal[f].dot(n));
  }
  return a;
}

namespace {
Vec3 node_position(const Mesh& mesh, const VecX& u, Index n) {
  Vec3 x = mesh.points[static_cast<std::size_t>(n)];
  if (u.size() > 0) x += u.segment<3>(3 * static_cast<Eigen::Index>(n));
  return x;
}

std::vector<Vec3> surface_positions(const Mesh& mesh, const ContactSurface& surface, const VecX& u) {
  std::vector<Vec3> x(surface.nodes.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    x[k] = node_position(mesh, u, surface.nodes[k]);
    if (!x[k].allFinite())
      throw Error("contact: non-finite position of surface node " + std::to_string(surface.nodes[k]));
  }
  return x;
}
}  // namespace

SurfaceGrid::SurfaceGrid(const Mesh& mesh, const ContactSurface& surface, const VecX& u, double cell)
    : SurfaceGrid(surface_positions(mesh, surface, u), surface.mean_edge, cell) {}

void SurfaceGrid::refit(const Mesh& mesh, const ContactSurface& surface, const VecX& u) {
  refit(surface_positions(mesh, surface, u));
}

SurfaceGrid::SurfaceGrid(const std::vector<Vec3>& x, double mean_edge, double cell) {
  cell_ = cell > 0.0 ? cell : 2.0 * mean_edge;
  // Keep the grid at most ~4 cells per point: a flat surface in a large box would otherwise
  // allocate mostly empty cells. Volume of the box / cell^3 <= 4 n.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& p : x) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 ext = (hi - lo).cwiseMax(cell_);
  const double budget = 4.0 * std::max<double>(1.0, static_cast<double>(x.size()));
  const double cells = (ext.array() / cell_).prod();
  if (cells > budget) cell_ *= std::cbrt(cells / budget);
  if (!(cell_ > 0.0) || !std::isfinite(cell_))
    throw Error("contact: cannot size the surface grid (degenerate mesh?)");
  refit(x);
}

void SurfaceGrid::refit(const std::vector<Vec3>& x) {
  const std::size_t n = x.size();
  pos_ = x;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t k = 0; k < n; ++k) {
    if (!pos_[k].allFinite())
      throw Error("contact: non-finite position of surface point " + std::to_string(k));
    lo = lo.cwiseMin(pos_[k]);
    hi = hi.cwiseMax(pos_[k]);
  }
  origin_ = lo;
  for (int c = 0; c < 3; ++c)
    dims_[static_cast<std::size_t>(c)] =
        std::max(1, static_cast<int>(std::floor((hi(c) - lo(c)) / cell_)) + 1);
  const std::size_t ncell = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
  cell_start_.assign(ncell + 1, 0);
  cell_of_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    std::size_t id = 0;
    for (int c = 2; c >= 0; --c) {
      const int i = std::clamp(static_cast<int>((pos_[k](c) - origin_(c)) / cell_), 0,
                               dims_[static_cast<std::size_t>(c)] - 1);
      id = id * static_cast<std::size_t>(dims_[static_cast<std::size_t>(c)]) + static_cast<std::size_t>(i);
    }
    cell_of_[k] = static_cast<Index>(id);
    ++cell_start_[id + 1];
  }
  for (std::size_t c = 0; c < ncell; ++c) cell_start_[c + 1] += cell_start_[c];
  entries_.resize(n);
  std::vector<Index> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t k = 0; k < n; ++k)
    entries_[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell_of_[k])]++)] = static_cast<Index>(k);
}

std::vector<Index> SurfaceGrid::query(const Vec3& lo, const Vec3& hi) const {
  std::vector<Index> out;
  std::array<int, 3> a{}, b{};
  for (int c = 0; c < 3; ++c) {
    const int d = dims_[static_cast<std::size_t>(c)];
    // Clamp in double before converting: the bounds may be infinite.
    const double fa = std::clamp((lo(c) - origin_(c)) / cell_, -1.0, static_cast<double>(d));
    const double fb = std::clamp((hi(c) - origin_(c)) / cell_, -1.0, static_cast<double>(d));
    if (!(fa <= fb)) return out;  // empty or NaN box
    a[static_cast<std::size_t>(c)] = std::max(0, static_cast<int>(std::floor(fa)));
    b[static_cast<std::size_t>(c)] = std::min(d - 1, static_cast<int>(std::floor(fb)));
    if (a[static_cast<std::size_t>(c)] > b[static_cast<std::size_t>(c)]) return out;
  }
  for (int k = a[2]; k <= b[2]; ++k)
    for (int j = a[1]; j <= b[1]; ++j)
      for (int i = a[0]; i <= b[0]; ++i) {
        const std::size_t id =
            (static_cast<std::size_t>(k) * static_cast<std::size_t>(dims_[1]) + static_cast<std::size_t>(j)) *
                static_cast<std::size_t>(dims_[0]) +
            static_cast<std::size_t>(i);
        for (Index e = cell_start_[id]; e < cell_start_[id + 1]; ++e) {
          const Index node = entries_[static_cast<std::size_t>(e)];
          const Vec3& x = pos_[static_cast<std::size_t>(node)];
          if ((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all()) out.push_back(node);
        }
      }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace tmlab::tm
