#include "tensormass/contact/contact_config.hpp"

#include "core/base/error.hpp"

namespace tmlab::tm {

namespace {

RigidBody rigid_body(const ContactBodySpec& s, const std::string& where) {
  RigidBody b;
  static_cast<ContactBodySpec&>(b) = s;
  b.origin = where + ": key '" + s.key + "'";
  b.validate();
  return b;
}

}  // namespace

ContactSettings contact_settings(const ContactSpec& spec, const std::string& where) {
  ContactSettings s;
  s.options.method = spec.method == ContactEnforcement::Penalty ? ContactMethod::Penalty
                                                                : ContactMethod::AugmentedLagrangian;
  s.options.stiffness_factor = spec.stiffness_factor;
  s.options.stiffness = spec.stiffness;
  s.options.gap_tol = spec.gap_tol;
  s.options.initial_gap_tol = spec.initial_gap_tol;
  s.options.max_initial_gap = spec.max_initial_gap;
  s.options.search_margin = spec.search_margin;
  s.options.max_outer_iterations = spec.max_outer_iterations;
  for (const ContactBodySpec& b : spec.bodies) {
    s.bodies.push_back(rigid_body(b, where));
    s.keys.push_back(b.key);
  }
  return s;
}

ContactSettings parse_contact_section(const nlohmann::json& section, const std::string& where,
                                      const std::string& path) {
  return contact_settings(parse_contact_spec(section, where, path), where);
}

}  // namespace tmlab::tm
