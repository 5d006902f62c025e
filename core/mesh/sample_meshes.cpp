// Sample meshes for the test rigs: graded indentation blocks and structured cylinders.
#include "core/mesh/sample_meshes.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace tmlab {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

std::vector<double> graded_coordinates(double lo, double hi, int n, double focus, double power) {
  if (n < 1) throw Error("graded_coordinates: need at least one cell, got " + std::to_string(n));
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo)) {
    throw Error("graded_coordinates: need finite lo < hi");
  }
  if (!(focus >= lo && focus <= hi)) throw Error("graded_coordinates: the focus must lie in [lo, hi]");
  if (!(power >= 1.0 && power <= 4.0)) throw Error("graded_coordinates: the power must be in [1, 4]");
  const double left = focus - lo, right = hi - focus;
  // Cells on the left side in proportion to its length, at least one on a side of non-zero length.
  int n_left = static_cast<int>(std::lround(n * left / (hi - lo)));
  if (left > 0.0 && n_left == 0) n_left = 1;
  if (right > 0.0 && n_left == n) n_left = n - 1;
  if (n_left < 0 || (left > 0.0 && right > 0.0 && n < 2)) {
    throw Error("graded_coordinates: a focus strictly inside [lo, hi] needs at least two cells");
  }
  const int n_right = n - n_left;
  std::vector<double> c;
  c.reserve(static_cast<std::size_t>(n) + 1);
  c.push_back(lo);
  for (int i = n_left - 1; i >= 1; --i) {
    c.push_back(focus - left * std::pow(static_cast<double>(i) / n_left, power));
  }
  if (n_left > 0 && n_right > 0) c.push_back(focus);
  for (int i = 1; i < n_right; ++i) {
    c.push_back(focus + right * std::pow(static_cast<double>(i) / n_right, power));
  }
  c.push_back(hi);
  return c;
}

namespace {

/// One side of contact_graded_coordinates: distances 0 = t_0 < ... < t_N = length from the focus.
struct GradedSide {
  bool uniform = false;  ///< the whole side uniform (no room for a growth zone)
  double m = 0.0;        ///< fine cells (r = 1); uniform: all cells
  double w = 0.0;        ///< fine zone width m h
  double n = 0.0;        ///< growth cells (r = 1)
  double a = 0.0;        ///< the growth map's rate
  double fine_cells(double r) const { return std::max(1.0, std::round(m * r)); }
  double growth_cells(double r) const { return n > 0.0 ? std::max(1.0, std::round(n * r)) : 0.0; }
  double cells(double r) const { return fine_cells(r) + growth_cells(r); }
};

/// The cells of a growth zone of length g from spacing h at the rate a: h (e^{a n} - 1) / a = g.
double growth_length(double h, double a, double n) { return a > 0.0 ? h * std::expm1(a * n) / a : h * n; }

GradedSide plan_side(double length, double h, double half_width, double growth) {
  GradedSide p;
  const double a_max = std::log(growth);
  p.m = std::max(1.0, std::ceil(half_width / h - 1e-9));
  for (;; p.m += 1.0) {
    p.w = p.m * h;
    const double g = length - p.w;
    if (g < h || !(a_max > 0.0)) {  // no room to grow (or no growth): the side is uniform
      p.uniform = true;
      p.m = std::max(1.0, std::ceil(length / h - 1e-9));
      p.w = length;
      p.n = 0.0;
      return p;
    }
    p.n = std::ceil(std::log1p(a_max * g / h) / a_max - 1e-9);
    if (p.n * h > g) continue;  // it would have to shrink: widen the fine zone by one cell
    // The rate a in [0, a_max] that ends the side exactly (growth_length increases with a).
    double lo = 0.0, hi = a_max;
    for (int it = 0; it < 200 && hi - lo > 1e-15 * a_max; ++it) {
      const double mid = 0.5 * (lo + hi);
      (growth_length(h, mid, p.n) < g ? lo : hi) = mid;
    }
    p.a = 0.5 * (lo + hi);
    return p;
  }
}

void check_contact_grading(double lo, double hi, double focus, double h, double half_width, double growth,
                           double refinement) {
  const std::string f = "contact_graded_coordinates: ";
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo)) throw Error(f + "need finite lo < hi");
  if (!(focus >= lo && focus <= hi)) throw Error(f + "the focus must lie in [lo, hi]");
  if (!(h > 0.0) || !std::isfinite(h)) throw Error(f + "the fine spacing must be positive and finite");
  if (!(half_width >= 0.0) || !std::isfinite(half_width))
    throw Error(f + "the fine zone's half width must be >= 0 and finite");
  if (!(growth >= 1.0 && growth <= 4.0)) throw Error(f + "the growth ratio must be in [1, 4]");
  if (!(refinement > 0.0) || !std::isfinite(refinement))
    throw Error(f + "the refinement must be positive and finite");
  // Beyond 1e7 fine cells per side the plan's loop would be long: the count is then huge anyway.
  if (std::min(hi - lo, half_width) / h > 1e7 || (growth == 1.0 && (hi - lo) / h > 1e7))
    throw Error(f + "more than 10,000,000 cells of the fine spacing on an axis");
}

