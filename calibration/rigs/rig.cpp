// The test rigs as case files (rig.hpp explains the fixtures).
#include "calibration/rigs/rig.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/config/case_config.hpp"
#include "core/config/element_kind.hpp"
#include "core/constitutive/law_catalogue.hpp"
#include "core/io/atomic_file.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/sample_meshes.hpp"
#include "core/results/run_output.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>

#include <stdlib.h>
#include <unistd.h>

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
  json body = {{"name", "indenter"},
               {"mode", s.indenter_contact == Support::Bonded ? "bonded" : "frictionless"}};
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

namespace {

[[noreturn]] void refuse(const RigSpec& s, const std::string& field, const std::string& why) {
  throw Error("rig '" + s.name + "': " + field + ": " + why);
}

std::string mm(double metres) { return significant(1e3 * metres, 4) + " mm"; }

/// "12,345,678": counts in messages (beyond 10^18, "1.2e+22").
std::string grouped(double v) {
  if (!(v < 1e18)) return significant(v, 3);
  std::string d = std::to_string(static_cast<long long>(std::llround(v)));
  for (int i = static_cast<int>(d.size()) - 3; i > 0; i -= 3) d.insert(static_cast<std::size_t>(i), ",");
  return d;
}

std::string memory(double bytes) {
  return bytes >= 1e9 ? significant(bytes / 1e9, 3) + " GB" : significant(bytes / 1e6, 3) + " MB";
}

/// The shortest time between two samples of the history (at least two samples).
double shortest_segment(const DisplacementHistory& h) {
  double shortest = h.t.back();
  for (std::size_t k = 1; k < h.t.size(); ++k) shortest = std::min(shortest, h.t[k] - h.t[k - 1]);
  return shortest;
}

/// The explicit form's cells and layers, times the refinement (doubles: a far too large rig still has a
/// size).
double refined_count(int n, double refinement) { return std::max(1.0, std::round(n * refinement)); }

/// The block's cells per axis in the explicit form, as rig_mesh makes them.
std::array<double, 3> block_cells(const RigSpec& s) {
  const double lateral = std::min(s.size_x, s.size_y);
  const double cells = refined_count(s.cells, s.refinement);
  return {std::max(2.0, std::round(cells * s.size_x / lateral)),
          std::max(2.0, std::round(cells * s.size_y / lateral)), refined_count(s.layers, s.refinement)};
}

int cylinder_rings(const RigSpec& s) {
  return std::max(1, static_cast<int>(refined_count(s.cells, s.refinement)) / 2);
}

bool explicit_mesh(const RigSpec& s) { return s.cells > 0; }

/// The rule's fine spacing and fine zone width: indentation h_c = a_max / contact_cells within
/// contact_zone a_max; platen tests h_e = L / rim_cells within kRimZone L.
struct RuleScale {
  double h = 0.0, zone = 0.0;
};

double platen_length(const RigSpec& s) {
  const double lateral = s.shape == SampleShape::Cylinder ? s.radius : 0.5 * std::min(s.size_x, s.size_y);
  return std::min(lateral, 0.5 * s.height);
}

RuleScale rule_scale(const RigSpec& s) {
  if (s.test == RigTest::Indentation) {
    const double a = rig_contact_radius(s);
    return {a / s.contact_cells, s.contact_zone * a};
  }
  const double L = platen_length(s);
  return {L / s.rim_cells, kRimZone * L};
}

/// The rule's grid (validated arguments); `count_only`: the cell counts in grid[k][0] (no coordinates).
BoxGrid rule_grid(const RigSpec& s, bool count_only) {
  const RuleScale r = rule_scale(s);
  const double g = s.growth, ref = s.refinement;
  const auto one_sided = [&](double lo, double hi, double focus) {
    return count_only ? std::vector<double>{contact_graded_cells(lo, hi, focus, r.h, r.zone, g, ref)}
                      : contact_graded_coordinates(lo, hi, focus, r.h, r.zone, g, ref);
  };
  const auto two_sided = [&](double lo, double hi) {
    return count_only
               ? std::vector<double>{2.0 * contact_graded_cells(lo, 0.5 * (lo + hi), lo, r.h, r.zone, g, ref)}
               : two_sided_graded_coordinates(lo, hi, r.h, r.zone, g, ref);
  };
  const double hx = 0.5 * s.size_x, hy = 0.5 * s.size_y;
  if (s.test == RigTest::Indentation)
    return {one_sided(-hx, hx, s.cx), one_sided(-hy, hy, s.cy), one_sided(0.0, s.height, s.height)};
  if (s.shape == SampleShape::Cylinder)
    return {one_sided(0.0, s.radius, s.radius), {}, two_sided(0.0, s.height)};
  return {two_sided(-hx, hx), two_sided(-hy, hy), two_sided(0.0, s.height)};
}

void validate_sample(const RigSpec& s) {
  const auto positive = [&](double v, const char* field) {
    if (!(v > 0.0) || !std::isfinite(v)) refuse(s, field, "must be positive and finite");
  };
  positive(s.height, "height");
  if (s.shape == SampleShape::Block) {
    positive(s.size_x, "size_x");
    positive(s.size_y, "size_y");
  } else {
    positive(s.radius, "radius");
  }
  if (!std::isfinite(s.cx) || !std::isfinite(s.cy))
    refuse(s, "--at (the indenter centre cx, cy)", "must be two finite numbers, m");
  if (s.shape == SampleShape::Block && (std::abs(s.cx) > 0.5 * s.size_x || std::abs(s.cy) > 0.5 * s.size_y))
    refuse(s, "--at (the indenter centre cx, cy)",
           "(" + mm(s.cx) + ", " + mm(s.cy) + ") lies outside the top face, x in +-" + mm(0.5 * s.size_x) +
               " and y in +-" + mm(0.5 * s.size_y) +
               " (the sample is centred on x = y = 0; --at is in metres)");
}

void validate_indenter(const RigSpec& s) {
  if (!(s.indenter_radius > 0.0) || !std::isfinite(s.indenter_radius))
    refuse(s, "indenter_radius", "must be positive and finite");
  if (s.shape != SampleShape::Block) refuse(s, "shape", "indentation rigs use a block sample");
  const double hx = 0.5 * s.size_x, hy = 0.5 * s.size_y, r = s.indenter_radius;
  if (std::abs(s.cx) + r <= hx && std::abs(s.cy) + r <= hy) return;
  if (r > hx || r > hy)
    refuse(s, "indenter_radius",
           "the indenter (radius " + mm(r) + ") is wider than the top face (half widths " + mm(hx) + ", " +
               mm(hy) + ")");
  refuse(s, "--at (the indenter centre cx, cy)",
         "(" + mm(s.cx) + ", " + mm(s.cy) +
             ") is too close to the edge of the top face for the indenter radius " + mm(r) +
             ": the indenter reaches beyond the face (|cx| + radius must stay within " + mm(hx) +
             " and |cy| + radius within " + mm(hy) + ")");
}

void validate_history(const RigSpec& s) {
  const DisplacementHistory& h = s.history;
  if (h.t.size() != h.d.size() || h.t.size() < 2)
    refuse(s, "history", "needs at least two (time, displacement) samples");
  for (std::size_t k = 0; k < h.t.size(); ++k) {
    if (!std::isfinite(h.t[k]) || !std::isfinite(h.d[k]))
      refuse(s, "history", "sample " + std::to_string(k) + " is not finite");
    if (k > 0 && !(h.t[k] > h.t[k - 1]))
      refuse(s, "history", "times must increase strictly (sample " + std::to_string(k) + ")");
  }
  if (h.t.front() != 0.0 || h.d.front() != 0.0)
    refuse(s, "history", "must start at t = 0 with zero displacement");
  if (!(h.peak() > 0.0)) refuse(s, "history", "the displacement is zero throughout");
  if (h.peak() >= s.height) refuse(s, "history", "the displacement reaches the sample height");
  const double min_d = *std::min_element(h.d.begin(), h.d.end());
  const double max_d = *std::max_element(h.d.begin(), h.d.end());
  if (min_d < 0.0 && max_d > 0.0) refuse(s, "history", "mixes compression (d > 0) and tension (d < 0)");
  if (s.test == RigTest::UniaxialTension) {
    if (max_d > 0.0) refuse(s, "history", "a tension test pulls: the displacement must be <= 0");
    if (s.platens != Support::Bonded) refuse(s, "platens", "a tension test needs bonded (gripped) platens");
  } else if (min_d < 0.0) {
    refuse(s, "history", "a compression or indentation test pushes: the displacement must be >= 0");
  }
  if (s.steps_per_sample < 1 || s.steps_per_sample > kMaxLoadSteps)
    refuse(s, "steps_per_segment", "must be in [1, " + grouped(kMaxLoadSteps) + "]");
  const double steps = rig_load_steps(s);
  if (steps > kMaxLoadSteps)
    refuse(s, "steps_per_segment",
           std::to_string(s.steps_per_sample) + " steps across the shortest segment of the history (" +
               significant(shortest_segment(h), 6) + " s), at that step over all its " +
               significant(h.t.back(), 6) + " s, make " + grouped(steps) + " load steps; the limit is " +
               grouped(kMaxLoadSteps) + " (a static run of more would take days): give fewer");
}

/// The contact rule's own fields (checked whatever the form: a bad value is never silently ignored).
void validate_rule(const RigSpec& s) {
  const auto count = [&](int v, const char* field) {
    if (v < 1 || v > kMaxContactCells)
      refuse(s, field,
             "must be in [1, " + std::to_string(kMaxContactCells) + "] (got " + std::to_string(v) + ")");
  };
  count(s.contact_cells, "contact_cells");
  count(s.rim_cells, "rim_cells");
  const auto range = [&](double v, double lo, double hi, const char* field, const char* what) {
    if (!(v >= lo && v <= hi))
      refuse(
          s, field,
          std::string("must be in [") + significant(lo, 4) + ", " + significant(hi, 4) + "] (" + what + ")");
  };
  range(s.contact_zone, 0.5, 10.0, "contact_zone", "the fine zone's half width in contact radii");
  range(s.growth, 1.0, 2.0, "growth", "the largest ratio of neighbouring cells");
  if (!(s.refinement > 0.0 && s.refinement <= kMaxRefinement))
    refuse(s, "refinement",
           "must be in (0, " + significant(kMaxRefinement, 4) + "] (it multiplies every cell count)");
}

/// The mesh's size before it is generated, against kMaxRigTets.
void validate_mesh_size(const RigSpec& s) {
  validate_rule(s);
  const bool expl = explicit_mesh(s);
  if (expl) {
    if (s.cells < kMinCells || s.cells > kMaxCells)
      refuse(s, "cells", "must be in [" + std::to_string(kMinCells) + ", " + std::to_string(kMaxCells) + "]");
    if (s.layers < 1 || s.layers > kMaxLayers)
      refuse(
          s, "layers",
          "must be in [1, " + std::to_string(kMaxLayers) + "] (the explicit mesh form: give it with cells)");
    if (!(s.grading >= 1.0 && s.grading <= 4.0)) refuse(s, "grading", "must be in [1, 4]");
  } else if (s.layers != 0) {
    refuse(s, "layers", "goes with cells (the explicit mesh form); the contact rule sets the layers itself");
  }
  SampleMeshSize size;
  std::string formula, fields;
  const std::string refinement = s.refinement != 1.0 ? " at refinement " + significant(s.refinement, 6) : "";
  if (expl) {
    fields = "cells, layers";
    if (s.shape == SampleShape::Block) {
      const auto n = block_cells(s);
      size = block_mesh_size(n[0], n[1], n[2]);
      formula = "cells " + std::to_string(s.cells) + " and layers " + std::to_string(s.layers) + refinement +
                " give a block of " + grouped(n[0]) + " x " + grouped(n[1]) + " x " + grouped(n[2]) +
                " cells (cells across the smaller side, scaled to the other; layers through the height), 6 "
                "tets each";
    } else {
      const double layers = refined_count(s.layers, s.refinement);
      size = cylinder_mesh_size(cylinder_rings(s), layers);
      formula = "cells " + std::to_string(s.cells) + " and layers " + std::to_string(s.layers) + refinement +
                " give a cylinder of " + std::to_string(cylinder_rings(s)) + " rings (cells / 2) and " +
                grouped(layers) + " layers, 18 rings^2 tets per layer";
    }
  } else {
    // The rule's counts, from the 1-D plans (nothing is allocated).
    if (s.test == RigTest::Indentation) {
      fields = "contact_cells, contact_zone, growth, refinement";
      formula = "contact_cells " + std::to_string(s.contact_cells) + " (h = " + mm(rule_scale(s).h) +
                " across a_max = " + mm(rig_contact_radius(s)) + ")";
    } else {
      fields = "rim_cells, growth, refinement";
      formula = "rim_cells " + std::to_string(s.rim_cells) + " (h = " + mm(rule_scale(s).h) + ")";
    }
    const BoxGrid n = rule_grid(s, true);
    if (s.shape == SampleShape::Block || s.test == RigTest::Indentation) {
      size = block_mesh_size(n[0][0], n[1][0], n[2][0]);
      formula += refinement + " give a block of " + grouped(n[0][0]) + " x " + grouped(n[1][0]) + " x " +
                 grouped(n[2][0]) + " cells, 6 tets each";
    } else {
      size = cylinder_mesh_size(n[0][0], n[2][0]);
      formula += refinement + " give a cylinder of " + grouped(n[0][0]) + " rings and " + grouped(n[2][0]) +
                 " layers, 18 rings^2 tets per layer";
    }
    if (std::max({n[0][0], s.test == RigTest::Indentation || s.shape == SampleShape::Block ? n[1][0] : 0.0,
                  n[2][0]}) > kMaxGradedCells)
      size.tets = std::max(size.tets, 2.0 * kMaxRigTets);  // beyond the generator's axis limit
  }
  if (size.tets <= kMaxRigTets) return;
  refuse(s, fields,
         formula + ": " + grouped(size.nodes) + " nodes and " + grouped(size.tets) + " tets (about " +
             memory(size.generator_bytes() + size.gmsh_bytes()) + " of memory to generate and a " +
             memory(size.gmsh_bytes()) + " mesh file); the limit is " + grouped(kMaxRigTets) +
             " tets (the largest mesh tmlab's benchmarks run is 2.4M tets, and a static contact run "
             "costs far more per tet): " +
             (expl ? std::string("give fewer cells or layers")
                   : std::string("give fewer ") +
                         (s.test == RigTest::Indentation ? "contact_cells" : "rim_cells") +
                         ", a larger growth or a smaller refinement"));
}

/// The material section and the model as `tmlab run` reads them (core/config's case-file parser),
/// and the law-model pairing the runner accepts (runner/: St VK models run St VK only).
void validate_material(const RigSpec& s) {
  const std::optional<CaseModel> model = case_model_from_string(s.model);
  if (!model)
    refuse(s, "model",
           "must be 'tensor_mass', 'tl_oracle' or 'hyperelastic_tl' (got '" + printable(s.model, 40) + "')");
  const MaterialSpec m = parse_material_section(s.material, "rig '" + s.name + "'");
  if (!law_descriptor(m.law).tensor_mass && *model != CaseModel::HyperelasticTL)
    refuse(s, "model",
           "'" + s.model + "' runs St Venant-Kirchhoff only; material.law '" + to_string(m.law) +
               "' runs on the F-based kernel: use model hyperelastic_tl (--model hyperelastic_tl)");
  const std::optional<ElementKind> element = element_kind_from_string(s.element);
  if (!element)
    refuse(s, "element (--element)",
           "must be " + choice_list(element_kind_names()) + " (got '" + printable(s.element, 40) + "')");
  // The runner's element checks (core/config/element_kind.hpp) on the case this rig writes.
  CaseConfig c;
  c.file = "rig '" + s.name + "'";
  c.mesh.element = *element;
  c.material = m;
  c.contact.enabled = s.test == RigTest::Indentation;
  check_element_support(c, *model);
}

}  // namespace

