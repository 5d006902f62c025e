#include "tensormass/system/dirichlet.hpp"

#include "core/base/error.hpp"

#include <cassert>

namespace tmlab::tm {

DirichletSet::DirichletSet(Index num_nodes, std::vector<DirichletCondition> conditions)
    : conditions_(std::move(conditions)),
      constrained_(3 * static_cast<std::size_t>(num_nodes), 0),
      owner_(dirichlet_dof_owners(num_nodes, conditions_)) {
  for (std::size_t d = 0; d < owner_.size(); ++d) constrained_[d] = owner_[d] >= 0 ? 1 : 0;
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
