// Mesh geometry and quality report.
#include "core/mesh/mesh_quality.hpp"

#include "core/base/format.hpp"

#include "core/mesh/mesh_ops.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <utility>

namespace tmlab {

double tet_signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

double tet_signed_volume(const Mesh& mesh, Index t) {
  assert(t >= 0 && t < mesh.num_tets());
  const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
  const auto p = [&](int k) -> const Vec3& {
    return mesh.points[static_cast<std::size_t>(tet[static_cast<std::size_t>(k)])];
  };
  return tet_signed_volume(p(0), p(1), p(2), p(3));
}

double tet_rms_edge(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double sum = (b - a).squaredNorm() + (c - a).squaredNorm() + (d - a).squaredNorm() +
                     (c - b).squaredNorm() + (d - b).squaredNorm() + (d - c).squaredNorm();
  return std::sqrt(sum / 6.0);
}

double tet_quality(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double l = tet_rms_edge(a, b, c, d);
  if (l == 0.0) return 0.0;
  return 6.0 * std::sqrt(2.0) * tet_signed_volume(a, b, c, d) / (l * l * l);
}

MeshReport analyse_mesh(const Mesh& mesh) {
  MeshReport r;
  r.source = mesh.source;
  r.num_points = mesh.num_points();
  r.num_tets = mesh.num_tets();
  r.num_triangles = static_cast<Index>(mesh.triangles.size());
  r.num_vertices = static_cast<Index>(mesh.vertices.size());
  r.groups = mesh.groups;

  if (!mesh.points.empty()) {
    r.bbox_min = mesh.points.front();
    r.bbox_max = mesh.points.front();
    for (const Vec3& p : mesh.points) {
      r.bbox_min = r.bbox_min.cwiseMin(p);
      r.bbox_max = r.bbox_max.cwiseMax(p);
    }
  }

  std::vector<char> used(mesh.points.size(), 0);
  std::vector<std::pair<Index, Index>> edges;
  edges.reserve(mesh.tets.size() * 6);
  r.volumes.reserve(mesh.tets.size());
  r.quality.reserve(mesh.tets.size());
  double q_sum = 0.0;
  for (Index t = 0; t < r.num_tets; ++t) {
    const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
    for (const Index n : tet) {
      assert(n >= 0 && n < r.num_points);
      used[static_cast<std::size_t>(n)] = 1;
    }
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) {
        const Index a = tet[static_cast<std::size_t>(i)];
        const Index b = tet[static_cast<std::size_t>(j)];
        edges.emplace_back(std::min(a, b), std::max(a, b));
      }
    }
    const Vec3& a = mesh.points[static_cast<std::size_t>(tet[0])];
    const Vec3& b = mesh.points[static_cast<std::size_t>(tet[1])];
    const Vec3& c = mesh.points[static_cast<std::size_t>(tet[2])];
    const Vec3& d = mesh.points[static_cast<std::size_t>(tet[3])];
    const double v = tet_signed_volume(a, b, c, d);
    const double l = tet_rms_edge(a, b, c, d);
    const double q = tet_quality(a, b, c, d);
    r.volumes.push_back(v);
    r.quality.push_back(q);
    r.total_volume += v;
    q_sum += q;
    if (t == 0 || v < r.min_volume) r.min_volume = v;
    if (t == 0 || v > r.max_volume) r.max_volume = v;
    if (t == 0 || q < r.q_min) {
      r.q_min = q;
      r.q_min_tet = t;
    }
    if (t == 0 || q > r.q_max) r.q_max = q;
    const int bin = std::clamp(static_cast<int>(std::floor(q * 10.0)), 0, 9);
    ++r.q_histogram[static_cast<std::size_t>(bin)];
    if (v < 0.0) r.inverted.push_back(t);
    if (std::abs(v) < kDegenerateRelVolume * l * l * l) r.degenerate.push_back(t);
  }
  if (r.num_tets > 0) r.q_mean = q_sum / r.num_tets;
  r.num_unused_points = static_cast<Index>(std::count(used.begin(), used.end(), 0));

  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  r.num_edges = static_cast<Index>(edges.size());
  double len_sum = 0.0;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const double len = (mesh.points[static_cast<std::size_t>(edges[e].first)] -
                        mesh.points[static_cast<std::size_t>(edges[e].second)])
                           .norm();
    if (e == 0 || len < r.edge_min) r.edge_min = len;
    if (e == 0 || len > r.edge_max) r.edge_max = len;
    len_sum += len;
  }
  if (!edges.empty()) r.edge_mean = len_sum / static_cast<double>(edges.size());

  r.num_boundary_faces = static_cast<Index>(boundary_faces(mesh).size());
  r.tet_file_ids = mesh.tet_file_ids;
  return r;
}

