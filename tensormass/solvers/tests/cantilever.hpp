// Shared by the solver tests (test_static_solver, test_explicit_dynamics, test_implicit_dynamics):
// a 40 x 10 x 10 mm soft cantilever clamped at x = 0 (E = 100 kPa, nu = 0.3, rho = 1000) under its
// own weight, which bends it by ~4 mm, a geometrically nonlinear but well-posed static problem; its
// static rest state; and the observed order of a time integrator by self-convergence.
#pragma once

#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

namespace tmlab::tm::testing {

struct Cantilever {
  Mesh mesh;
  StVenantKirchhoff material = StVenantKirchhoff::from_young_poisson(100e3, 0.3);
  double density = 1000.0;
  std::unique_ptr<TensorMassStVK> model;

  explicit Cantilever(int nx = 8, int n = 2) {
    mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(0.04, 0.01, 0.01), nx, n, n);
    model = std::make_unique<TensorMassStVK>(mesh, material);
  }
  MechanicalSystem system(RayleighDamping damping, Vec3 g = Vec3(0, 0, -9.81),
                          TimeFunction gravity_function = TimeFunction::constant()) const {
    NodeSelector clamp;
    clamp.kind = NodeSelector::Kind::Plane;
    clamp.axis = 0;
    clamp.value = 0.0;
    DirichletCondition fixed;
    fixed.name = "clamp";
    fixed.nodes = select_nodes(mesh, clamp);
    const VecX node_mass = lumped_node_mass(mesh, density);
    ExternalLoads loads(mesh, node_mass);
    Gravity grav;
    grav.acceleration = g;
    grav.function = gravity_function;
    loads.add(grav);
    return MechanicalSystem(*model, lumped_dof_mass(node_mass), DirichletSet(mesh.num_points(), {fixed}),
                            loads, damping);
  }
};

/// The static rest state of the cantilever under gravity, and a damping that brings a dynamic run
/// there quickly (issue test 5: static, explicit-to-rest and implicit-to-rest agree).
struct CantileverRest {
  VecX u_static;
  double scale = 0.0;       ///< |u_static|, for relative differences
  double omega1 = 0.0;      ///< first bending frequency, from the static tip deflection
  RayleighDamping damping;  ///< mass damping 2 zeta omega_1 with zeta ~ 1 (near critical)
};

inline CantileverRest cantilever_rest(const Cantilever& c) {
  CantileverRest r;
  MechanicalSystem sys_static = c.system({});
  r.u_static = VecX::Zero(sys_static.num_dofs());
  StaticSolver(sys_static, NewtonOptions{}).advance(0.0, 1.0, r.u_static);
  r.scale = r.u_static.norm();
  double tip = 0.0;
  for (Index i = 0; i < c.mesh.num_points(); ++i) tip = std::min(tip, r.u_static[3 * i + 2]);
  r.omega1 = std::sqrt(9.81 / std::abs(tip));
  r.damping = RayleighDamping{2.0 * r.omega1, 0.0};
  return r;
}

/// Observed order in dt by self-convergence: e(dt) = |u_dt(T) - u_{dt/2}(T)| shrinks as dt^p.
template <class Run>
double observed_order(Run run, double dt) {
  const VecX a = run(dt), b = run(dt / 2), c2 = run(dt / 4);
  return std::log2((a - b).norm() / (b - c2).norm());
}

/// The cantilever for observed orders: gravity switched on smoothly over [0, T] (C1 ramp), so the
/// stiff, unresolved modes are hardly excited and the error measured is that of the resolved motion.
inline constexpr double kOrderTestEndTime = 0.05;
inline MechanicalSystem smooth_gravity_system(const Cantilever& c) {
  return c.system({5.0, 0.0}, Vec3(0, 0, -9.81), TimeFunction::smooth_ramp(0.0, kOrderTestEndTime));
}

}  // namespace tmlab::tm::testing
