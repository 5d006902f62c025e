// Mesh operations, boundary extraction, group lookup and NodeSelector.
#include "core/mesh/mesh_ops.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_quality.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

namespace tmlab {

namespace {

const Vec3& point(const Mesh& mesh, Index i) { return mesh.points[static_cast<std::size_t>(i)]; }

Tri sorted_tri(Tri t) {
  std::sort(t.begin(), t.end());
  return t;
}

void sort_unique(std::vector<Index>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

std::string list_groups(const Mesh& mesh) {
  if (mesh.groups.empty()) return "the mesh has no physical groups";
  std::string out = "available groups:";
  for (const PhysicalGroup& g : mesh.groups) {
    out += " (dim " + std::to_string(g.dim) + ", tag " + std::to_string(g.tag) +
           (g.name.empty() ? std::string() : ", \"" + g.name + "\"") + ")";
  }
  return out;
}

/// Nodes of the elements of dimension dim with tag (no existence check).
void collect_group_nodes(const Mesh& mesh, int dim, int tag, std::vector<Index>& out) {
  if (dim == 3) {
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
      if (mesh.tet_physical[t] == tag) out.insert(out.end(), mesh.tets[t].begin(), mesh.tets[t].end());
    }
  } else if (dim == 2) {
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (mesh.triangle_physical[t] == tag) {
        out.insert(out.end(), mesh.triangles[t].begin(), mesh.triangles[t].end());
      }
    }
  } else if (dim == 0) {
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
      if (mesh.vertex_physical[v] == tag) out.push_back(mesh.vertices[v]);
    }
  }
}

/// The groups a group selector refers to; throws when there is none or a bare tag is ambiguous.
std::vector<PhysicalGroup> resolve_groups(const Mesh& mesh, const NodeSelector& s) {
  std::vector<PhysicalGroup> found;
  for (const PhysicalGroup& g : mesh.groups) {
    const bool id_match = s.group_name.empty() ? g.tag == s.group_tag : g.name == s.group_name;
    if (id_match && (s.group_dim < 0 || g.dim == s.group_dim)) found.push_back(g);
  }
  const std::string what =
      s.group_name.empty() ? "group tag " + std::to_string(s.group_tag) : "group \"" + s.group_name + "\"";
  const std::string dim = s.group_dim < 0 ? std::string() : " of dimension " + std::to_string(s.group_dim);
  if (found.empty()) {
    throw Error((mesh.source.empty() ? std::string("mesh") : mesh.source) + ": no " + what + dim + "; " +
                list_groups(mesh));
  }
  if (s.group_name.empty() && found.size() > 1) {
    throw Error((mesh.source.empty() ? std::string("mesh") : mesh.source) + ": " + what +
                " exists in several dimensions; add \"dim\" to the selector; " + list_groups(mesh));
  }
  return found;
}

// Local faces of a positively oriented tet, each with outward normal (b-a)x(c-a).
constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

}  // namespace

int repair_orientation(Mesh& mesh) {
  int flipped = 0;
  for (Index t = 0; t < mesh.num_tets(); ++t) {
    if (tet_signed_volume(mesh, t) < 0.0) {
      Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
      std::swap(tet[2], tet[3]);
      ++flipped;
    }
  }
  return flipped;
}

void scale_mesh(Mesh& mesh, double factor) {
  if (!std::isfinite(factor) || factor <= 0.0) {
    throw Error("scale_mesh: scale factor must be finite and > 0, got " + std::to_string(factor));
  }
  for (Vec3& p : mesh.points) p *= factor;
}

void translate_mesh(Mesh& mesh, const Vec3& offset) {
  if (!offset.allFinite()) throw Error("translate_mesh: offset must be finite");
  for (Vec3& p : mesh.points) p += offset;
}

