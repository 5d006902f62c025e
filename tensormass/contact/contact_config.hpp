// The `contact` section of a case file (docs/contact.md), parsed and validated into the plain
// structs of the contact module. The case-file parser calls parse_contact_section() on the section;
// errors name the file and the full key ("case.json: key 'contact.bodies[1].radius': must be > 0").
//
//   "contact": {
//     "method": "augmented_lagrangian" | "penalty",      (default augmented_lagrangian)
//     "stiffness_factor": 100, "stiffness": 0,            (eps; see ContactOptions)
//     "gap_tol": 0, "initial_gap_tol": 0, "search_margin": 0, "max_outer_iterations": 30,
//     "bodies": [
//       {"name": "indenter", "type": "sphere", "center": [x,y,z], "radius": R, "axis": [0,0,-1],
//        "mode": "frictionless" | "bonded", "displacement": [dx,dy,dz], "function": {time function}},
//       {"type": "punch", "center": [..] (face centre), "axis": [..] (into the sample), "radius": R,
//        "edge_radius": 0, ...},
//       {"type": "plane", "point": [..], "normal": [..] (towards the sample), ...}
//     ]
//   }
#pragma once

#include "tensormass/contact/contact_solver.hpp"
#include "tensormass/contact/rigid_body.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tmlab::tm {

struct ContactSettings {
  ContactOptions options;
  std::vector<RigidBody> bodies;
};

/// Parses the list of bodies (`where` names the file, `path` the key of the list). Unknown keys,
/// missing keys, wrong types, impossible values and duplicate names throw tmlab::Error naming the
/// key.
std::vector<RigidBody> parse_contact_bodies(const nlohmann::json& bodies, const std::string& where,
                                            const std::string& path = "contact.bodies");

/// Parses the whole section (options and bodies); at least one body is required.
ContactSettings parse_contact_section(const nlohmann::json& section, const std::string& where,
                                      const std::string& path = "contact");

}  // namespace tmlab::tm