double rig_load_steps(const RigSpec& s) {
  const DisplacementHistory& h = s.history;
  if (h.t.size() < 2) return 0.0;
  return std::ceil(h.t.back() / shortest_segment(h) * s.steps_per_sample - 1e-9);
}

void validate(const RigSpec& s) {
  if (const std::string problem = result_name_problem(s.name); !problem.empty())
    refuse(s, "name", problem + " (it names the case and its result directory)");
  validate_sample(s);
  // The explicit form's size first (as ever); the contact rule's after the history and the indenter,
  // which set its scale.
  if (explicit_mesh(s)) validate_mesh_size(s);
  validate_history(s);
  if (s.test == RigTest::Indentation) validate_indenter(s);
  if (!explicit_mesh(s)) validate_mesh_size(s);
  validate_material(s);
}

double rig_contact_radius(const RigSpec& s) {
  const double r = s.indenter_radius;
  return s.indenter == IndenterShape::Sphere ? std::min(r, std::sqrt(r * s.history.peak())) : r;
}

RigSpec refined(const RigSpec& s, double ratio) {
  if (!(ratio > 0.0) || !std::isfinite(ratio))
    throw Error("rig '" + s.name + "': refined: the ratio must be positive and finite (got " +
                significant(ratio, 6) + ")");
  RigSpec r = s;
  r.refinement = s.refinement * ratio;
  return r;
}

