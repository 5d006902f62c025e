#include "rig_options.hpp"

#include "cli_args.hpp"

#include "core/base/error.hpp"

#include <cmath>

namespace tmlab::cli {

namespace {

// The sample, fixture and mesh options.
void apply_geometry(const ParsedOptions& p, rigs::RigSpec& s) {
  if (p.given("--shape")) s.shape = rigs::parse_sample_shape(p.text("--shape"), "--shape");
  if (p.given("--size")) {
    const auto v = p.numbers("--size");
    s.size_x = v[0];
    s.size_y = v[1];
    s.height = v[2];
  }
  p.assign_if_given("--radius", s.radius);
  p.assign_if_given("--height", s.height);
  if (p.given("--indenter")) s.indenter = rigs::parse_indenter_shape(p.text("--indenter"), "--indenter");
  p.assign_if_given("--indenter-radius", s.indenter_radius);
  if (p.given("--at")) {
    const auto v = p.numbers("--at");
    s.cx = v[0];
    s.cy = v[1];
  }
  if (p.given("--bottom")) s.bottom = rigs::parse_support(p.text("--bottom"), "--bottom");
  if (p.given("--platens")) s.platens = rigs::parse_support(p.text("--platens"), "--platens");
  if (p.given("--indenter-contact")) {
    if (s.test != rigs::RigTest::Indentation)
      throw UsageError("--indenter-contact goes with an indentation rig");
    s.indenter_contact = rigs::parse_support(p.text("--indenter-contact"), "--indenter-contact");
  }
  // The explicit form's defaults: the earlier rig meshes (indentation 16 x 8 graded; platens 8 x 10).
  const bool indentation = s.test == rigs::RigTest::Indentation;
  apply_resolution(p, s, indentation ? 16 : 8, indentation ? 8 : 10);
}

// The displacement history.
void apply_loading(const ParsedOptions& p, rigs::RigSpec& s) {
  const bool tension = s.test == rigs::RigTest::UniaxialTension;
  double depth = 0.1 * s.height, ramp = 1.0, hold = 0.0;
  p.assign_if_given("--depth", depth);
  p.assign_if_given("--ramp", ramp);
  p.assign_if_given("--hold", hold);
  const double signed_depth = tension ? -std::abs(depth) : depth;
  if (p.given("--cycles")) {
    s.history = rigs::DisplacementHistory::cycles(signed_depth, ramp, static_cast<int>(p.whole("--cycles")));
  } else {
    s.history = rigs::DisplacementHistory::ramp_hold(signed_depth, ramp, hold);
  }
}

const char* const kRigOptions[] = {"--shape",
                                   "--size",
                                   "--radius",
                                   "--height",
                                   "--indenter",
                                   "--indenter-radius",
                                   "--at",
                                   "--bottom",
                                   "--platens",
                                   "--indenter-contact",
                                   "--depth",
                                   "--ramp",
                                   "--hold",
                                   "--cycles",
                                   "--cells",
                                   "--layers",
                                   "--grading",
                                   "--contact-cells",
                                   "--rim-cells",
                                   "--refine",
                                   "--steps-per-segment",
                                   "--material",
                                   "--E",
                                   "--nu",
                                   "--density",
                                   "--model",
                                   "--element"};

}  // namespace

bool explicit_mesh_given(const ParsedOptions& p) {
  const bool expl = p.given("--cells") || p.given("--layers") || p.given("--grading");
  for (const char* rule : {"--contact-cells", "--rim-cells"})
    if (expl && p.given(rule))
      throw UsageError(std::string(rule) +
                       " (the contact rule) does not go with --cells, --layers, --grading (the explicit "
                       "mesh form): give one or the other");
  return expl;
}

void apply_resolution(const ParsedOptions& p, rigs::RigSpec& s, int cells0, int layers0) {
  if (explicit_mesh_given(p)) {
    s.cells = cells0;
    s.layers = layers0;
    p.assign_if_given("--cells", s.cells);
    p.assign_if_given("--layers", s.layers);
    p.assign_if_given("--grading", s.grading);
  }
  p.assign_if_given("--contact-cells", s.contact_cells);
  p.assign_if_given("--rim-cells", s.rim_cells);
  p.assign_if_given("--refine", s.refinement);
  p.assign_if_given("--steps-per-segment", s.steps_per_sample);
}

rigs::RigTest rig_test(const std::string& name) {
  if (name == "unconfined") return rigs::RigTest::UnconfinedCompression;
  if (name == "confined") return rigs::RigTest::ConfinedCompression;
  if (name == "tension") return rigs::RigTest::UniaxialTension;
  try {
    return rigs::parse_rig_test(name, "rig test");
  } catch (const Error& e) {
    throw UsageError(std::string(e.what()) + "; short forms: unconfined, confined, tension");
  }
}

bool is_rig_test(const std::string& name) {
  if (name == "unconfined" || name == "confined" || name == "tension") return true;
  try {
    rigs::parse_rig_test(name, "rig test");
    return true;
  } catch (const Error&) {
    return false;
  }
}

void apply_material(const ParsedOptions& p, rigs::RigSpec& s) {
  if (p.given("--model")) s.model = p.text("--model");
  if (p.given("--element")) {
    s.element = p.text("--element");
    // The elements other than p1 run on the F-based kernel only: its model unless one is named.
    if (s.element != "p1" && !p.given("--model")) s.model = "hyperelastic_tl";
  }
  if (p.given("--material")) {
    try {
      s.material = nlohmann::json::parse(p.text("--material"));
    } catch (const nlohmann::json::exception& e) {
      throw UsageError(std::string("--material is not valid JSON: ") + e.what());
    }
    if (!s.material.is_object())
      throw UsageError("--material must be a JSON object (the case file's material section)");
  }
  for (const char* key : {"E", "nu", "density"}) {
    const std::string opt = std::string("--") + key;
    if (p.given(opt)) s.material[key] = p.decimal(opt);
  }
}

rigs::RigSpec rig_from_options(const ParsedOptions& p, rigs::RigTest test, const std::string& name) {
  rigs::RigSpec s;
  s.test = test;
  s.name = name;
  if (s.test != rigs::RigTest::Indentation) {
    // Platen tests default to the phantom geometry (a 50 mm x 30 mm cylinder); tension is gripped.
    s.shape = rigs::SampleShape::Cylinder;
    s.height = 0.03;
    if (s.test == rigs::RigTest::UniaxialTension) s.platens = rigs::Support::Bonded;
  }
  apply_geometry(p, s);
  apply_loading(p, s);
  apply_material(p, s);
  return s;
}

std::string first_rig_option_given(const ParsedOptions& p) {
  for (const char* o : kRigOptions)
    if (p.spec().find(o) != nullptr && p.given(o)) return o;
  return "";
}

}  // namespace tmlab::cli
