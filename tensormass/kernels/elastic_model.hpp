// The interface every elastic force model offers the solvers: energy, internal force, tangent action
// and assembled tangent, as functions of the nodal displacement vector.
//
// DOF order (docs/conventions.md): node-major, u[3*i + c] is component c (x, y, z) of node i.
// Sign: internal_force() returns f_int = dW/du. The force the body exerts on node i is -f_int;
// equilibrium is f_int(u) = f_ext.
#pragma once

#include "core/base/error.hpp"
#include "core/mesh/mesh.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <string>
#include <vector>

namespace tmlab::tm {

using VecX = Eigen::VectorXd;
using SpMat = Eigen::SparseMatrix<double>;  // column-major, symmetric stored in full

class ElasticModel {
 public:
  virtual ~ElasticModel() = default;
  virtual Index num_nodes() const = 0;
  Index num_dofs() const { return 3 * num_nodes(); }

  /// Stored elastic energy W(u), joules.
  virtual double energy(const VecX& u) const = 0;
  /// f = dW/du (overwrites f, resized to num_dofs()).
  virtual void internal_force(const VecX& u, VecX& f) const = 0;
  /// Kv = (d^2 W / du^2)(u) v, matrix-free (overwrites Kv).
  virtual void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const = 0;
  /// K = d^2 W / du^2 at u, assembled in full (both triangles). The sparsity pattern is the mesh
  /// graph; implementations reuse it between calls when K already has it.
  virtual void tangent(const VecX& u, SpMat& K) const = 0;

  // ---- History (viscoelastic models). Elastic models keep the no-op defaults. ----
  // A solver step from t to t + dt calls begin_step(dt) once, then evaluates energy/force/tangent
  // as often as it needs (Newton iterations, line search, rejected attempts: the *trial* state,
  // which depends on the committed history and u), and commit_step(u) once when the step is
  // accepted; only commit_step advances the history. A rejected step calls begin_step again
  // with a smaller dt and never commits.

  /// True when the model carries history (begin_step/commit_step matter).
  virtual bool has_history() const { return false; }
  /// True when internal_force() is the gradient of energy() (hyperelastic models). The trial
  /// forces of a history model are not, so its solvers cannot use the energy as a merit function.
  virtual bool energy_is_potential() const { return !has_history(); }
  /// Sets the trial step size from the committed state (dt >= 0; dt = 0 gives the instantaneous response).
  virtual void begin_step(double /*dt*/) {}
  /// Accepts the step ending at displacement u: advances the committed history.
  virtual void commit_step(const VecX& /*u*/) {}

  // ---- Checkpoints (--resume, core/results/checkpoint.hpp). ----
  /// The committed state as one flat array (empty for a model without history); restoring it
  /// after a commit gives a model whose later results are identical bit for bit.
  virtual std::vector<double> committed_state() const { return {}; }
  /// Sets the committed state saved by committed_state() (the trial step is reset to dt = 0, as
  /// after commit_step). Throws tmlab::Error when the array has the wrong size.
  virtual void restore_committed_state(const std::vector<double>& state);
  /// internal_force(u, f) of the trial step, then commit_step(u): what an explicit step does at
  /// every step. History models fuse the two into one pass over the tets (the trial force at u and
  /// the history update need the same per-tet strains or forces); the result is the same.
  virtual void force_and_commit(const VecX& u, VecX& f) {
    internal_force(u, f);
    commit_step(u);
  }
};

inline void ElasticModel::restore_committed_state(const std::vector<double>& state) {
  if (!state.empty())
    throw Error("checkpoint: a committed model state of " + std::to_string(state.size()) +
                " values for a model without history (a checkpoint of another model?)");
}

}  // namespace tmlab::tm
