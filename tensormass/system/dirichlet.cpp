#include "tensormass/system/dirichlet.hpp"

#include "core/base/error.hpp"

#include <cassert>

namespace tmlab::tm {

DirichletSet::DirichletSet(Index num_nodes, std::vector<DirichletCondition> conditions)
    : conditions_(std::move(conditions)),
      constrained_(3 * static_cast<std::size_t>(num_nodes), 0),
      owner_(3 * static_cast<std::size_t>(num_nodes), -1) {
  for (std::size_t k = 0; k < conditions_.size(); ++k) {
    const auto& c = conditions_[k];
    if (c.nodes.empty())
      throw Error("boundary condition '" + c.name + "' selects no nodes (check its node selector)");
    for (Index n : c.nodes) {
      if (n < 0 || n >= num_nodes)
        throw Error("boundary condition '" + c.name + "': node " + std::to_string(n) + " out of range");
      for (int comp = 0; comp < 3; ++comp) {
        if (!c.components[comp]) continue;
        const Index d = 3 * n + comp;
        const int prev = owner_[d];
        if (prev >= 0 && prev != static_cast<int>(k)) {
          // Two conditions on one DOF are fine only if they agree for all time: both zero.
          const auto& p = conditions_[prev];
          const bool both_zero = p.value[comp] == 0.0 && c.value[comp] == 0.0;
          if (!both_zero)
            throw Error("boundary conditions '" + p.name + "' and '" + c.name +
                        "' both prescribe component " + std::to_string(comp) + " of node " +
                        std::to_string(n) + " with different values");
          continue;
        }
        owner_[d] = static_cast<int>(k);
        constrained_[d] = 1;
      }
    }
  }
  for (Index d = 0; d < static_cast<Index>(constrained_.size()); ++d)
    if (constrained_[d]) dofs_.push_back(d);
}

void DirichletSet::apply(double t, VecX& u) const {
  assert(u.size() == static_cast<Eigen::Index>(constrained_.size()));
  for (Index d : dofs_) {
    const auto& c = conditions_[owner_[d]];
    u[d] = c.value[d % 3] * c.function(t);
  }
}

void DirichletSet::zero_constrained(VecX& v) const {
  for (Index d : dofs_) v[d] = 0.0;
}

Vec3 DirichletSet::resultant(std::size_t k, const VecX& r) const {
  Vec3 s = Vec3::Zero();
  for (Index n : conditions_.at(k).nodes)
    for (int comp = 0; comp < 3; ++comp)
      if (owner_[3 * n + comp] == static_cast<int>(k)) s[comp] += r[3 * n + comp];
  return s;
}

}  // namespace tmlab::tm