BoxGrid rig_grid(const RigSpec& s) {
  validate(s);
  if (!explicit_mesh(s)) return rule_grid(s, false);
  if (s.shape == SampleShape::Cylinder) {
    const int rings = cylinder_rings(s), layers = static_cast<int>(refined_count(s.layers, s.refinement));
    BoxGrid g;
    for (int k = 0; k <= rings; ++k) g[0].push_back(k == rings ? s.radius : s.radius * k / rings);
    for (int l = 0; l <= layers; ++l) g[2].push_back(l == layers ? s.height : s.height * l / layers);
    return g;
  }
  const auto n = block_cells(s);
  const double power = s.test == RigTest::Indentation ? s.grading : 1.0;
  return {graded_coordinates(-0.5 * s.size_x, 0.5 * s.size_x, static_cast<int>(n[0]), s.cx, power),
          graded_coordinates(-0.5 * s.size_y, 0.5 * s.size_y, static_cast<int>(n[1]), s.cy, power),
          graded_coordinates(0.0, s.height, static_cast<int>(n[2]), s.height, power)};
}

Mesh rig_mesh(const RigSpec& s) {
  BoxGrid g = rig_grid(s);
  if (s.shape == SampleShape::Cylinder) {
    CylinderSpec c;
    c.radius = s.radius;
    c.height = s.height;
    c.rings = static_cast<int>(g[0].size()) - 1;
    c.layers = static_cast<int>(g[2].size()) - 1;
    if (!explicit_mesh(s)) {  // the explicit form's uniform cylinder stays the generator's own
      c.ring_radii = std::move(g[0]);
      c.layer_z = std::move(g[2]);
    }
    return make_cylinder_mesh(c);
  }
  return make_block_mesh(g);
}

