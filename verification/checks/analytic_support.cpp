// What the analytic checks share: see analytic_support.hpp.
#include "verification/checks/analytic_support.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"

#include <cmath>
#include <utility>

namespace tmlab::verify::analytic {

std::vector<double> positive_list(ConfigReader& p, const std::string& key) {
  const auto v = p.require<std::vector<double>>(key);
  if (v.empty()) throw p.error(key, "must not be empty");
  for (double x : v)
    if (!(x > 0.0) || !std::isfinite(x))
      throw p.error(key, "entries must be finite and > 0 (got " + std::to_string(x) + ")");
  return v;
}

std::vector<int> count_list(ConfigReader& p, const std::string& key, int min_value) {
  const auto v = p.require<std::vector<int>>(key);
  if (v.empty()) throw p.error(key, "must not be empty");
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i] < min_value) throw p.error(key, "entries must be >= " + std::to_string(min_value));
    if (i > 0 && v[i] <= v[i - 1]) throw p.error(key, "must increase strictly");
  }
  return v;
}

tm::StVenantKirchhoff read_material(ConfigReader& p) {
  const double E = p.positive("E");
  const double nu = p.require<double>("nu");
  try {
    return tm::StVenantKirchhoff::from_young_poisson(E, nu);
  } catch (const Error& e) {
    throw p.error("nu", e.what());
  }
}

tm::NewtonOptions newton_options(ConfigReader& p) {
  tm::NewtonOptions o;
  o.rtol = p.positive("newton_rtol", 1e-12);
  // Absolute floor off: several cases load with tiny forces (small-strain regime), where the
  // default 1e-14 N floor would stop Newton long before the relative tolerance.
  o.atol = 0.0;
  o.max_iterations = 30;
  return o;
}

std::vector<Index> group_nodes(const Mesh& m, const std::string& name) { return nodes_of_group(m, name); }

tm::DirichletCondition condition(const std::string& name, std::vector<Index> nodes, std::array<bool, 3> comps,
                                 const Vec3& value, TimeFunction f) {
  tm::DirichletCondition c;
  c.name = name;
  c.nodes = std::move(nodes);
  c.components = comps;
  c.value = value;
  c.function = std::move(f);
  return c;
}

std::vector<tm::DirichletCondition> symmetry_planes(const Mesh& m) {
  return {condition("x0", group_nodes(m, "xmin"), {true, false, false}),
          condition("y0", group_nodes(m, "ymin"), {false, true, false}),
          condition("z0", group_nodes(m, "zmin"), {false, false, true})};
}

}  // namespace tmlab::verify::analytic
