// The test rigs as case files (rig.hpp explains the fixtures).
#include "calibration/rigs/rig.hpp"

#include "core/base/error.hpp"
#include "core/io/atomic_file.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/sample_meshes.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace tmlab::rigs {

namespace {

using nlohmann::json;

template <class Enum, std::size_t N>
Enum parse_choice(const std::string& name, const std::string& where, const char* const (&names)[N],
                  const Enum (&values)[N]) {
  std::string accepted;
  for (std::size_t i = 0; i < N; ++i) {
    if (name == names[i]) return values[i];
    accepted += (i ? ", " : "") + std::string(names[i]);
  }
  throw Error(where + ": unknown value '" + name + "' (accepted: " + accepted + ")");
}

constexpr const char* kTestNames[] = {"indentation", "unconfined_compression", "confined_compression",
                                      "uniaxial_tension"};
constexpr RigTest kTests[] = {RigTest::Indentation, RigTest::UnconfinedCompression,
                              RigTest::ConfinedCompression, RigTest::UniaxialTension};

json box_selector(const Vec3& lo, const Vec3& hi) {
  return {{"box", {{"min", {lo.x(), lo.y(), lo.z()}}, {"max", {hi.x(), hi.y(), hi.z()}}}}};
}

json group(const std::string& name) { return {{"group", name}}; }

json fixed(const std::string& name, const json& nodes, const std::string& components) {
  return {{"name", name}, {"nodes", nodes}, {"components", components}};
}

// The history as a time function f(t) = d(t) / peak, a table (the case scales it by the value).
json history_function(const DisplacementHistory& h) {
  const double peak = h.peak();
  json points = json::array();
  for (std::size_t k = 0; k < h.t.size(); ++k) points.push_back({h.t[k], h.d[k] / peak});
  return {{"type", "table"}, {"points", points}};
}

// In-plane rigid motions of a sample on a frictionless support, through its mirror planes
// (rig.hpp): u_y = 0 on bottom nodes with y = 0, u_x = 0 on bottom nodes with x = 0 (block) or at
// the bottom centre (cylinder).
void add_mirror_restraints(const RigSpec& s, json& boundary) {
  const double big = 1e3 * std::max({s.size_x, s.size_y, s.height, s.radius});
  const double eps = 1e-9 * std::max({s.size_x, s.size_y, s.height, s.radius});
  const double x0 = s.shape == SampleShape::Block ? s.cx : 0.0,
               y0 = s.shape == SampleShape::Block ? s.cy : 0.0;
  boundary.push_back(
      fixed("bottom_mirror_y", box_selector(Vec3(-big, y0 - eps, -eps), Vec3(big, y0 + eps, eps)), "y"));
  const double reach = s.shape == SampleShape::Block ? big : eps;
  boundary.push_back(fixed("bottom_mirror_x",
                           box_selector(Vec3(x0 - eps, y0 - reach, -eps), Vec3(x0 + eps, y0 + reach, eps)),
                           "x"));
}

json platen_boundary(const RigSpec& s) {
  json b = json::array();
  const bool bonded = s.platens == Support::Bonded;
  const std::string moving = bonded ? "xyz" : "z";
  if (s.test == RigTest::ConfinedCompression) {
    if (s.shape == SampleShape::Cylinder) {
      b.push_back(fixed("wall", group("side"), "xy"));
    } else {
      for (const char* side : {"xmin", "xmax", "ymin", "ymax"})
        b.push_back(fixed(std::string("wall_") + side, group(side), "xy"));
    }
  }
  b.push_back(fixed("bottom_platen", group("bottom"), bonded ? "xyz" : "z"));
  if (!bonded && s.test != RigTest::ConfinedCompression) add_mirror_restraints(s, b);
  // The top face follows the platen: u_z = -d(t) (value -peak times f(t) = d(t)/peak).
  json top = {{"name", "top_platen"},
              {"nodes", group("top")},
              {"components", moving},
              {"value", {0.0, 0.0, -s.history.peak()}},
              {"function", history_function(s.history)}};
  b.push_back(top);
  return b;
}

json indentation_boundary(const RigSpec& s) {
  json b = json::array();
  if (s.bottom == Support::Bonded) {
    b.push_back(fixed("bottom", group("bottom"), "xyz"));
  } else {
    b.push_back(fixed("bottom", group("bottom"), "z"));
    add_mirror_restraints(s, b);
  }
  return b;
}

json indenter_body(const RigSpec& s) {
  const double top = s.height;
  json body = {{"name", "indenter"}, {"mode", "frictionless"}};
  if (s.indenter == IndenterShape::Sphere) {
    body["type"] = "sphere";
    body["center"] = {s.cx, s.cy, top + s.indenter_radius};
    body["radius"] = s.indenter_radius;
  } else {
    body["type"] = "punch";
    body["center"] = {s.cx, s.cy, top};
    body["axis"] = {0.0, 0.0, -1.0};
    body["radius"] = s.indenter_radius;
  }
  body["displacement"] = {0.0, 0.0, -s.history.peak()};
  body["function"] = history_function(s.history);
  return body;
}

}  // namespace