/// The sides of [lo, hi] about the focus: lengths of the left and right sides.
std::pair<double, double> side_lengths(double lo, double hi, double focus) {
  return {focus - lo, hi - focus};
}

}  // namespace

double contact_graded_cells(double lo, double hi, double focus, double h_fine, double fine_half_width,
                            double growth, double refinement) {
  check_contact_grading(lo, hi, focus, h_fine, fine_half_width, growth, refinement);
  const auto [left, right] = side_lengths(lo, hi, focus);
  double cells = 0.0;
  for (const double side : {left, right})
    if (side > 0.0) cells += plan_side(side, h_fine, fine_half_width, growth).cells(refinement);
  return cells;
}

std::vector<double> contact_graded_coordinates(double lo, double hi, double focus, double h_fine,
                                               double fine_half_width, double growth, double refinement) {
  const double cells = contact_graded_cells(lo, hi, focus, h_fine, fine_half_width, growth, refinement);
  if (cells > kMaxGradedCells)
    throw Error("contact_graded_coordinates: " + std::to_string(static_cast<long long>(cells)) +
                " cells on one axis (the limit is " +
                std::to_string(static_cast<long long>(kMaxGradedCells)) + ")");
  // Distances from the focus of one side's nodes, 0 first, `length` last (exact).
  const auto side_nodes = [&](double length) {
    const GradedSide p = plan_side(length, h_fine, fine_half_width, growth);
    const double nf = p.fine_cells(refinement), ng = p.growth_cells(refinement);
    std::vector<double> t;
    for (double i = 0.0; i < nf; i += 1.0) t.push_back(p.w * (i / nf));
    t.push_back(p.w);
    for (double j = 1.0; j <= ng; j += 1.0) t.push_back(p.w + growth_length(h_fine, p.a, p.n * (j / ng)));
    t.back() = length;
    return t;
  };
  const auto [left, right] = side_lengths(lo, hi, focus);
  std::vector<double> c;
  if (left > 0.0) {
    const std::vector<double> t = side_nodes(left);
    for (auto it = t.rbegin(); it != t.rend(); ++it) c.push_back(focus - *it);
    c.front() = lo;
  }
  if (right > 0.0) {
    const std::vector<double> t = side_nodes(right);
    for (std::size_t i = c.empty() ? 0 : 1; i < t.size(); ++i) c.push_back(focus + t[i]);
    c.back() = hi;
  }
  return c;
}

std::vector<double> two_sided_graded_coordinates(double lo, double hi, double h_fine, double fine_width,
                                                 double growth, double refinement) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo))
    throw Error("two_sided_graded_coordinates: need finite lo < hi");
  const double mid = 0.5 * (lo + hi);
  const std::vector<double> half =
      contact_graded_coordinates(lo, mid, lo, h_fine, fine_width, growth, refinement);
  std::vector<double> c = half;
  for (std::size_t i = half.size() - 1; i-- > 0;) c.push_back(hi - (half[i] - lo));
  c.back() = hi;
  return c;
}

Mesh make_block_mesh(const BlockSpec& s) {
  if (!(s.size_x > 0.0 && s.size_y > 0.0 && s.size_z > 0.0)) {
    throw Error("make_block_mesh: the block size must be positive on every axis");
  }
  if (std::abs(s.cx) > 0.5 * s.size_x || std::abs(s.cy) > 0.5 * s.size_y) {
    throw Error("make_block_mesh: the refinement point (cx, cy) lies outside the top face");
  }
  BoxGrid grid;
  grid[0] = graded_coordinates(-0.5 * s.size_x, 0.5 * s.size_x, s.nx, s.cx, s.grading);
  grid[1] = graded_coordinates(-0.5 * s.size_y, 0.5 * s.size_y, s.ny, s.cy, s.grading);
  grid[2] = graded_coordinates(0.0, s.size_z, s.nz, s.size_z, s.grading);
  return make_block_mesh(grid);
}

