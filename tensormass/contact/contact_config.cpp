#include "tensormass/contact/contact_config.hpp"

#include "core/base/error.hpp"
#include "core/config/config_reader.hpp"

#include <cmath>
#include <set>

namespace tmlab::tm {

namespace {

Vec3 read_vec3(ConfigReader& r, const std::string& key) {
  const auto v = r.require<std::vector<double>>(key);
  if (v.size() != 3) throw r.error(key, "must be a list of 3 numbers");
  for (double x : v)
    if (!std::isfinite(x)) throw r.error(key, "must be finite");
  return Vec3(v[0], v[1], v[2]);
}

Vec3 read_direction(ConfigReader& r, const std::string& key) {
  const Vec3 v = read_vec3(r, key);
  if (!(v.norm() > 0.0)) throw r.error(key, "must be a non-zero vector");
  return v.normalized();
}

double read_nonnegative(ConfigReader& r, const std::string& key, double fallback) {
  const double v = r.get<double>(key, fallback);
  if (!std::isfinite(v) || v < 0.0) throw r.error(key, "must be a finite number >= 0");
  return v;
}

}  // namespace

std::vector<RigidBody> parse_contact_bodies(const nlohmann::json& bodies, const std::string& where,
                                            const std::string& path) {
  if (!bodies.is_array()) throw Error(where + ": key '" + path + "' must be a list of bodies");
  std::vector<RigidBody> out;
  std::set<std::string> names;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    ConfigReader r(bodies[i], where, path + "[" + std::to_string(i) + "]");
    RigidBody b;
    b.name = r.get<std::string>("name", "body" + std::to_string(i));
    if (b.name.empty()) throw r.error("name", "must not be empty");
    if (!names.insert(b.name).second) throw r.error("name", "'" + b.name + "' names two contact bodies");
    const std::string type = r.require<std::string>("type");
    const std::string mode = r.get<std::string>("mode", "frictionless");
    if (mode == "frictionless")
      b.mode = ContactMode::Frictionless;
    else if (mode == "bonded")
      b.mode = ContactMode::Bonded;
    else
      throw r.error("mode", "must be \"frictionless\" or \"bonded\" (got \"" + mode + "\")");
    b.displacement = r.has("displacement") ? read_vec3(r, "displacement") : Vec3::Zero();
    if (r.has("function"))
      b.function =
          TimeFunction::from_json(r.raw("function"), where + ": key '" + r.key_path("function") + "'");
    if (type == "sphere") {
      b.shape = RigidShape::Sphere;
      b.reference = read_vec3(r, "center");
      b.radius = r.positive("radius");
      // The axis only orients the contact-radius output; by default the direction of travel.
      if (r.has("axis"))
        b.axis = read_direction(r, "axis");
      else if (b.displacement.norm() > 0.0)
        b.axis = b.displacement.normalized();
      else
        b.axis = -Vec3::UnitZ();
    } else if (type == "punch") {
      b.shape = RigidShape::Punch;
      b.reference = read_vec3(r, "center");
      b.axis = read_direction(r, "axis");
      b.radius = r.positive("radius");
      b.edge_radius = read_nonnegative(r, "edge_radius", 0.0);
      if (b.edge_radius > b.radius) throw r.error("edge_radius", "must not exceed radius");
    } else if (type == "plane") {
      b.shape = RigidShape::Plane;
      b.reference = read_vec3(r, "point");
      b.axis = read_direction(r, "normal");
    } else {
      throw r.error("type", "must be \"sphere\", \"punch\" or \"plane\" (got \"" + type + "\")");
    }
    r.finish();
    b.validate();
    out.push_back(std::move(b));
  }
  return out;
}

ContactSettings parse_contact_section(const nlohmann::json& section, const std::string& where,
                                      const std::string& path) {
  ConfigReader r(section, where, path);
  ContactSettings s;
  const std::string method = r.get<std::string>("method", "augmented_lagrangian");
  if (method == "augmented_lagrangian")
    s.options.method = ContactMethod::AugmentedLagrangian;
  else if (method == "penalty")
    s.options.method = ContactMethod::Penalty;
  else
    throw r.error("method", "must be \"augmented_lagrangian\" or \"penalty\" (got \"" + method + "\")");
  s.options.stiffness_factor = r.positive("stiffness_factor", s.options.stiffness_factor);
  s.options.stiffness = read_nonnegative(r, "stiffness", 0.0);
  s.options.gap_tol = read_nonnegative(r, "gap_tol", 0.0);
  s.options.initial_gap_tol = read_nonnegative(r, "initial_gap_tol", 0.0);
  s.options.search_margin = read_nonnegative(r, "search_margin", 0.0);
  s.options.max_outer_iterations = r.get<int>("max_outer_iterations", s.options.max_outer_iterations);
  if (s.options.max_outer_iterations < 1) throw r.error("max_outer_iterations", "must be >= 1");
  if (!r.has("bodies")) throw r.error("bodies", "is required (a list of at least one body)");
  s.bodies = parse_contact_bodies(r.raw("bodies"), where, r.key_path("bodies"));
  if (s.bodies.empty()) throw r.error("bodies", "must list at least one body");
  r.finish();
  return s;
}

}  // namespace tmlab::tm
