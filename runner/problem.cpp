// The problem a case file describes: see problem.hpp.
#include "runner/problem.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "runner/model_factory.hpp"
#include "tensormass/materials/law_factory.hpp"
#include "tensormass/system/lumped_mass.hpp"

#include <algorithm>
#include <string>

namespace tmlab::tm::runner {

namespace {

/// The nodes a selector picks on the model's nodes: the linear mesh's selection, extended on a
/// quadratic mesh to the midside nodes (a group whose vertices are exactly those of its faces: the
/// 6-node faces' nodes; otherwise the midside node of every edge with both ends selected).
std::vector<Index> model_nodes(const Mesh& mesh, const QuadraticMesh* qm, const NodeSelector& s) {
  std::vector<Index> vertices = select_nodes(mesh, s);
  if (!qm || vertices.empty()) return vertices;
  if (s.kind == NodeSelector::Kind::Group) {
    const std::vector<Tri> faces = select_faces(mesh, s);
    std::vector<Index> face_vertices;
    for (const Tri& f : faces) face_vertices.insert(face_vertices.end(), f.begin(), f.end());
    std::sort(face_vertices.begin(), face_vertices.end());
    face_vertices.erase(std::unique(face_vertices.begin(), face_vertices.end()), face_vertices.end());
    if (!faces.empty() && face_vertices == vertices) return qm->face_nodes(faces);
  }
  return qm->with_midside_nodes(vertices);
}

/// A copy of `linear` whose points are the quadratic mesh's (midside nodes get file id -1).
Mesh quadratic_node_mesh(const Mesh& linear, const QuadraticMesh* qm) {
  if (!qm) return Mesh{};
  Mesh m = linear;
  m.points = qm->points;
  m.point_file_ids.resize(qm->points.size(), -1);
  return m;
}

/// The Dirichlet conditions of the case's node selectors; an empty selection is an error.
std::vector<DirichletCondition> make_conditions(const CaseConfig& cfg, const Mesh& mesh,
                                                const QuadraticMesh* qm) {
  std::vector<DirichletCondition> conditions;
  for (std::size_t i = 0; i < cfg.boundary.size(); ++i) {
    const auto& b = cfg.boundary[i];
    DirichletCondition c{b.name, model_nodes(mesh, qm, b.nodes), b.components, b.value, b.function};
    if (c.nodes.empty())
      throw Error(cfg.file + ": boundary[" + std::to_string(i) + "] '" + b.name + "' selects no nodes");
    conditions.push_back(std::move(c));
  }
  return conditions;
}

/// The loads of the case's node/face selectors; an empty selection is an error. `nodes` is the
/// model's node mesh (Problem::node_mesh()); selections are made on the linear `mesh`.
ExternalLoads make_loads(const CaseConfig& cfg, const Mesh& mesh, const Mesh& nodes, const QuadraticMesh* qm,
                         const VecX& node_mass) {
  ExternalLoads loads(nodes, node_mass);
  const auto tri6 = [qm](const std::vector<Tri>& faces) {
    std::vector<Tri6> out;
    for (const Tri& f : faces) out.push_back(qm->triangle(f));
    return out;
  };
  for (std::size_t i = 0; i < cfg.loads.size(); ++i) {
    const auto& l = cfg.loads[i];
    const std::string where = cfg.file + ": loads[" + std::to_string(i) + "] '" + l.name + "'";
    if (l.type == LoadSpec::Type::NodalForce) {
      NodalForce f{l.name, select_nodes(mesh, l.selector), l.vector, l.function};  // vertices
      if (f.nodes.empty()) throw Error(where + " selects no nodes");
      loads.add(std::move(f));
    } else if (l.type == LoadSpec::Type::Traction) {
      SurfaceTraction tr{l.name, select_faces(mesh, l.selector), l.vector, l.function};
      if (tr.faces.empty()) throw Error(where + " selects no boundary faces");
      if (qm)
        loads.add(QuadraticFaceLoad{l.name, tri6(tr.faces), 0.0, l.vector, l.function});
      else
        loads.add(std::move(tr));
    } else if (l.type == LoadSpec::Type::Pressure) {
      SurfacePressure p{l.name, select_faces(mesh, l.selector), l.pressure, l.follower, l.function};
      if (p.faces.empty()) throw Error(where + " selects no boundary faces");
      if (qm)  // dead (check_element_support refuses a follower pressure on quadratic elements)
        loads.add(QuadraticFaceLoad{l.name, tri6(p.faces), l.pressure, Vec3::Zero(), l.function});
      else
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
      quadratic(make_quadratic_mesh(cfg, mesh)),
      quadratic_nodes(quadratic_node_mesh(mesh, quadratic.get())),
      size((report.bbox_max - report.bbox_min).norm()),
      material(StVenantKirchhoff::from_young_poisson(cfg.material.young, cfg.material.poisson)),
      law(make_law(cfg.material.law, cfg.material.parameters, cfg.file + ": material")),
      model(make_model(cfg, mesh, quadratic.get(), material, law, visco)),
      fields_kernel(mesh, material),
      node_mass(make_node_mass(cfg, mesh, quadratic.get())),
      conditions(make_conditions(cfg, mesh, quadratic.get())),
      loads(make_loads(cfg, mesh, node_mesh(), quadratic.get(), node_mass)),
      system(*model, lumped_dof_mass(node_mass), DirichletSet(num_nodes(), conditions), loads,
             RayleighDamping{cfg.solver.damping_alpha, cfg.solver.damping_beta}) {
  if (system.bc().dofs().empty() && cfg.solver.type == SolverSpec::Type::Static)
    throw Error(cfg.file + ": a static run needs boundary conditions that stop rigid motion (none given)");
  for (const auto& p : cfg.output.probes) probe_nodes.push_back(probe_node(mesh, p, cfg.file));
}

}  // namespace tmlab::tm::runner
