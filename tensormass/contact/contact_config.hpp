// The case file's `contact` section in the contact module's terms. The section itself is parsed
// into the model-agnostic ContactSpec by core/config (contact_spec.hpp), which the deal.II reference
// reads too; contact_settings() converts that spec into the RigidBody list and ContactOptions of
// the fast model's contact solver (docs/contact.md).
#pragma once

#include "core/config/contact_spec.hpp"
#include "tensormass/contact/contact_solver.hpp"
#include "tensormass/contact/rigid_body.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tmlab::tm {

struct ContactSettings {
  ContactOptions options;
  std::vector<RigidBody> bodies;
  std::vector<std::string> keys;  ///< each body's case-file key ("contact.bodies[0]"), for messages
};

/// The bodies and options of a parsed spec (validated again by RigidBody::validate()); each body's
/// origin is "<where>: key '<its key>'" for messages.
ContactSettings contact_settings(const ContactSpec& spec, const std::string& where);

/// parse_contact_spec + contact_settings: the section at key `path` of file `where`. Errors name
/// the file and the key.
ContactSettings parse_contact_section(const nlohmann::json& section, const std::string& where,
                                      const std::string& path = "contact");

}  // namespace tmlab::tm