std::vector<Tri> boundary_faces(const Mesh& mesh) {
  struct Face {
    Tri key;
    Index tet;
    int local;
  };
  std::vector<Face> faces;
  faces.reserve(mesh.tets.size() * 4);
  for (Index t = 0; t < mesh.num_tets(); ++t) {
    const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
    for (int f = 0; f < 4; ++f) {
      faces.push_back({sorted_tri({tet[static_cast<std::size_t>(kFaces[f][0])],
                                   tet[static_cast<std::size_t>(kFaces[f][1])],
                                   tet[static_cast<std::size_t>(kFaces[f][2])]}),
                       t, f});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.key < b.key; });
  std::vector<std::pair<Index, int>> single;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j == i + 1) single.emplace_back(faces[i].tet, faces[i].local);
    i = j;
  }
  std::sort(single.begin(), single.end());
  std::vector<Tri> out;
  out.reserve(single.size());
  for (const auto& [t, f] : single) {
    const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
    Tri tri{tet[static_cast<std::size_t>(kFaces[f][0])], tet[static_cast<std::size_t>(kFaces[f][1])],
            tet[static_cast<std::size_t>(kFaces[f][2])]};
    if (tet_signed_volume(mesh, t) < 0.0) std::swap(tri[1], tri[2]);
    out.push_back(tri);
  }
  return out;
}

std::vector<Index> boundary_nodes(const Mesh& mesh) {
  std::vector<Index> out;
  for (const Tri& f : boundary_faces(mesh)) out.insert(out.end(), f.begin(), f.end());
  sort_unique(out);
  return out;
}

std::vector<Index> nodes_of_group(const Mesh& mesh, int dim, int tag) {
  NodeSelector s;
  s.kind = NodeSelector::Kind::Group;
  s.group_tag = tag;
  s.group_dim = dim;
  return select_nodes(mesh, s);
}

std::vector<Index> nodes_of_group(const Mesh& mesh, const std::string& name) {
  NodeSelector s;
  s.kind = NodeSelector::Kind::Group;
  s.group_name = name;
  return select_nodes(mesh, s);
}

// ---- NodeSelector JSON ----------------------------------------------------------------------

namespace {

[[noreturn]] void bad(const std::string& where, const std::string& reason) {
  throw Error(where + ": " + reason);
}

void check_keys(const nlohmann::json& j, const std::string& where, const std::set<std::string>& allowed) {
  if (!j.is_object()) bad(where, "expected a JSON object, got " + j.dump());
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (allowed.count(it.key()) == 0) {
      std::string list;
      for (const std::string& k : allowed) list += (list.empty() ? "" : ", ") + k;
      bad(where, "unknown key \"" + it.key() + "\" (expected " + list + ")");
    }
  }
}

const nlohmann::json& need(const nlohmann::json& j, const std::string& key, const std::string& where) {
  const auto it = j.find(key);
  if (it == j.end()) bad(where, "missing key \"" + key + "\"");
  return *it;
}

double number(const nlohmann::json& j, const std::string& where) {
  if (!j.is_number()) bad(where, "expected a number, got " + j.dump());
  const double v = j.get<double>();
  if (!std::isfinite(v)) bad(where, "expected a finite number");
  return v;
}

Vec3 vec3(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3) bad(where, "expected an array of 3 numbers, got " + j.dump());
  return Vec3(number(j[0], where + "[0]"), number(j[1], where + "[1]"), number(j[2], where + "[2]"));
}

}  // namespace

