// What the analytic checks (analytic_*_checks.cpp) share: their material and Newton parameters,
// the lists they read, boundary conditions on the generated box meshes, and StaticRun, a static
// problem solved by the tensor-mass StaticSolver.
#pragma once

#include "core/base/format.hpp"
#include "core/config/config_reader.hpp"
#include "core/mesh/mesh.hpp"
#include "tensormass/materials/stvk_material.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/dirichlet.hpp"
#include "tensormass/system/external_loads.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace tmlab::verify::analytic {

using tm::Mat3;
using tm::VecX;

inline std::string fmt(double v, int digits = 3) { return scientific(v, digits); }

/// Reads a list of numbers (non-empty, each finite and > 0).
std::vector<double> positive_list(ConfigReader& p, const std::string& key);

/// Reads a list of whole numbers (non-empty, each >= min_value, strictly increasing).
std::vector<int> count_list(ConfigReader& p, const std::string& key, int min_value);

/// The St VK material of parameters "E" and "nu" (errors name the key).
tm::StVenantKirchhoff read_material(ConfigReader& p);

/// Newton's options: "newton_rtol" (default 1e-12), no absolute floor, 30 iterations.
tm::NewtonOptions newton_options(ConfigReader& p);

/// A static problem on a mesh: the model, the constraints and loads, solved by the tensor-mass
/// StaticSolver (Newton with line search and cut-backs; begin_step/commit_step per increment).
struct StaticRun {
  const Mesh& mesh;
  tm::ElasticModel& model;
  tm::MechanicalSystem system;
  tm::StaticSolver solver;
  VecX u;
  StaticRun(const Mesh& m, tm::ElasticModel& mod, std::vector<tm::DirichletCondition> bcs,
            const std::vector<tm::NodalForce>& nodal, const std::vector<tm::SurfaceTraction>& tractions,
            const tm::NewtonOptions& options)
      : mesh(m),
        model(mod),
        system(mod, tm::lumped_dof_mass(tm::lumped_node_mass(m, 1000.0)),
               tm::DirichletSet(m.num_points(), std::move(bcs)), make_loads(m, nodal, tractions)),
        solver(system, options),
        u(VecX::Zero(3 * m.num_points())) {}

  static tm::ExternalLoads make_loads(const Mesh& m, const std::vector<tm::NodalForce>& nodal,
                                      const std::vector<tm::SurfaceTraction>& tractions) {
    tm::ExternalLoads loads(m, tm::lumped_node_mass(m, 1000.0));
    for (const auto& f : nodal) loads.add(f);
    for (const auto& t : tractions) loads.add(t);
    return loads;
  }
  void advance(double t0, double t1) { solver.advance(t0, t1, u); }
  /// Reaction of Dirichlet condition k at the committed state: sum over its DOFs of f_int - f_ext.
  Vec3 reaction(std::size_t k, double t) const {
    VecX fi, fe;
    model.internal_force(u, fi);
    system.loads().assemble(u, t, fe);
    return system.bc().resultant(k, fi - fe);
  }
  /// |R_free| / |f_int| at u: the equilibrium residual actually reached.
  double relative_residual(double t) const {
    VecX fi, fe;
    model.internal_force(u, fi);
    system.loads().assemble(u, t, fe);
    VecX r = fi - fe;
    const double scale = std::max(fi.norm(), fe.norm());
    system.bc().zero_constrained(r);
    return scale > 0 ? r.norm() / scale : r.norm();
  }
};

/// The nodes of the named group of a generated mesh ("xmin", "zmax", ...).
std::vector<Index> group_nodes(const Mesh& m, const std::string& name);

/// A Dirichlet condition on `nodes`: the components `comps` prescribed to value * f(t).
tm::DirichletCondition condition(const std::string& name, std::vector<Index> nodes, std::array<bool, 3> comps,
                                 const Vec3& value = Vec3::Zero(),
                                 TimeFunction f = TimeFunction::constant(1.0));

/// The three symmetry planes of a box [0, L]^3 (x = 0: u_x = 0, y = 0: u_y = 0, z = 0: u_z = 0).
std::vector<tm::DirichletCondition> symmetry_planes(const Mesh& m);

}  // namespace tmlab::verify::analytic
