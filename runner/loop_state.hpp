// What a stepping loop of the runner owns besides the problem and the recorder: the state it
// advances and the objects the run's checkpoint saves and restores (runner/run_checkpoint.hpp).
// Plain references and pointers; tested through test_run_checkpoint.
#pragma once

#include "core/mesh/mesh.hpp"
#include "runner/newton_log.hpp"
#include "tensormass/solvers/explicit_dynamics.hpp"
#include "tensormass/solvers/implicit_dynamics.hpp"

namespace tmlab::tm::runner {

/// Displacement u and velocity v of the run, advanced by the stepping functions.
struct State {
  VecX u, v;
};

/// What a stepping loop owns besides the problem and the recorder (null: not in this loop).
struct LoopState {
  State& s;
  double& t;  ///< the loop's time (static: the load factor reached)
  NewtonLog* newton;
  long* total_newton;
  long* total_cutbacks;
  CentralDifference* central;
  ImplicitDynamics* implicit;
};

}  // namespace tmlab::tm::runner
