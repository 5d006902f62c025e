// The semi-discrete mechanical system shared by every solver:
//   M a + C v + f_int(u) = f_ext(u, t),   u = g(t) on the Dirichlet DOFs,
// with lumped M, Rayleigh damping C = alpha M + beta K_0 (K_0 the tangent at the reference
// configuration, so C is constant and the Jacobian exact), f_int from an ElasticModel.
#pragma once

#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/system/dirichlet.hpp"
#include "tensormass/system/external_loads.hpp"

namespace tmlab::tm {

struct RayleighDamping {
  double alpha = 0.0;  ///< mass-proportional, 1/s
  double beta = 0.0;   ///< stiffness-proportional, s
};

class MechanicalSystem {
 public:
  MechanicalSystem(ElasticModel& model, VecX dof_mass, DirichletSet bc, ExternalLoads loads,
                   RayleighDamping damping = {});

  /// The model; non-const because solvers advance its history (begin_step/commit_step).
  ElasticModel& model() const { return model_; }
  const VecX& mass() const { return mass_; }  ///< diagonal of M (per DOF)
  const DirichletSet& bc() const { return bc_; }
  const ExternalLoads& loads() const { return loads_; }
  const RayleighDamping& damping() const { return damping_; }
  Index num_dofs() const { return static_cast<Index>(mass_.size()); }

  /// C v = alpha M v + beta K_0 v.
  void damping_force(const VecX& v, VecX& out) const;
  /// J += -d f_ext/du at (u, t): the load stiffness of follower pressure (no-op without follower loads).
  void add_load_stiffness(const VecX& u, double t, SpMat& J) const;
  /// K_0, the tangent at u = 0 (assembled once, lazily).
  const SpMat& reference_tangent() const;

 private:
  ElasticModel& model_;
  VecX mass_;
  DirichletSet bc_;
  ExternalLoads loads_;
  RayleighDamping damping_;
  mutable SpMat k0_;
  mutable bool k0_ready_ = false;
};

}  // namespace tmlab::tm