Mesh make_block_mesh(const BoxGrid& grid) {
  Mesh mesh = make_box_mesh(grid);
  for (PhysicalGroup& g : mesh.groups) {
    if (g.dim == 2 && g.tag == kBoxZmin) g.name = "bottom";
    if (g.dim == 2 && g.tag == kBoxZmax) g.name = "top";
  }
  return mesh;
}

namespace {

// The disk of hexagonal rings: node 0 at the centre, ring k (1..rings) with 6k nodes starting at
// angle 0, counter-clockwise. Returns the triangles joining consecutive rings.
std::vector<Tri> disk_triangles(int rings) {
  const auto ring_start = [](int k) { return k == 0 ? 0 : 1 + 3 * k * (k - 1); };
  std::vector<Tri> tris;
  for (int k = 1; k <= rings; ++k) {
    const int n_in = k == 1 ? 1 : 6 * (k - 1), n_out = 6 * k;
    const int s_in = ring_start(k - 1), s_out = ring_start(k);
    const auto in = [&](int i) { return static_cast<Index>(s_in + (n_in == 1 ? 0 : i % n_in)); };
    const auto out = [&](int j) { return static_cast<Index>(s_out + j % n_out); };
    // Zipper by angle: advance along the ring whose next node comes first (angles compared
    // exactly as fractions (i+1)/n_in against (j+1)/n_out).
    int i = 0, j = 0;
    const int i_end = k == 1 ? 0 : n_in;
    while (i < i_end || j < n_out) {
      const bool advance_out =
          i == i_end || (j < n_out && static_cast<long>(j + 1) * n_in <= static_cast<long>(i + 1) * n_out);
      if (advance_out) {
        tris.push_back({in(i), out(j), out(j + 1)});
        ++j;
      } else {
        tris.push_back({in(i), out(j), in(i + 1)});
        ++i;
      }
    }
  }
  return tris;
}

// Splits the prism (b0 b1 b2 | t0 t1 t2), t_i above b_i, into three tets, each quadrilateral face
// cut along the diagonal through its lowest-numbered node (so adjacent prisms conform).
void split_prism(std::array<Index, 6> v, std::vector<Tet>& tets) {
  // Bring the lowest node to position 0: swap bottom and top if it is on top, then rotate.
  const auto lowest = static_cast<int>(std::min_element(v.begin(), v.end()) - v.begin());
  if (lowest >= 3) {
    std::swap(v[0], v[3]);
    std::swap(v[1], v[4]);
    std::swap(v[2], v[5]);
  }
  const int r = lowest % 3;
  const std::array<Index, 6> w{v[static_cast<std::size_t>(r)],
                               v[static_cast<std::size_t>((r + 1) % 3)],
                               v[static_cast<std::size_t>((r + 2) % 3)],
                               v[static_cast<std::size_t>(3 + r)],
                               v[static_cast<std::size_t>(3 + (r + 1) % 3)],
                               v[static_cast<std::size_t>(3 + (r + 2) % 3)]};
  // Faces (w0 w1 w4 w3) and (w0 w2 w5 w3) are cut through w0; the face (w1 w2 w5 w4) through the
  // lower of its two diagonals' lowest nodes.
  if (std::min(w[1], w[5]) < std::min(w[2], w[4])) {
    tets.push_back({w[0], w[1], w[2], w[5]});
    tets.push_back({w[0], w[1], w[5], w[4]});
  } else {
    tets.push_back({w[0], w[1], w[2], w[4]});
    tets.push_back({w[0], w[4], w[2], w[5]});
  }
  tets.push_back({w[0], w[4], w[5], w[3]});
}

}  // namespace

