// Small problems shared by the SUNDIALS reference tests (tensormass/tests and reference_fem/tests).
//
// CreepCube, quasi-static creep: [0, L]^3 with L = 1 cm (2x2x2 cells, 48 tets), E_inf = 10 kPa, nu = 0.3,
// rho = 1000, symmetry planes at x, y, z = 0, and a dead nominal traction 0.02 E_inf on x = L
// (SurfaceTraction: consistent nodal loads A/3 per face node) scaled by the time function `load`.
#pragma once

#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/materials/stvk_material.hpp"
#include "tensormass/system/dirichlet.hpp"
#include "tensormass/system/external_loads.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/viscoelastic/prony_series.hpp"

#include <string>
#include <utility>
#include <vector>

namespace tmlab::tm::test {

/// The quasi-static creep cube (see the top of this file); `series` and `load` vary per test.
struct CreepCube {
  static constexpr double L = 0.01, E = 10e3, nu = 0.3, traction = 0.02 * E;
  Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Constant(L), 2, 2, 2);
  StVenantKirchhoff mat = StVenantKirchhoff::from_young_poisson(E, nu);
  PronySeries prony;
  VecX node_mass = lumped_node_mass(mesh, 1000.0);
  std::vector<DirichletCondition> bc;
  ExternalLoads loads{mesh, node_mass};

  explicit CreepCube(PronySeries series = PronySeries::from_long_term({1.0}, {0.5}),
                     TimeFunction load = TimeFunction::smooth_ramp(0.0, 1.0))
      : prony(std::move(series)) {
    for (int a = 0; a < 3; ++a) {
      DirichletCondition c;
      c.name = std::string("sym") + "xyz"[a];
      c.nodes = select_nodes(mesh, NodeSelector::plane(a, 0.0, 1e-12));
      c.components = {a == 0, a == 1, a == 2};
      bc.push_back(c);
    }
    loads.add(SurfaceTraction{"traction", select_faces(mesh, NodeSelector::plane(0, L, 1e-12)),
                              Vec3(traction, 0.0, 0.0), std::move(load)});
  }
};

/// Dynamics: a block 2 x 1 x 1 cm (3x2x2 cells, 72 tets), E_inf = 5 kPa, rho = 1000, clamped at
/// x = 0, released with a transverse velocity growing linearly to 0.05 m/s at the tip.
struct ReleasedBlock {
  Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3(0.02, 0.01, 0.01), 3, 2, 2);
  StVenantKirchhoff mat;
  PronySeries prony;
  VecX node_mass = lumped_node_mass(mesh, 1000.0);
  DirichletCondition clamp;
  VecX v0;

  ReleasedBlock(double nu, PronySeries series)
      : mat(StVenantKirchhoff::from_young_poisson(5e3, nu)), prony(std::move(series)) {
    clamp.name = "clamp";
    clamp.nodes = select_nodes(mesh, NodeSelector::plane(0, 0.0, 1e-12));
    v0 = VecX::Zero(3 * mesh.num_points());
    for (Index i = 0; i < mesh.num_points(); ++i) v0[3 * i + 2] = 0.05 * mesh.points[i].x() / 0.02;
  }
  DirichletSet bc() const { return DirichletSet(mesh.num_points(), {clamp}); }
};

}  // namespace tmlab::tm::test