json rig_case(const RigSpec& s, const std::string& mesh_file) {
  validate(s);
  json c;
  c["name"] = s.name;
  c["description"] = rig_test_name(s.test) + " rig (tmlab rig)";
  c["model"] = s.model;
  c["mesh"] = {{"file", mesh_file}};
  if (s.element != "p1") c["mesh"]["element"] = s.element;  // p1: the case as before (the default)
  c["material"] = s.material;
  c["boundary"] = s.test == RigTest::Indentation ? indentation_boundary(s) : platen_boundary(s);
  if (s.test == RigTest::Indentation) c["contact"] = {{"bodies", json::array({indenter_body(s)})}};
  // Uniform quasi-static steps, `steps_per_sample` across the shortest history segment (so the
  // kinks of a ramp-hold or cycle history fall on step ends).
  const int steps = static_cast<int>(rig_load_steps(s));  // <= kMaxLoadSteps (validate)
  c["solver"] = {{"type", "static"}, {"t_end", s.history.t.back()}, {"steps", steps}};
  c["output"] = {{"vtu", false}, {"xdmf", true}, {"plots", true}};
  return c;
}

namespace {

namespace fs = std::filesystem;

/// Refuses an output that is one of the inputs (always) or that exists (unless overwrite), naming it.
void check_output(const RigSpec& s, const fs::path& out, const RigWriteOptions& opt) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(out, ec);
  if (ec || !fs::exists(st)) return;
  for (const fs::path& in : opt.inputs)
    if (fs::equivalent(in, out, ec))
      throw Error("rig '" + s.name + "': " + out.string() + " is the input " + in.string() +
                  ": a rig never writes over its input; choose another --name or --out");
  if (!opt.overwrite)
    throw Error("rig '" + s.name + "': " + out.string() +
                " already exists: choose another --name or --out, or give --overwrite to replace " + s.name +
                ".json and " + s.name + ".msh");
  if (fs::is_directory(st)) throw Error("rig '" + s.name + "': " + out.string() + " is a directory");
}

}  // namespace