NodeSelector NodeSelector::from_json(const nlohmann::json& j, const std::string& where) {
  check_keys(j, where, {"group", "dim", "box", "plane", "sphere", "nodes"});
  int kinds = 0;
  for (const char* k : {"group", "box", "plane", "sphere", "nodes"}) kinds += j.contains(k) ? 1 : 0;
  if (kinds != 1) {
    bad(where,
        "expected exactly one of \"group\", \"box\", \"plane\", \"sphere\", \"nodes\", got " + j.dump());
  }
  if (j.contains("dim") && !j.contains("group")) bad(where, "key \"dim\" is only allowed with \"group\"");

  NodeSelector s;
  if (j.contains("group")) {
    s.kind = Kind::Group;
    const nlohmann::json& g = j["group"];
    if (g.is_string()) {
      s.group_name = g.get<std::string>();
      if (s.group_name.empty()) bad(where + ".group", "empty group name");
    } else if (g.is_number_integer() && g.get<long long>() > 0 && g.get<long long>() <= 2147483647LL) {
      s.group_tag = g.get<int>();
    } else {
      bad(where + ".group", "expected a group name or a positive integer tag, got " + g.dump());
    }
    if (j.contains("dim")) {
      const nlohmann::json& d = j["dim"];
      if (!d.is_number_integer() || (d.get<int>() != 0 && d.get<int>() != 2 && d.get<int>() != 3)) {
        bad(where + ".dim", "expected 0, 2 or 3, got " + d.dump());
      }
      s.group_dim = d.get<int>();
    }
  } else if (j.contains("box")) {
    s.kind = Kind::Box;
    const nlohmann::json& b = j["box"];
    check_keys(b, where + ".box", {"min", "max"});
    s.box_min = vec3(need(b, "min", where + ".box"), where + ".box.min");
    s.box_max = vec3(need(b, "max", where + ".box"), where + ".box.max");
    if ((s.box_min.array() > s.box_max.array()).any()) bad(where + ".box", "min exceeds max");
  } else if (j.contains("plane")) {
    s.kind = Kind::Plane;
    const nlohmann::json& p = j["plane"];
    check_keys(p, where + ".plane", {"axis", "value", "tol"});
    const nlohmann::json& a = need(p, "axis", where + ".plane");
    const std::string axis = a.is_string() ? a.get<std::string>() : std::string();
    if (axis == "x") {
      s.axis = 0;
    } else if (axis == "y") {
      s.axis = 1;
    } else if (axis == "z") {
      s.axis = 2;
    } else {
      bad(where + ".plane.axis", "expected \"x\", \"y\" or \"z\", got " + a.dump());
    }
    s.value = number(need(p, "value", where + ".plane"), where + ".plane.value");
    if (p.contains("tol")) {
      s.tol = number(p["tol"], where + ".plane.tol");
      if (s.tol < 0.0) bad(where + ".plane.tol", "must be >= 0");
    }
  } else if (j.contains("sphere")) {
    s.kind = Kind::Sphere;
    const nlohmann::json& sp = j["sphere"];
    check_keys(sp, where + ".sphere", {"center", "radius"});
    s.center = vec3(need(sp, "center", where + ".sphere"), where + ".sphere.center");
    s.radius = number(need(sp, "radius", where + ".sphere"), where + ".sphere.radius");
    if (s.radius < 0.0) bad(where + ".sphere.radius", "must be >= 0");
  } else {
    s.kind = Kind::Nodes;
    const nlohmann::json& n = j["nodes"];
    if (!n.is_array()) bad(where + ".nodes", "expected an array of node indices, got " + n.dump());
    for (std::size_t i = 0; i < n.size(); ++i) {
      if (!n[i].is_number_integer() || n[i].get<long long>() < 0 || n[i].get<long long>() > 2147483647LL) {
        bad(where + ".nodes[" + std::to_string(i) + "]",
            "expected a non-negative node index, got " + n[i].dump());
      }
      s.nodes.push_back(n[i].get<Index>());
    }
  }
  return s;
}

nlohmann::json NodeSelector::to_json() const {
  using nlohmann::json;
  const auto v3 = [](const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); };
  switch (kind) {
    case Kind::Group: {
      json j;
      if (group_name.empty()) {
        j["group"] = group_tag;
      } else {
        j["group"] = group_name;
      }
      if (group_dim >= 0) j["dim"] = group_dim;
      return j;
    }
    case Kind::Box:
      return json{{"box", {{"min", v3(box_min)}, {"max", v3(box_max)}}}};
    case Kind::Plane: {
      const char* names[3] = {"x", "y", "z"};
      return json{{"plane", {{"axis", names[axis]}, {"value", value}, {"tol", tol}}}};
    }
    case Kind::Sphere:
      return json{{"sphere", {{"center", v3(center)}, {"radius", radius}}}};
    case Kind::Nodes:
      return json{{"nodes", nodes}};
  }
  assert(false);
  return json();
}

