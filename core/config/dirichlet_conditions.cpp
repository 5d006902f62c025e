#include "core/config/dirichlet_conditions.hpp"

#include "core/base/error.hpp"

namespace tmlab {

std::vector<int> dirichlet_dof_owners(Index num_nodes, const std::vector<DirichletCondition>& conditions) {
  std::vector<int> owner(3 * static_cast<std::size_t>(num_nodes), -1);
  for (std::size_t k = 0; k < conditions.size(); ++k) {
    const auto& c = conditions[k];
    if (c.nodes.empty())
      throw Error("boundary condition '" + c.name + "' selects no nodes (check its node selector)");
    for (Index n : c.nodes) {
      if (n < 0 || n >= num_nodes)
        throw Error("boundary condition '" + c.name + "': node " + std::to_string(n) + " out of range");
      for (int comp = 0; comp < 3; ++comp) {
        if (!c.components[static_cast<std::size_t>(comp)]) continue;
        int& o = owner[3 * static_cast<std::size_t>(n) + static_cast<std::size_t>(comp)];
        if (o >= 0 && o != static_cast<int>(k)) {
          // Two conditions on one DOF are fine only if they agree for all time: both zero.
          const auto& p = conditions[static_cast<std::size_t>(o)];
          if (p.value[comp] == 0.0 && c.value[comp] == 0.0) continue;
          throw Error("boundary conditions '" + p.name + "' and '" + c.name + "' both prescribe component " +
                      std::to_string(comp) + " of node " + std::to_string(n) + " with different values");
        }
        o = static_cast<int>(k);
      }
    }
  }
  return owner;
}

}  // namespace tmlab
