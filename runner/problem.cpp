// The problem a case file describes: see problem.hpp.
#include "runner/problem.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "runner/model_factory.hpp"
#include "tensormass/materials/law_factory.hpp"
#include "tensormass/system/lumped_mass.hpp"

#include <string>

namespace tmlab::tm::runner {

namespace {

/// The Dirichlet conditions of the case's node selectors; an empty selection is an error.
std::vector<DirichletCondition> make_conditions(const CaseConfig& cfg, const Mesh& mesh) {
  std::vector<DirichletCondition> conditions;
  for (std::size_t i = 0; i < cfg.boundary.size(); ++i) {
    const auto& b = cfg.boundary[i];
    DirichletCondition c{b.name, select_nodes(mesh, b.nodes), b.components, b.value, b.function};
    if (c.nodes.empty())
      throw Error(cfg.file + ": boundary[" + std::to_string(i) + "] '" + b.name + "' selects no nodes");
    conditions.push_back(std::move(c));
  }
  return conditions;
}

/// The loads of the case's node/face selectors; an empty selection is an error.
ExternalLoads make_loads(const CaseConfig& cfg, const Mesh& mesh, const VecX& node_mass) {
  ExternalLoads loads(mesh, node_mass);
  for (std::size_t i = 0; i < cfg.loads.size(); ++i) {
    const auto& l = cfg.loads[i];
    const std::string where = cfg.file + ": loads[" + std::to_string(i) + "] '" + l.name + "'";
    if (l.type == LoadSpec::Type::NodalForce) {
      NodalForce f{l.name, select_nodes(mesh, l.selector), l.vector, l.function};
      if (f.nodes.empty()) throw Error(where + " selects no nodes");
      loads.add(std::move(f));
    } else if (l.type == LoadSpec::Type::Traction) {
      SurfaceTraction tr{l.name, select_faces(mesh, l.selector), l.vector, l.function};
      if (tr.faces.empty()) throw Error(where + " selects no boundary faces");
      loads.add(std::move(tr));
    } else if (l.type == LoadSpec::Type::Pressure) {
      SurfacePressure p{l.name, select_faces(mesh, l.selector), l.pressure, l.follower, l.function};
      if (p.faces.empty()) throw Error(where + " selects no boundary faces");
      loads.add(std::move(p));
    } else {
      loads.add(Gravity{l.vector, l.function});
    }
  }
  return loads;
}

}  // namespace

Problem::Problem(const CaseConfig& config)
    : cfg(config),
      mesh(load_case_mesh(cfg.mesh, report, repaired)),
      size((report.bbox_max - report.bbox_min).norm()),
      material(StVenantKirchhoff::from_young_poisson(cfg.material.young, cfg.material.poisson)),
      law(make_law(cfg.material.law, cfg.material.parameters, cfg.file + ": material")),
      model(make_model(cfg, mesh, material, law, visco)),
      fields_kernel(mesh, material),
      node_mass(lumped_node_mass(mesh, cfg.material.density)),
      conditions(make_conditions(cfg, mesh)),
      loads(make_loads(cfg, mesh, node_mass)),
      system(*model, lumped_dof_mass(node_mass), DirichletSet(mesh.num_points(), conditions), loads,
             RayleighDamping{cfg.solver.damping_alpha, cfg.solver.damping_beta}) {
  if (system.bc().dofs().empty() && cfg.solver.type == SolverSpec::Type::Static)
    throw Error(cfg.file + ": a static run needs boundary conditions that stop rigid motion (none given)");
  for (const auto& p : cfg.output.probes) probe_nodes.push_back(probe_node(mesh, p, cfg.file));
}

}  // namespace tmlab::tm::runner