std::vector<Index> select_nodes(const Mesh& mesh, const NodeSelector& s) {
  std::vector<Index> out;
  switch (s.kind) {
    case NodeSelector::Kind::Group:
      for (const PhysicalGroup& g : resolve_groups(mesh, s)) collect_group_nodes(mesh, g.dim, g.tag, out);
      break;
    case NodeSelector::Kind::Box:
      for (Index i = 0; i < mesh.num_points(); ++i) {
        const Vec3& p = point(mesh, i);
        if ((p.array() >= s.box_min.array()).all() && (p.array() <= s.box_max.array()).all())
          out.push_back(i);
      }
      break;
    case NodeSelector::Kind::Plane:
      assert(s.axis >= 0 && s.axis < 3);
      for (Index i = 0; i < mesh.num_points(); ++i) {
        if (std::abs(point(mesh, i)[s.axis] - s.value) <= s.tol) out.push_back(i);
      }
      break;
    case NodeSelector::Kind::Sphere:
      for (Index i = 0; i < mesh.num_points(); ++i) {
        if ((point(mesh, i) - s.center).norm() <= s.radius) out.push_back(i);
      }
      break;
    case NodeSelector::Kind::Nodes:
      for (const Index n : s.nodes) {
        if (n < 0 || n >= mesh.num_points()) {
          throw Error((mesh.source.empty() ? std::string("mesh") : mesh.source) + ": selected node index " +
                      std::to_string(n) + " out of range (mesh has " + std::to_string(mesh.num_points()) +
                      " nodes)");
        }
      }
      out = s.nodes;
      break;
  }
  sort_unique(out);
  return out;
}

std::vector<Tri> select_faces(const Mesh& mesh, const NodeSelector& s) {
  const std::vector<Tri> boundary = boundary_faces(mesh);
  if (s.kind == NodeSelector::Kind::Group) {
    std::vector<int> surface_tags;
    for (const PhysicalGroup& g : resolve_groups(mesh, s)) {
      if (g.dim == 2) surface_tags.push_back(g.tag);
    }
    std::vector<Tri> out;
    if (!surface_tags.empty()) {
      std::vector<std::pair<Tri, std::size_t>> keys;
      keys.reserve(boundary.size());
      for (std::size_t i = 0; i < boundary.size(); ++i) keys.emplace_back(sorted_tri(boundary[i]), i);
      std::sort(keys.begin(), keys.end());
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        if (std::find(surface_tags.begin(), surface_tags.end(), mesh.triangle_physical[t]) ==
            surface_tags.end()) {
          continue;
        }
        const Tri key = sorted_tri(mesh.triangles[t]);
        const auto it = std::lower_bound(keys.begin(), keys.end(), std::make_pair(key, std::size_t{0}));
        out.push_back(it != keys.end() && it->first == key ? boundary[it->second] : mesh.triangles[t]);
      }
      if (!out.empty()) return out;
    }
  }
  const std::vector<Index> nodes = select_nodes(mesh, s);
  std::vector<char> selected(mesh.points.size(), 0);
  for (const Index n : nodes) selected[static_cast<std::size_t>(n)] = 1;
  std::vector<Tri> out;
  for (const Tri& f : boundary) {
    if (selected[static_cast<std::size_t>(f[0])] && selected[static_cast<std::size_t>(f[1])] &&
        selected[static_cast<std::size_t>(f[2])]) {
      out.push_back(f);
    }
  }
  return out;
}

Index nearest_node(const Mesh& mesh, const Vec3& p) {
  Index best = 0;
  double d = std::numeric_limits<double>::infinity();
  for (Index i = 0; i < mesh.num_points(); ++i) {
    const double di = (mesh.points[i] - p).squaredNorm();
    if (di < d) {
      d = di;
      best = i;
    }
  }
  return best;
}

}  // namespace tmlab