namespace {

std::string fmt(double v) { return significant(v, 6); }

std::string vec(const Vec3& v) { return "(" + fmt(v.x()) + ", " + fmt(v.y()) + ", " + fmt(v.z()) + ")"; }

std::string index_list(const std::vector<Index>& idx) {
  constexpr std::size_t kShow = 20;
  std::string out;
  for (std::size_t i = 0; i < idx.size() && i < kShow; ++i) out += (i ? " " : "") + std::to_string(idx[i]);
  if (idx.size() > kShow) out += " ... (" + std::to_string(idx.size() - kShow) + " more)";
  return out;
}

/// The file's element ids of the listed tets, when the mesh came from a file.
std::vector<long> file_ids(const MeshReport& r, const std::vector<Index>& idx) {
  std::vector<long> out;
  if (r.tet_file_ids.size() != static_cast<std::size_t>(r.num_tets)) return out;
  for (Index t : idx) out.push_back(r.tet_file_ids[static_cast<std::size_t>(t)]);
  return out;
}

std::string id_list(const MeshReport& r, const std::vector<Index>& idx) {
  const std::vector<long> ids = file_ids(r, idx);
  std::string out = "tmlab index " + index_list(idx);
  if (ids.empty()) return out;
  std::vector<Index> as_index(ids.begin(), ids.end());
  return out + "; Gmsh element " + index_list(as_index);
}

}  // namespace

std::string format_mesh_report(const MeshReport& r) {
  std::ostringstream os;
  os << "mesh: " << (r.source.empty() ? std::string("(generated)") : r.source) << "\n";
  os << "  points " << r.num_points << " (" << r.num_unused_points << " unused), tets " << r.num_tets
     << ", file triangles " << r.num_triangles << ", point elements " << r.num_vertices << ", boundary faces "
     << r.num_boundary_faces << ", edges " << r.num_edges << "\n";
  for (const PhysicalGroup& g : r.groups) {
    os << "  group dim " << g.dim << " tag " << g.tag << (g.name.empty() ? "" : " \"" + g.name + "\"")
       << "\n";
  }
  const Vec3 extent = r.bbox_max - r.bbox_min;
  os << "  bbox min " << vec(r.bbox_min) << " max " << vec(r.bbox_max) << " extent " << vec(extent) << "\n";
  os << "  volume total " << fmt(r.total_volume) << ", per tet min " << fmt(r.min_volume) << " max "
     << fmt(r.max_volume) << "\n";
  os << "  edge length min " << fmt(r.edge_min) << " mean " << fmt(r.edge_mean) << " max " << fmt(r.edge_max)
     << "\n";
  os << "  quality q = 6 sqrt(2) V / l_rms^3: min " << fmt(r.q_min) << " ("
     << (r.q_min_tet >= 0 ? id_list(r, {r.q_min_tet}) : std::string("no tets")) << ") mean " << fmt(r.q_mean)
     << " max " << fmt(r.q_max) << "\n";
  os << "  q histogram:";
  for (std::size_t k = 0; k < r.q_histogram.size(); ++k) {
    os << " [" << fmt(0.1 * static_cast<double>(k)) << ")" << r.q_histogram[k];
  }
  os << "\n";
  os << "  inverted tets (V < 0): " << r.inverted.size();
  if (!r.inverted.empty()) os << ": " << id_list(r, r.inverted);
  os << "\n";
  os << "  degenerate tets (|V| < " << fmt(kDegenerateRelVolume) << " l_rms^3): " << r.degenerate.size();
  if (!r.degenerate.empty()) os << ": " << id_list(r, r.degenerate);
  os << "\n";
  return os.str();
}

nlohmann::json mesh_report_json(const MeshReport& r) {
  using nlohmann::json;
  json groups = json::array();
  for (const PhysicalGroup& g : r.groups)
    groups.push_back({{"dim", g.dim}, {"tag", g.tag}, {"name", g.name}});
  const auto v3 = [](const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); };
  return json{
      {"source", r.source},
      {"num_points", r.num_points},
      {"num_unused_points", r.num_unused_points},
      {"num_tets", r.num_tets},
      {"num_triangles", r.num_triangles},
      {"num_vertices", r.num_vertices},
      {"num_boundary_faces", r.num_boundary_faces},
      {"num_edges", r.num_edges},
      {"groups", groups},
      {"bbox", {{"min", v3(r.bbox_min)}, {"max", v3(r.bbox_max)}, {"extent", v3(r.bbox_max - r.bbox_min)}}},
      {"volume", {{"total", r.total_volume}, {"min", r.min_volume}, {"max", r.max_volume}}},
      {"edge_length", {{"min", r.edge_min}, {"mean", r.edge_mean}, {"max", r.edge_max}}},
      {"quality",
       {{"definition", "6*sqrt(2)*V/l_rms^3"},
        {"min", r.q_min},
        {"min_tet", r.q_min_tet},
        {"mean", r.q_mean},
        {"max", r.q_max},
        {"histogram", r.q_histogram},
        {"histogram_bins", "10 bins of width 0.1 on [0,1]; q<=0 in the first, q>=1 in the last"}}},
      {"inverted", r.inverted},
      {"inverted_file_ids", file_ids(r, r.inverted)},
      {"degenerate", r.degenerate},
      {"degenerate_file_ids", file_ids(r, r.degenerate)},
      {"degenerate_rel_volume", kDegenerateRelVolume},
  };
}

}  // namespace tmlab