RigTest parse_rig_test(const std::string& name, const std::string& where) {
  return parse_choice(name, where, kTestNames, kTests);
}

std::string rig_test_name(RigTest test) { return kTestNames[static_cast<int>(test)]; }

SampleShape parse_sample_shape(const std::string& name, const std::string& where) {
  constexpr const char* names[] = {"block", "cylinder"};
  constexpr SampleShape values[] = {SampleShape::Block, SampleShape::Cylinder};
  return parse_choice(name, where, names, values);
}

Support parse_support(const std::string& name, const std::string& where) {
  constexpr const char* names[] = {"bonded", "frictionless"};
  constexpr Support values[] = {Support::Bonded, Support::Frictionless};
  return parse_choice(name, where, names, values);
}

IndenterShape parse_indenter_shape(const std::string& name, const std::string& where) {
  constexpr const char* names[] = {"sphere", "flat_punch"};
  constexpr IndenterShape values[] = {IndenterShape::Sphere, IndenterShape::FlatPunch};
  return parse_choice(name, where, names, values);
}

DisplacementHistory DisplacementHistory::ramp_hold(double depth, double ramp, double hold) {
  if (!(ramp > 0.0) || !(hold >= 0.0))
    throw Error("rig history: the ramp time must be > 0 and the hold >= 0");
  DisplacementHistory h{{0.0, ramp}, {0.0, depth}};
  if (hold > 0.0) {
    h.t.push_back(ramp + hold);
    h.d.push_back(depth);
  }
  return h;
}

DisplacementHistory DisplacementHistory::cycles(double depth, double ramp, int cycles) {
  if (!(ramp > 0.0) || cycles < 1) throw Error("rig history: need a ramp time > 0 and at least one cycle");
  DisplacementHistory h{{0.0}, {0.0}};
  for (int c = 0; c < cycles; ++c) {
    h.t.push_back((2 * c + 1) * ramp);
    h.d.push_back(depth);
    h.t.push_back((2 * c + 2) * ramp);
    h.d.push_back(0.0);
  }
  return h;
}

double DisplacementHistory::peak() const {
  double p = 0.0;
  for (const double v : d) p = std::max(p, std::abs(v));
  return p;
}

void validate(const RigSpec& s) {
  const auto bad = [&](const std::string& field, const std::string& why) {
    throw Error("rig '" + s.name + "': " + field + ": " + why);
  };
  if (s.name.empty() ||
      s.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") !=
          std::string::npos) {
    bad("name", "use letters, digits, '_', '-' and '.' only");
  }
  const auto positive = [&](double v, const char* field) {
    if (!(v > 0.0) || !std::isfinite(v)) bad(field, "must be positive and finite");
  };
  positive(s.height, "height");
  if (s.shape == SampleShape::Block) {
    positive(s.size_x, "size_x");
    positive(s.size_y, "size_y");
  } else {
    positive(s.radius, "radius");
  }
  if (s.cells < 2 || s.cells > 400) bad("cells", "must be in [2, 400]");
  if (s.layers < 1 || s.layers > 400) bad("layers", "must be in [1, 400]");
  if (!(s.grading >= 1.0 && s.grading <= 4.0)) bad("grading", "must be in [1, 4]");
  if (s.steps_per_sample < 1) bad("steps_per_sample", "must be >= 1");
  const DisplacementHistory& h = s.history;
  if (h.t.size() != h.d.size() || h.t.size() < 2)
    bad("history", "needs at least two (time, displacement) samples");
  for (std::size_t k = 0; k < h.t.size(); ++k) {
    if (!std::isfinite(h.t[k]) || !std::isfinite(h.d[k]))
      bad("history", "sample " + std::to_string(k) + " is not finite");
    if (k > 0 && !(h.t[k] > h.t[k - 1]))
      bad("history", "times must increase strictly (sample " + std::to_string(k) + ")");
  }
  if (h.t.front() != 0.0 || h.d.front() != 0.0) bad("history", "must start at t = 0 with zero displacement");
  if (!(h.peak() > 0.0)) bad("history", "the displacement is zero throughout");
  if (h.peak() >= s.height) bad("history", "the displacement reaches the sample height");
  const double min_d = *std::min_element(h.d.begin(), h.d.end());
  const double max_d = *std::max_element(h.d.begin(), h.d.end());
  if (min_d < 0.0 && max_d > 0.0) bad("history", "mixes compression (d > 0) and tension (d < 0)");
  if (s.test == RigTest::UniaxialTension) {
    if (max_d > 0.0) bad("history", "a tension test pulls: the displacement must be <= 0");
    if (s.platens != Support::Bonded) bad("platens", "a tension test needs bonded (gripped) platens");
  } else if (min_d < 0.0) {
    bad("history", "a compression or indentation test pushes: the displacement must be >= 0");
  }
  if (s.test == RigTest::Indentation) {
    positive(s.indenter_radius, "indenter_radius");
    if (s.shape != SampleShape::Block) bad("shape", "indentation rigs use a block sample");
    const double half = 0.5 * std::min(s.size_x, s.size_y);
    if (std::abs(s.cx) + s.indenter_radius > 0.5 * s.size_x ||
        std::abs(s.cy) + s.indenter_radius > 0.5 * s.size_y) {
      bad("indenter_radius", "the indenter (radius " + std::to_string(s.indenter_radius) +
                                 " m at its position) reaches beyond the top face (half width " +
                                 std::to_string(half) + " m)");
    }
  }
}