fs::path write_rig(const RigSpec& s, const fs::path& dir, const RigWriteOptions& opt) {
  validate(s);
  const fs::path mesh_path = dir / (s.name + ".msh");
  const fs::path case_path = dir / (s.name + ".json");
  for (const fs::path& out : {mesh_path, case_path}) check_output(s, out, opt);
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw Error(dir.string() + ": not a directory (the rig's NAME.json and NAME.msh go into --out)");
  // Everything is known to be writable in principle: build both in memory, then write.
  const Mesh mesh = rig_mesh(s);
  const std::string case_text = rig_case(s, mesh_path.filename().string()).dump(2) + "\n";
  fs::create_directories(dir, ec);
  if (ec) throw Error(dir.string() + ": cannot create the directory: " + ec.message());
  // A fresh temporary (created exclusively): never a file that was there.
  std::string tmpl = (dir / (s.name + ".msh.tmpXXXXXX")).string();
  const int fd = ::mkstemp(tmpl.data());
  if (fd < 0) throw Error(mesh_path.string() + ": cannot write the mesh: " + std::strerror(errno));
  ::close(fd);
  const fs::path tmp = tmpl;
  try {
    write_gmsh22(mesh, tmp.string());
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  try {
    write_file_atomically(case_path, case_text);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, mesh_path, ec);
  if (ec) throw Error(mesh_path.string() + ": cannot write the mesh: " + ec.message());
  return case_path;
}

}  // namespace tmlab::rigs
