// The `contact` section of a case file (docs/contact.md, docs/case-files.md): rigid analytic bodies
// (sphere, flat cylindrical punch, infinite plane) translated by a prescribed displacement history,
// and the options of the contact enforcement. A plain description, parsed strictly once here, so that
// both models build their contact from the same values: the fast model converts it into its
// RigidBody / ContactOptions (tensormass/contact/contact_config.hpp), the deal.II reference into its
// own constraints. Errors name the file and the full key ("case.json: key 'contact.bodies[1].radius':
// must be > 0").
//
//   "contact": {
//     "method": "augmented_lagrangian" | "penalty",      (default augmented_lagrangian)
//     "stiffness_factor": 100, "stiffness": 0,            (eps; 0 = automatic)
//     "gap_tol": 0, "initial_gap_tol": 0, "max_initial_gap": 0, "search_margin": 0,
//     "max_outer_iterations": 30,
//     "bodies": [
//       {"name": "indenter", "type": "sphere", "center": [x,y,z], "radius": R, "axis": [0,0,-1],
//        "mode": "frictionless" | "bonded", "displacement": [dx,dy,dz], "function": {time function}},
//       {"type": "punch", "center": [..] (face centre), "axis": [..] (into the sample), "radius": R,
//        "edge_radius": 0, ...},
//       {"type": "plane", "point": [..], "normal": [..] (towards the sample), ...}
//     ]
//   }
#pragma once

#include "core/config/time_function.hpp"
#include "core/geometry/rigid_gap.hpp"
#include "core/mesh/mesh.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace tmlab {

enum class ContactBodyMode {
  Frictionless,  ///< unilateral, g >= 0, normal force only
  Bonded,        ///< a node that touches sticks to the body (glue, never released)
};
enum class ContactEnforcement {
  AugmentedLagrangian,  ///< exact to gap_tol (Uzawa updates until the stopping test holds)
  Penalty,              ///< one solve with zero multipliers; penetration O(force / stiffness)
};

std::string to_string(ContactShape s);
std::string to_string(ContactBodyMode m);
std::string to_string(ContactEnforcement m);
std::optional<ContactShape> contact_shape_from_string(const std::string& name);
std::optional<ContactBodyMode> contact_body_mode_from_string(const std::string& name);
std::optional<ContactEnforcement> contact_enforcement_from_string(const std::string& name);

/// One rigid body: its shape, contact mode and motion c(t) = reference + displacement * function(t).
struct ContactBodySpec {
  std::string name;  ///< unique within the case ("indenter", "top_platen", ...)
  std::string key;   ///< its key in the case file, for messages ("contact.bodies[0]")
  ContactShape shape = ContactShape::Plane;
  ContactBodyMode mode = ContactBodyMode::Frictionless;
  Vec3 reference = Vec3::Zero();  ///< sphere centre, punch face centre, a point of the plane, m
  /// Unit vector. plane: outward normal (towards the sample); punch: face normal into the sample;
  /// sphere: orients the contact-radius output only (default: direction of travel, else -z).
  Vec3 axis = -Vec3::UnitZ();
  double radius = 0.0;               ///< sphere / punch radius R, m (0 for the plane)
  double edge_radius = 0.0;          ///< punch rim radius in [0, R] (0: sharp edge), m
  Vec3 displacement = Vec3::Zero();  ///< translation at function(t) = 1, m
  TimeFunction function = TimeFunction::constant(1.0);

  Vec3 position(double t) const { return reference + displacement * function(t); }
};

struct ContactSpec {
  bool enabled = false;  ///< the case has a `contact` section
  ContactEnforcement method = ContactEnforcement::AugmentedLagrangian;
  /// eps = stiffness_factor * (a nodal stiffness scale of the sample), unless stiffness > 0 (N/m).
  double stiffness_factor = 100.0;
  double stiffness = 0.0;
  double gap_tol = 0.0;          ///< m; 0: automatic (1e-8 * mean boundary edge)
  double initial_gap_tol = 0.0;  ///< penetration accepted at t = 0, m; 0: gap_tol
  /// A body farther than this from the sample at t = 0 is refused (it would not touch: a wrong
  /// position or units), m; 0: automatic (1e-3 * the mesh's bounding-box diagonal). Give a
  /// larger value for a deliberate approach phase.
  double max_initial_gap = 0.0;
  double search_margin = 0.0;  ///< m; 0: automatic
  int max_outer_iterations = 30;
  std::vector<ContactBodySpec> bodies;
};

/// Parses the section at key `path` of file `where`. Unknown keys, missing keys, wrong types,
/// impossible values (radius <= 0, edge radius above the radius, zero normal, non-finite numbers)
/// and duplicate body names throw tmlab::Error naming the file and the key. At least one body.
ContactSpec parse_contact_spec(const nlohmann::json& section, const std::string& where,
                               const std::string& path = "contact");

/// The section in case-file form with every default filled in (parse_contact_spec of it gives the
/// same spec again).
nlohmann::json contact_spec_json(const ContactSpec& spec);

}  // namespace tmlab