Mesh rig_mesh(const RigSpec& s) {
  validate(s);
  if (s.shape == SampleShape::Cylinder) {
    CylinderSpec c;
    c.radius = s.radius;
    c.height = s.height;
    c.rings = std::max(1, s.cells / 2);
    c.layers = s.layers;
    return make_cylinder_mesh(c);
  }
  BlockSpec b;
  b.size_x = s.size_x;
  b.size_y = s.size_y;
  b.size_z = s.height;
  b.cx = s.cx;
  b.cy = s.cy;
  const double lateral = std::min(s.size_x, s.size_y);
  b.nx = std::max(2, static_cast<int>(std::lround(s.cells * s.size_x / lateral)));
  b.ny = std::max(2, static_cast<int>(std::lround(s.cells * s.size_y / lateral)));
  b.nz = s.layers;
  b.grading = s.test == RigTest::Indentation ? s.grading : 1.0;
  return make_block_mesh(b);
}

json rig_case(const RigSpec& s, const std::string& mesh_file) {
  validate(s);
  json c;
  c["name"] = s.name;
  c["description"] = rig_test_name(s.test) + " rig (tmlab rig)";
  c["model"] = s.model;
  c["mesh"] = {{"file", mesh_file}};
  c["material"] = s.material;
  c["boundary"] = s.test == RigTest::Indentation ? indentation_boundary(s) : platen_boundary(s);
  if (s.test == RigTest::Indentation) c["contact"] = {{"bodies", json::array({indenter_body(s)})}};
  // Uniform quasi-static steps, `steps_per_sample` across the shortest history segment (so the
  // kinks of a ramp-hold or cycle history fall on step ends).
  double shortest = s.history.t.back();
  for (std::size_t k = 1; k < s.history.t.size(); ++k)
    shortest = std::min(shortest, s.history.t[k] - s.history.t[k - 1]);
  const double steps_real = std::ceil(s.history.t.back() / shortest * s.steps_per_sample - 1e-9);
  if (steps_real > 1e6) throw Error("rig '" + s.name + "': the history needs more than 10^6 load steps");
  const int steps = static_cast<int>(steps_real);
  c["solver"] = {{"type", "static"}, {"t_end", s.history.t.back()}, {"steps", steps}};
  c["output"] = {{"vtu", false}, {"xdmf", true}, {"plots", true}};
  return c;
}

std::filesystem::path write_rig(const RigSpec& s, const std::filesystem::path& dir) {
  validate(s);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(dir.string() + ": cannot create the directory: " + ec.message());
  const std::filesystem::path mesh_path = dir / (s.name + ".msh");
  const std::filesystem::path case_path = dir / (s.name + ".json");
  const Mesh mesh = rig_mesh(s);
  const std::filesystem::path tmp = dir / (s.name + ".msh.tmp");
  write_gmsh22(mesh, tmp.string());
  std::filesystem::rename(tmp, mesh_path, ec);
  if (ec) throw Error(mesh_path.string() + ": cannot write the mesh: " + ec.message());
  write_file_atomically(case_path, rig_case(s, mesh_path.filename().string()).dump(2) + "\n");
  return case_path;
}

}  // namespace tmlab::rigs