Mesh make_cylinder_mesh(const CylinderSpec& s) {
  if (!(s.radius > 0.0 && std::isfinite(s.radius)) || !(s.height > 0.0 && std::isfinite(s.height))) {
    throw Error("make_cylinder_mesh: radius and height must be positive and finite");
  }
  if (s.rings < 1 || s.layers < 1 || s.rings > 2000 || s.layers > 100000) {
    throw Error("make_cylinder_mesh: need 1 <= rings <= 2000 and 1 <= layers <= 100000");
  }
  const auto check_grid = [](const std::vector<double>& v, int n, double end, const char* what) {
    if (v.empty()) return;
    bool ok = v.size() == static_cast<std::size_t>(n) + 1 && v.front() == 0.0 && v.back() == end;
    for (std::size_t i = 1; ok && i < v.size(); ++i) ok = std::isfinite(v[i]) && v[i] > v[i - 1];
    if (!ok)
      throw Error(std::string("make_cylinder_mesh: ") + what +
                  " must hold one increasing value per node from 0 to the end (or be empty)");
  };
  check_grid(s.ring_radii, s.rings, s.radius, "ring_radii");
  check_grid(s.layer_z, s.layers, s.height, "layer_z");
  const Index per_layer = static_cast<Index>(1 + 3 * s.rings * (s.rings + 1));
  Mesh mesh;
  mesh.points.reserve(static_cast<std::size_t>(per_layer) * static_cast<std::size_t>(s.layers + 1));
  for (int l = 0; l <= s.layers; ++l) {
    const double z = !s.layer_z.empty() ? s.layer_z[static_cast<std::size_t>(l)]
                     : l == s.layers    ? s.height
                                        : s.height * l / s.layers;
    mesh.points.emplace_back(0.0, 0.0, z);
    for (int k = 1; k <= s.rings; ++k) {
      const double r = !s.ring_radii.empty() ? s.ring_radii[static_cast<std::size_t>(k)]
                       : k == s.rings        ? s.radius
                                             : s.radius * k / s.rings;
      for (int j = 0; j < 6 * k; ++j) {
        const double a = 2.0 * kPi * j / (6 * k);
        mesh.points.emplace_back(r * std::cos(a), r * std::sin(a), z);
      }
    }
  }
  for (std::size_t p = 0; p < mesh.points.size(); ++p)
    mesh.point_file_ids.push_back(static_cast<long>(p + 1));

  const std::vector<Tri> disk = disk_triangles(s.rings);
  for (int l = 0; l < s.layers; ++l) {
    const Index b = per_layer * l, t = per_layer * (l + 1);
    for (const Tri& tri : disk) {
      split_prism({tri[0] + b, tri[1] + b, tri[2] + b, tri[0] + t, tri[1] + t, tri[2] + t}, mesh.tets);
    }
  }
  // Positive orientation: swap two nodes of any tet with a negative signed volume.
  for (Index e = 0; e < mesh.num_tets(); ++e) {
    if (tet_signed_volume(mesh, e) < 0.0)
      std::swap(mesh.tets[static_cast<std::size_t>(e)][2], mesh.tets[static_cast<std::size_t>(e)][3]);
  }
  mesh.tet_physical.assign(mesh.tets.size(), kCylinderBody);

  for (const Tri& f : boundary_faces(mesh)) {
    const auto layer = [&](Index v) { return v / per_layer; };
    const bool bottom = layer(f[0]) == 0 && layer(f[1]) == 0 && layer(f[2]) == 0;
    const bool top = layer(f[0]) == s.layers && layer(f[1]) == s.layers && layer(f[2]) == s.layers;
    mesh.triangles.push_back(f);
    mesh.triangle_physical.push_back(bottom ? kCylinderBottom : top ? kCylinderTop : kCylinderSide);
  }
  mesh.groups = {{2, kCylinderBottom, "bottom"},
                 {2, kCylinderTop, "top"},
                 {2, kCylinderSide, "side"},
                 {3, kCylinderBody, "body"}};
  return mesh;
}

double SampleMeshSize::generator_bytes() const {
  const double per_node = sizeof(Vec3) + sizeof(long);
  const double per_tet = sizeof(Tet) + sizeof(int) + 4.0 * (sizeof(Tri) + sizeof(Index) + sizeof(int));
  const double per_triangle = sizeof(Tri) + sizeof(int);
  return per_node * nodes + per_tet * tets + per_triangle * boundary_triangles;
}

double SampleMeshSize::gmsh_bytes() const { return 64.0 * nodes + 48.0 * (tets + boundary_triangles); }

SampleMeshSize block_mesh_size(double nx, double ny, double nz) {
  SampleMeshSize m;
  m.nodes = (nx + 1.0) * (ny + 1.0) * (nz + 1.0);
  m.tets = 6.0 * nx * ny * nz;
  m.boundary_triangles = 4.0 * (nx * ny + ny * nz + nz * nx);
  return m;
}

SampleMeshSize cylinder_mesh_size(double rings, double layers) {
  SampleMeshSize m;
  m.nodes = (1.0 + 3.0 * rings * (rings + 1.0)) * (layers + 1.0);
  m.tets = 18.0 * rings * rings * layers;
  m.boundary_triangles = 12.0 * rings * rings + 12.0 * rings * layers;
  return m;
}

double cylinder_mesh_volume(const CylinderSpec& s) {
  const double n = 6.0 * s.rings;
  return 0.5 * n * s.radius * s.radius * std::sin(2.0 * kPi / n) * s.height;
}

}  // namespace tmlab
