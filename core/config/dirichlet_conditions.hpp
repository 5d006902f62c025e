// Prescribed displacements on node sets, and the one rule both models use to decide which
// condition prescribes each nodal DOF (docs/case-files.md, "boundary").
#pragma once

#include "core/config/time_function.hpp"
#include "core/mesh/mesh.hpp"

#include <array>
#include <string>
#include <vector>

namespace tmlab {

struct DirichletCondition {
  std::string name;                                  ///< for messages and output ("fixed", "probe", ...)
  std::vector<Index> nodes;                          ///< 0-based node indices
  std::array<bool, 3> components{true, true, true};  ///< which of x, y, z are prescribed
  Vec3 value = Vec3::Zero();                         ///< displacement at f(t) = 1, metres
  TimeFunction function = TimeFunction::constant(1.0);
};

/// The owning condition of each nodal DOF (3 per node, node-major; -1 where free). A DOF two
/// conditions prescribe belongs to the first, and is allowed only when both prescribe zero (they
/// then agree for all time); otherwise tmlab::Error names both conditions, the component and the
/// node. A condition that selects no node, or a node out of range, is an error too.
std::vector<int> dirichlet_dof_owners(Index num_nodes, const std::vector<DirichletCondition>& conditions);

}  // namespace tmlab
