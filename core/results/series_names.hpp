// The result protocol's series names, in one place: every writer (the tensor-mass runner, the
// deal.II reference) and every reader (tmlab compare, the plots, the studies) builds them here.
//
//   time, elastic_energy, max_displacement, min_volume_ratio, newton_iterations, ...  scalars
//   reaction_<condition>_{x,y,z,norm}   the reaction of a Dirichlet condition, N
//   probe_<probe>_{x,y,z,norm}          the displacement of a probe's node, m
//   contact_<body>_position_{x,y,z,norm}  a rigid contact body's reference point c(t), m
//   contact_<body>_force_{x,y,z,norm}     the force the sample exerts on the body, N
//   contact_<body>_moment_{x,y,z,norm}    its moment about c(t), N m
//   contact_<body>_area, _radius, _radius_max, _active_nodes, _max_pressure, _max_penetration
//                                       (m^2, m, m, 1, Pa, m; docs/contact.md)
//
// A vector quantity is four series named <base>_x, <base>_y, <base>_z and <base>_norm.
#pragma once

#include "core/results/series_table.hpp"

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace tmlab::series_names {

/// The scalar series (one value per recorded step).
inline constexpr const char* kTime = "time";                           ///< s
inline constexpr const char* kMaxDisplacement = "max_displacement";    ///< m, the largest nodal |u|
inline constexpr const char* kElasticEnergy = "elastic_energy";        ///< J, the stored energy
inline constexpr const char* kKineticEnergy = "kinetic_energy";        ///< J
inline constexpr const char* kExternalWork = "external_work";          ///< J, of loads and supports
inline constexpr const char* kSpringEnergy = "spring_energy";          ///< J, the long-term spring
inline constexpr const char* kBranchEnergy = "branch_energy";          ///< J, the Maxwell branches
inline constexpr const char* kDissipatedEnergy = "dissipated_energy";  ///< J, accumulated
inline constexpr const char* kStepDissipation = "step_dissipation";    ///< J, of the last step
inline constexpr const char* kMinVolumeRatio = "min_volume_ratio";     ///< 1, smallest J of the step
inline constexpr const char* kNewtonIterations = "newton_iterations";  ///< 1

/// The component suffixes of a vector quantity, in order.
inline constexpr std::array<const char*, 4> kComponents{"x", "y", "z", "norm"};

/// The base name of the reaction of Dirichlet condition `condition`: "reaction_<condition>".
inline std::string reaction(const std::string& condition) { return "reaction_" + condition; }
/// The base name of the displacement of probe `probe`: "probe_<probe>".
inline std::string probe(const std::string& probe) { return "probe_" + probe; }
/// One component of a vector quantity: component(reaction("base"), "z") = "reaction_base_z".
inline std::string component(const std::string& base, const std::string& suffix) {
  return base + "_" + suffix;
}

/// The base name of the outputs of contact body `body`: "contact_<body>".
inline std::string contact(const std::string& body) { return "contact_" + body; }

/// The contact outputs of one rigid body at one recorded step (docs/contact.md).
struct ContactValues {
  std::string body;
  std::array<double, 3> position{}, force{}, moment{};  ///< m, N, N m
  double area = 0.0;                                    ///< m^2, projected reference area in contact
  double radius = 0.0;           ///< m, area-equivalent contact radius sqrt(area / pi) (0 for a plane)
  double radius_max = 0.0;       ///< m, largest distance of a contact point from the body's axis
  double active_nodes = 0.0;     ///< nodes in contact
  double max_pressure = 0.0;     ///< Pa, largest nodal contact pressure
  double max_penetration = 0.0;  ///< m, largest penetration of a node in contact
};

/// The contact values of one body's record in either model (the fast model's ContactBodyState, the
/// deal.II reference's ContactBodyOutput): both name their members name, position, force, moment
/// (Vec3), area, radius_equivalent, radius_max, active_nodes and max_penetration; the largest nodal
/// pressure is given (each model keeps it its own way).
template <class Body>
ContactValues contact_values(const Body& b, double max_pressure) {
  ContactValues c;
  c.body = b.name;
  c.position = {b.position.x(), b.position.y(), b.position.z()};
  c.force = {b.force.x(), b.force.y(), b.force.z()};
  c.moment = {b.moment.x(), b.moment.y(), b.moment.z()};
  c.area = b.area;
  c.radius = b.radius_equivalent;
  c.radius_max = b.radius_max;
  c.active_nodes = b.active_nodes;
  c.max_pressure = max_pressure;
  c.max_penetration = b.max_penetration;
  return c;
}

/// Appends the series of one body's contact outputs (contact_<body>_...) to the table.
inline void add_contact(SeriesTable& table, const ContactValues& c) {
  const std::string b = contact(c.body);
  const auto vec = [&](const char* what, const char* unit, const std::array<double, 3>& v) {
    const std::string base = b + "_" + what;
    table.add(component(base, "x"), unit, v[0]);
    table.add(component(base, "y"), unit, v[1]);
    table.add(component(base, "z"), unit, v[2]);
    table.add(component(base, "norm"), unit, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  };
  vec("position", "m", c.position);
  vec("force", "N", c.force);
  vec("moment", "N m", c.moment);
  table.add(b + "_area", "m^2", c.area);
  table.add(b + "_radius", "m", c.radius);
  table.add(b + "_radius_max", "m", c.radius_max);
  table.add(b + "_active_nodes", "1", c.active_nodes);
  table.add(b + "_max_pressure", "Pa", c.max_pressure);
  table.add(b + "_max_penetration", "m", c.max_penetration);
}

/// The <x> of every series named <pre><x><suf> (x not empty: no case can declare an empty name) in
/// a list of series names, in the order given.
inline std::vector<std::string> names_between(const std::vector<std::string>& names, const std::string& pre,
                                              const std::string& suf) {
  std::vector<std::string> out;
  for (const auto& name : names)
    if (name.rfind(pre, 0) == 0 && name.size() > pre.size() + suf.size() &&
        name.compare(name.size() - suf.size(), suf.size(), suf) == 0)
      out.push_back(name.substr(pre.size(), name.size() - pre.size() - suf.size()));
  return out;
}

/// The conditions whose reactions a list of series names holds (those with a reaction_<c>_x series),
/// in the order given.
inline std::vector<std::string> reaction_conditions(const std::vector<std::string>& names) {
  return names_between(names, "reaction_", "_x");
}

/// The bodies whose contact outputs a list of series names holds (those with a contact_<body>_force_x
/// series), in the order given.
inline std::vector<std::string> contact_bodies(const std::vector<std::string>& names) {
  return names_between(names, "contact_", "_force_x");
}

/// Appends the four series of a vector quantity (x, y, z and its norm) to the table.
inline void add_vector(SeriesTable& table, const std::string& base, const std::string& unit, double x,
                       double y, double z) {
  table.add(component(base, "x"), unit, x);
  table.add(component(base, "y"), unit, y);
  table.add(component(base, "z"), unit, z);
  table.add(component(base, "norm"), unit, std::sqrt(x * x + y * y + z * z));
}

/// The last (x, y, z) of a vector quantity.
inline std::array<double, 3> last_vector(const SeriesTable& table, const std::string& base) {
  return {table.last(component(base, "x")), table.last(component(base, "y")),
          table.last(component(base, "z"))};
}

}  // namespace tmlab::series_names
