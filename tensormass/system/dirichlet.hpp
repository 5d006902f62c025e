// Prescribed displacements (Dirichlet conditions) on node sets.
//
// Each condition prescribes u_c(t) = value_c * f(t) on the chosen components c of its nodes, f a
// TimeFunction. The set resolves, once, which DOFs are constrained; a DOF prescribed by two
// conditions with different values is an error naming both.
#pragma once

#include "core/config/dirichlet_conditions.hpp"
#include "core/config/time_function.hpp"
#include "core/mesh/mesh.hpp"
#include "tensormass/kernels/elastic_model.hpp"

#include <array>
#include <string>
#include <vector>

namespace tmlab::tm {

using tmlab::DirichletCondition;  // core/config/dirichlet_conditions.hpp (shared with the reference)

class DirichletSet {
 public:
  DirichletSet() = default;
  DirichletSet(Index num_nodes, std::vector<DirichletCondition> conditions);

  Index num_dofs() const { return static_cast<Index>(constrained_.size()); }
  const std::vector<DirichletCondition>& conditions() const { return conditions_; }
  /// Sorted list of constrained DOFs.
  const std::vector<Index>& dofs() const { return dofs_; }
  /// mask()[d] != 0 when DOF d is constrained.
  const std::vector<char>& mask() const { return constrained_; }
  bool is_constrained(Index dof) const { return constrained_[dof] != 0; }

  /// Writes the prescribed values at time t into the constrained entries of u (others untouched).
  void apply(double t, VecX& u) const;
  /// Zeros the constrained entries of v (residuals, increments).
  void zero_constrained(VecX& v) const;
  /// Sum over the DOFs of condition k of r (the reaction force of that condition when r is the
  /// out-of-balance internal minus external force).
  Vec3 resultant(std::size_t k, const VecX& r) const;

 private:
  std::vector<DirichletCondition> conditions_;
  std::vector<char> constrained_;
  std::vector<Index> dofs_;
  std::vector<int> owner_;  ///< condition index per DOF, -1 when free
};

}  // namespace tmlab::tm
