#include "core/config/contact_spec.hpp"

#include "core/base/enum_names.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/config/config_reader.hpp"

#include <cmath>
#include <set>

namespace tmlab {

namespace {

// Names in declaration order of the enums.
const char* const kShapeNames[] = {"sphere", "punch", "plane"};
const char* const kModeNames[] = {"frictionless", "bonded"};
const char* const kMethodNames[] = {"augmented_lagrangian", "penalty"};

Vec3 read_direction(ConfigReader& r, const std::string& key) {
  const Vec3 v = r.vec3(key);
  if (!(v.norm() > 0.0)) throw r.error(key, "must be a non-zero vector");
  return v.normalized();
}

double read_nonnegative(ConfigReader& r, const std::string& key, double fallback) {
  const double v = r.get<double>(key, fallback);
  if (!std::isfinite(v) || v < 0.0) throw r.error(key, "must be a finite number >= 0");
  return v;
}

double read_positive(ConfigReader& r, const std::string& key) {
  const double v = r.positive(key);
  if (!std::isfinite(v)) throw r.error(key, "must be finite");
  return v;
}

template <class E, std::size_t N>
E read_choice(ConfigReader& r, const std::string& key, E fallback, const char* const (&names)[N]) {
  if (!r.has(key)) return fallback;
  const std::string name = r.require<std::string>(key);
  if (const std::optional<E> value = enum_from_name<E>(names, name)) return *value;
  throw r.error(key, "must be " + choice_list(enum_names(names)) + " (got '" + name + "')");
}

ContactBodySpec parse_body(const nlohmann::json& j, const std::string& where, const std::string& key,
                           std::size_t i) {
  ConfigReader r(j, where, key);
  ContactBodySpec b;
  b.key = key;
  b.name = r.get<std::string>("name", "body" + std::to_string(i));
  if (b.name.empty()) throw r.error("name", "must not be empty");
  if (!r.has("type")) throw r.error("type", "is required (" + choice_list(enum_names(kShapeNames)) + ")");
  b.shape = read_choice(r, "type", ContactShape::Plane, kShapeNames);
  b.mode = read_choice(r, "mode", ContactBodyMode::Frictionless, kModeNames);
  b.displacement = r.has("displacement") ? r.vec3("displacement") : Vec3::Zero();
  if (r.has("function"))
    b.function = TimeFunction::from_json(r.raw("function"), where + ": key '" + r.key_path("function") + "'");
  switch (b.shape) {
    case ContactShape::Sphere:
      b.reference = r.vec3("center");
      b.radius = read_positive(r, "radius");
      // The axis only orients the contact-radius output; by default the direction of travel.
      if (r.has("axis"))
        b.axis = read_direction(r, "axis");
      else if (b.displacement.norm() > 0.0)
        b.axis = b.displacement.normalized();
      else
        b.axis = -Vec3::UnitZ();
      break;
    case ContactShape::Punch:
      b.reference = r.vec3("center");
      b.axis = read_direction(r, "axis");
      b.radius = read_positive(r, "radius");
      b.edge_radius = read_nonnegative(r, "edge_radius", 0.0);
      if (b.edge_radius > b.radius) throw r.error("edge_radius", "must not exceed radius");
      break;
    case ContactShape::Plane:
      b.reference = r.vec3("point");
      b.axis = read_direction(r, "normal");
      break;
  }
  r.finish();
  return b;
}

nlohmann::json v3(const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

}  // namespace

std::string to_string(ContactShape s) { return enum_name(kShapeNames, s); }
std::string to_string(ContactBodyMode m) { return enum_name(kModeNames, m); }
std::string to_string(ContactEnforcement m) { return enum_name(kMethodNames, m); }
std::optional<ContactShape> contact_shape_from_string(const std::string& name) {
  return enum_from_name<ContactShape>(kShapeNames, name);
}
std::optional<ContactBodyMode> contact_body_mode_from_string(const std::string& name) {
  return enum_from_name<ContactBodyMode>(kModeNames, name);
}
std::optional<ContactEnforcement> contact_enforcement_from_string(const std::string& name) {
  return enum_from_name<ContactEnforcement>(kMethodNames, name);
}

ContactSpec parse_contact_spec(const nlohmann::json& section, const std::string& where,
                               const std::string& path) {
  if (!section.is_object()) throw Error(where + ": key '" + path + "' must be an object");
  ConfigReader r(section, where, path);
  ContactSpec s;
  s.enabled = true;
  s.method = read_choice(r, "method", ContactEnforcement::AugmentedLagrangian, kMethodNames);
  s.stiffness_factor = r.positive("stiffness_factor", s.stiffness_factor);
  if (!std::isfinite(s.stiffness_factor)) throw r.error("stiffness_factor", "must be finite");
  s.stiffness = read_nonnegative(r, "stiffness", 0.0);
  s.gap_tol = read_nonnegative(r, "gap_tol", 0.0);
  s.initial_gap_tol = read_nonnegative(r, "initial_gap_tol", 0.0);
  s.max_initial_gap = read_nonnegative(r, "max_initial_gap", 0.0);
  s.search_margin = read_nonnegative(r, "search_margin", 0.0);
  s.max_outer_iterations = r.get<int>("max_outer_iterations", s.max_outer_iterations);
  if (s.max_outer_iterations < 1) throw r.error("max_outer_iterations", "must be >= 1");
  if (!r.has("bodies")) throw r.error("bodies", "is required (a list of at least one body)");
  const nlohmann::json& bodies = r.raw("bodies");
  if (!bodies.is_array() || bodies.empty()) throw r.error("bodies", "must be a list of at least one body");
  std::set<std::string> names;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const std::string key = r.key_path("bodies") + "[" + std::to_string(i) + "]";
    ContactBodySpec b = parse_body(bodies[i], where, key, i);
    if (!names.insert(b.name).second)
      throw Error(where + ": key '" + key + ".name': '" + b.name + "' names two contact bodies");
    s.bodies.push_back(std::move(b));
  }
  r.finish();
  return s;
}

nlohmann::json contact_spec_json(const ContactSpec& s) {
  using nlohmann::json;
  json bodies = json::array();
  for (const ContactBodySpec& b : s.bodies) {
    json j = {{"name", b.name},
              {"type", to_string(b.shape)},
              {"mode", to_string(b.mode)},
              {"displacement", v3(b.displacement)},
              {"function", b.function.to_json()}};
    switch (b.shape) {
      case ContactShape::Sphere:
        j["center"] = v3(b.reference), j["radius"] = b.radius, j["axis"] = v3(b.axis);
        break;
      case ContactShape::Punch:
        j["center"] = v3(b.reference), j["axis"] = v3(b.axis), j["radius"] = b.radius;
        j["edge_radius"] = b.edge_radius;
        break;
      case ContactShape::Plane:
        j["point"] = v3(b.reference), j["normal"] = v3(b.axis);
        break;
    }
    bodies.push_back(j);
  }
  return {{"method", to_string(s.method)},
          {"stiffness_factor", s.stiffness_factor},
          {"stiffness", s.stiffness},
          {"gap_tol", s.gap_tol},
          {"initial_gap_tol", s.initial_gap_tol},
          {"max_initial_gap", s.max_initial_gap},
          {"search_margin", s.search_margin},
          {"max_outer_iterations", s.max_outer_iterations},
          {"bodies", bodies}};
}

}  // namespace tmlab
