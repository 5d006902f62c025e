// run_reference_case: a tmlab case file -> the deal.II reference problem -> the result directory of
// the tensor-mass runner's protocol (same file and series names where they apply).
//
// The case is model-agnostic (tmlab::CaseConfig). Everything a case says in terms of mesh nodes is
// resolved on tmlab's own mesh, which every rank holds in full, so selections and their errors are
// identical on every rank; only the resulting DoFs are distributed:
//   * Dirichlet: a DoF is prescribed when every vertex of the mesh entity it belongs to is selected
//     (a vertex DoF: its vertex; a P2 edge DoF: both end vertices; Q2 face/cell DoFs: all vertices);
//   * nodal_force: the total force split equally over the selected vertices (vertex DoFs);
//   * pressure: dead load on the selected boundary faces (a surface group's triangles, or the
//     boundary faces all of whose vertices are selected), integrated with the face quadrature;
//   * gravity: body force rho g, integrated consistently (for P1 the same as lumped nodal masses);
//   * element: mesh.element p2_mean_dilatation runs the F-bar form of the fast model's element
//     (Discretisation::mean_dilatation, solid.cpp "Mean dilatation"); p1_anp runs plain P1 (the
//     reference has no averaged-nodal-pressure form; docs/elements.md);
//   * contact: the case's rigid bodies by the fast model's augmented Lagrangian (contact.hpp): P1 at
//     the mesh vertices, the same rule and stopping test, so P1 runs agree to round-off; P2 at the
//     quadrature points of the boundary faces (the vertex rule leaves the P2 edge nodes free).
#include "reference_fem/dealii/reference_runner.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/config/dirichlet_conditions.hpp"
#include "core/config/element_kind.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"
#include "core/results/recorder.hpp"
#include "core/results/run_output.hpp"
#include "reference_fem/dealii/contact.hpp"
#include "reference_fem/dealii/ida_dae.hpp"
#include "reference_fem/dealii/solid.hpp"

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/numerics/data_out.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace tmlab::ref {

namespace fs = std::filesystem;
using namespace dealii;

// ---- MPI ------------------------------------------------------------------------------------------

struct MpiSession::Impl {
  Impl(int& argc, char**& argv) : init(argc, argv, 1) {}
  Utilities::MPI::MPI_InitFinalize init;
};

MpiSession::MpiSession(int& argc, char**& argv) : impl_(std::make_unique<Impl>(argc, argv)) {}
MpiSession::~MpiSession() = default;
int MpiSession::rank() { return static_cast<int>(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD)); }
int MpiSession::size() { return static_cast<int>(Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)); }

namespace {

/// Which cell vertices the mesh entity of local DoF i touches (vertex, line, face or the cell),
/// found through the global vertex indices of the cell's lines and faces.
std::vector<unsigned> dof_entity_vertices(const DoFHandler<3>::active_cell_iterator& cell,
                                          const FiniteElement<3>& fe, unsigned i) {
  const unsigned nv = cell->n_vertices(), dpv = fe.n_dofs_per_vertex(), dpl = fe.n_dofs_per_line();
  auto local_vertex = [&](unsigned global) {
    for (unsigned v = 0; v < nv; ++v)
      if (cell->vertex_index(v) == global) return v;
    throw Error("reference: entity vertex not found in its cell");
  };
  if (i < nv * dpv) return {i / dpv};
  unsigned j = i - nv * dpv;
  if (dpl > 0 && j < cell->n_lines() * dpl) {
    const auto line = cell->line(j / dpl);
    return {local_vertex(line->vertex_index(0)), local_vertex(line->vertex_index(1))};
  }
  j -= cell->n_lines() * dpl;
  for (unsigned f = 0; f < cell->n_faces(); ++f) {
    const unsigned dpq = fe.n_dofs_per_quad(f);
    if (j < dpq) {
      std::vector<unsigned> out;
      for (unsigned k = 0; k < cell->face(f)->n_vertices(); ++k)
        out.push_back(local_vertex(cell->face(f)->vertex_index(k)));
      return out;
    }
    j -= dpq;
  }
  std::vector<unsigned> all(nv);
  for (unsigned v = 0; v < nv; ++v) all[v] = v;
  return all;
}

}  // namespace

std::string reference_result_name(const CaseConfig& cfg, const ReferenceOptions& ro) {
  if (!ro.name_suffix.empty()) return cfg.name + ro.name_suffix;
  std::string s = cfg.name + "-reference";
  if (ro.cells == CellType::Hex) s += "-hex";
  if (ro.degree == 2) s += "-p2";
  if (cfg.mesh.element == ElementKind::P2MeanDilatation) s += "-mean_dilatation";
  if (ro.time_integration == TimeIntegration::Ida) s += "-ida";
  return s;
}

namespace {

/// The law of the run: the case's (material.law and its keys, the parameters the fast model uses),
/// or the command line's override (--law stvk | neo_hookean | yeoh) of a case given by E and nu.
Material reference_material(const CaseConfig& cfg, const ReferenceOptions& ro) {
  try {
    if (!ro.law) return Material::make(cfg.material.law, cfg.material.parameters);
    if (!law_takes_young_poisson(cfg.material.law))
      throw Error("the law override '" + to_string(*ro.law) +
                  "' needs a case given by E and nu (material.law is '" + to_string(cfg.material.law) + "')");
    return Material::make(*ro.law, cfg.material.young, cfg.material.poisson, ro.yeoh_c20_ratio,
                          ro.yeoh_c30_ratio);
  } catch (const Error& e) {
    throw Error(cfg.file + ": " + e.what());
  }
}

/// What the reference does not do: say so instead of silently doing something else.
void check_supported(const CaseConfig& cfg, const ReferenceOptions& ro, unsigned n_ranks) {
  if (cfg.solver.type != SolverSpec::Type::Static)
    throw Error(cfg.file +
                ": key 'solver.type': the deal.II reference solves quasi-static problems only (got '" +
                std::string(cfg.solver.type == SolverSpec::Type::Explicit ? "explicit" : "implicit") +
                "'; explicit and implicit dynamics" +
                (cfg.contact.enabled ? ", with or without contact," : "") + " run in the fast model only)");
  const ViscoelasticSpec& vs = cfg.material.viscoelastic;
  if (vs.enabled && vs.history == PronyHistory::NodalForce)
    throw Error(
        cfg.file +
        ": key 'material.viscoelastic': the deal.II reference implements only the objective "
        "form (history on the PK2 stress, 'history': 'pk2' or 'scheme': 'objective'); the seed's "
        "nodal_force history is not objective (docs/theory/seed-errata.md) and has no continuum counterpart");
  if (ro.degree != 1 && ro.degree != 2)
    throw Error("reference: degree must be 1 or 2 (got " + std::to_string(ro.degree) + ")");
  if (vs.enabled && cfg.mesh.element == ElementKind::P2MeanDilatation)
    throw Error(cfg.file +
                ": key 'mesh.element' 'p2_mean_dilatation' has no viscoelastic form in the reference (nor in "
                "the fast model), and key 'material.viscoelastic' is given: use \"element\": \"p2\"");
  const MaterialLaw law = ro.law.value_or(cfg.material.law);
  if (vs.enabled && vs.relaxation == PronyRelaxation::Deviatoric && law != MaterialLaw::StVK)
    throw Error(
        "reference: deviatoric relaxation S_dev = 2 mu dev(E) is defined for St Venant-Kirchhoff only (law "
        "'" +
        to_string(law) + "')");
  const bool use_ida = ro.time_integration == TimeIntegration::Ida;
  if (use_ida) {
    if (!vs.enabled)
      throw Error(cfg.file +
                  ": the IDA time integration needs a viscoelastic material ('material.viscoelastic'): "
                  "an elastic quasi-static problem has no differential variables");
    if (n_ranks != 1)
      throw Error("reference: the IDA time integration runs on one MPI rank only (started on " +
                  std::to_string(n_ranks) + "); run it without mpirun or with the serial option");
    if (!(ro.ida_rtol > 0.0) || !(ro.ida_atol >= 0.0))
      throw Error("reference: ida_rtol must be > 0 and ida_atol >= 0");
    if (ro.linear_solver == LinearSolver::CgAmg)
      throw Error(
          "reference: the IDA time integration needs a direct linear solver ('direct' or "
          "'direct_klu'; got '" +
          to_string(ro.linear_solver) + "')");
  }
  if (cfg.contact.enabled && ro.cells == CellType::Hex)
    throw Error(cfg.file +
                ": key 'contact': contact is applied at the case mesh's vertices, which the hex cells "
                "(cells 'hex') do not have; run contact cases on the case's tets");
  if (cfg.contact.enabled && use_ida)
    throw Error(cfg.file +
                ": key 'contact': the IDA time integration has no contact (its outer loop of multiplier "
                "updates needs fixed steps); use time_integration 'fixed_step'");
  for (const auto& l : cfg.loads)
    if (l.type == LoadSpec::Type::Pressure && l.follower)
      throw Error(cfg.file + ": load '" + l.name +
                  "': follower pressure is not supported by the reference (dead loads only)");
}

/// The reference problem of a case: the tmlab mesh (every rank, checked like the tensor-mass runner
/// does), the coarse triangulation, material, Prony series and the Solid with its conditions and
/// loads. Built in place: the Solid refers to the coarse triangulation.
struct Problem {
  Problem(const CaseConfig& config, const ReferenceOptions& options, MPI_Comm communicator,
          std::ostream* log);
  Problem(const Problem&) = delete;
  Problem& operator=(const Problem&) = delete;

  const Mesh& nodes() const { return hex ? hex_nodes : mesh; }
  Index n_nodes() const { return nodes().num_points(); }

  const CaseConfig& cfg;
  const ReferenceOptions& ro;
  MPI_Comm comm;
  unsigned rank, n_ranks;
  bool hex;
  MeshReport report;
  int repaired = 0;
  Mesh mesh;
  dealii::Triangulation<3> coarse;
  Mesh hex_nodes;  ///< the node set in hex mode: the hex vertices
  Material material;
  std::optional<PronySeries> prony;
  std::unique_ptr<Solid> solid;
  std::vector<std::vector<unsigned>> vmap;  ///< (cell, vertex) -> node
  std::vector<Index> probe_nodes;
  std::unique_ptr<RigidContact> contact;  ///< the case's contact section, if any
};

/// The coarse triangulation: vertex i = tmlab node i and cell c = tet c (tet mode), or the
/// bounding box cut into hexahedra (hex mode; the node set is then the hex vertices).
void build_coarse(Problem& p) {
  if (!p.hex) {
    std::vector<Point<3>> pts(p.mesh.points.size());
    for (std::size_t i = 0; i < pts.size(); ++i)
      pts[i] = Point<3>(p.mesh.points[i].x(), p.mesh.points[i].y(), p.mesh.points[i].z());
    std::vector<std::array<unsigned, 4>> tets(p.mesh.tets.size());
    for (std::size_t c = 0; c < tets.size(); ++c)
      for (int a = 0; a < 4; ++a) tets[c][a] = static_cast<unsigned>(p.mesh.tets[c][a]);
    build_tet_triangulation(pts, tets, p.coarse);
  } else {
    const Point<3> lo(p.report.bbox_min.x(), p.report.bbox_min.y(), p.report.bbox_min.z());
    const Point<3> hi(p.report.bbox_max.x(), p.report.bbox_max.y(), p.report.bbox_max.z());
    const auto& n = p.ro.hex_subdivisions;
    GridGenerator::subdivided_hyper_rectangle(p.coarse, {n[0], n[1], n[2]}, lo, hi);
    for (const auto& v : p.coarse.get_vertices()) p.hex_nodes.points.emplace_back(v[0], v[1], v[2]);
  }
}

NewtonParameters newton_parameters(const CaseConfig& cfg, const ReferenceOptions& ro) {
  NewtonParameters np;
  np.max_iterations = cfg.solver.max_iterations;
  np.rtol = ro.newton_rtol;
  np.atol = cfg.solver.atol;
  np.line_search = cfg.solver.line_search;
  np.max_cutbacks = cfg.solver.max_cutbacks;
  np.linear_solver = ro.linear_solver;
  return np;
}

/// Dirichlet conditions: node-level ownership and conflicts by the rule both models share
/// (core/config/dirichlet_conditions.hpp); DoFs on edges and faces (P2, Q2) follow the condition
/// that selects all of their entity's vertices.
void add_dirichlet(Problem& p) {
  const CaseConfig& cfg = p.cfg;
  Solid& solid = *p.solid;
  const Index n_nodes = p.n_nodes();
  std::vector<DirichletCondition> conditions;
  std::vector<std::vector<char>> selected(cfg.boundary.size(), std::vector<char>(n_nodes, 0));
  for (std::size_t k = 0; k < cfg.boundary.size(); ++k) {
    const auto& b = cfg.boundary[k];
    DirichletCondition c{b.name, select_nodes(p.nodes(), b.nodes), b.components, b.value, b.function};
    if (c.nodes.empty())
      throw Error(cfg.file + ": boundary[" + std::to_string(k) + "] '" + b.name + "' selects no nodes");
    for (Index n : c.nodes) selected[k][n] = 1;
    conditions.push_back(std::move(c));
    solid.add_condition(b.name, b.function);
  }
  const std::vector<int> owner = dirichlet_dof_owners(n_nodes, conditions);
  const auto& fe = solid.fe();
  const unsigned n_local = fe.n_dofs_per_cell();
  std::vector<global_dof_index> dofs(n_local);
  // Per local DoF: component and the cell vertices of its entity (the same for every cell).
  std::vector<unsigned> comp(n_local);
  for (unsigned i = 0; i < n_local; ++i) comp[i] = fe.system_to_component_index(i).first;
  for (const auto& cell : solid.dof_handler().active_cell_iterators()) {
    if (cell->is_artificial()) continue;
    cell->get_dof_indices(dofs);
    const auto& vm = p.vmap[cell->active_cell_index()];
    for (unsigned i = 0; i < n_local; ++i) {
      const unsigned c = comp[i];
      const auto verts = dof_entity_vertices(cell, fe, i);
      int k = -1;
      if (verts.size() == 1)
        k = owner[3 * vm[verts[0]] + c];
      else
        for (std::size_t kk = 0; kk < cfg.boundary.size() && k < 0; ++kk) {
          if (!cfg.boundary[kk].components[c]) continue;
          bool all = true;
          for (unsigned v : verts) all = all && selected[kk][vm[v]];
          if (all) k = static_cast<int>(kk);
        }
      if (k >= 0) solid.prescribe(dofs[i], c, k, cfg.boundary[k].value[c]);
    }
  }
  if (cfg.boundary.empty())
    throw Error(cfg.file + ": a static run needs boundary conditions that stop rigid motion (none given)");
}

/// nodal_force: the total force split equally over the selected vertices (vertex DoFs).
void add_nodal_force(Problem& p, const LoadSpec& l, int lf, const std::string& where) {
  Solid& solid = *p.solid;
  const auto sel = select_nodes(p.nodes(), l.selector);
  if (sel.empty()) throw Error(where + " selects no nodes");
  std::vector<char> in(p.n_nodes(), 0);
  for (Index n : sel) in[n] = 1;
  const Vec3 per_node = l.vector / static_cast<double>(sel.size());
  std::set<global_dof_index> done;
  for (const auto& cell : solid.dof_handler().active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    const auto& vm = p.vmap[cell->active_cell_index()];
    for (unsigned v = 0; v < cell->n_vertices(); ++v) {
      if (!in[vm[v]]) continue;
      for (unsigned c = 0; c < 3; ++c) {
        const global_dof_index d = cell->vertex_dof_index(v, c);
        if (solid.locally_owned_dofs().is_element(d) && done.insert(d).second)
          solid.add_point_force(d, lf, per_node[static_cast<int>(c)]);
      }
    }
  }
}

/// The sorted node keys of the boundary faces a tet-mode surface selector picks.
std::set<std::vector<Index>> face_keys(const Mesh& mesh, const NodeSelector& selector) {
  std::set<std::vector<Index>> keys;
  for (const Tri& t : select_faces(mesh, selector)) {
    std::vector<Index> key(t.begin(), t.end());
    std::sort(key.begin(), key.end());
    keys.insert(key);
  }
  return keys;
}

/// pressure / traction: dead load on the selected boundary faces (a surface group's triangles, or
/// the boundary faces all of whose vertices are selected), integrated with the face quadrature.
void add_face_load(Problem& p, const LoadSpec& l, int lf, const std::string& where) {
  Solid& solid = *p.solid;
  std::set<std::vector<Index>> keys;
  std::vector<char> in;
  if (!p.hex) {
    keys = face_keys(p.mesh, l.selector);
  } else {
    in.assign(p.n_nodes(), 0);
    for (Index n : select_nodes(p.nodes(), l.selector)) in[n] = 1;
  }
  long found = 0;
  for (const auto& cell : solid.dof_handler().active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    const auto& vm = p.vmap[cell->active_cell_index()];
    for (unsigned f = 0; f < cell->n_faces(); ++f) {
      if (!cell->face(f)->at_boundary()) continue;
      std::vector<Index> key;
      for (unsigned k = 0; k < cell->face(f)->n_vertices(); ++k) {
        const auto gv = cell->face(f)->vertex_index(k);
        for (unsigned v = 0; v < cell->n_vertices(); ++v)
          if (cell->vertex_index(v) == gv) key.push_back(static_cast<Index>(vm[v]));
      }
      std::sort(key.begin(), key.end());
      bool take = false;
      if (!p.hex)
        take = keys.count(key) > 0;
      else {
        take = true;
        for (Index n : key) take = take && in[n];
      }
      if (take) {
        if (l.type == LoadSpec::Type::Pressure)
          solid.add_pressure(cell->id(), f, lf, l.pressure);
        else
          solid.add_traction(cell->id(), f, lf, Tensor<1, 3>({l.vector.x(), l.vector.y(), l.vector.z()}));
        ++found;
      }
    }
  }
  found = Utilities::MPI::sum(found, p.comm);
  if (found == 0) throw Error(where + " selects no boundary faces");
  if (!p.hex && found != static_cast<long>(keys.size()))
    throw Error(where + ": " + std::to_string(keys.size() - found) +
                " selected faces are not boundary faces of the mesh");
}

/// The case's loads; gravity is the body force rho g, integrated consistently (for P1 the same as
/// lumped nodal masses).
void add_loads(Problem& p) {
  const CaseConfig& cfg = p.cfg;
  for (std::size_t li = 0; li < cfg.loads.size(); ++li) {
    const auto& l = cfg.loads[li];
    const std::string where = cfg.file + ": loads[" + std::to_string(li) + "] '" + l.name + "'";
    const int lf = p.solid->add_load_function(l.function);
    if (l.type == LoadSpec::Type::NodalForce) {
      add_nodal_force(p, l, lf, where);
    } else if (l.type == LoadSpec::Type::Pressure || l.type == LoadSpec::Type::Traction) {
      add_face_load(p, l, lf, where);
    } else {
      Tensor<1, 3> rho_g;
      for (unsigned c = 0; c < 3; ++c) rho_g[c] = cfg.material.density * l.vector[static_cast<int>(c)];
      p.solid->add_body_force([rho_g](const Point<3>&) { return rho_g; }, lf);
    }
  }
}

/// The case's contact bodies: each node's vertex DoFs where this rank sees them (owned: the rank owns
/// them), the contact object (P1: at the vertices; P2: at the boundary faces' quadrature points)
/// started at t = 0 from the rest state, and the Solid told to run its outer loop.
void add_contact(Problem& p) {
  const Index n = p.mesh.num_points();
  std::vector<std::array<global_dof_index, 3>> node_dofs(
      static_cast<std::size_t>(n),
      {numbers::invalid_dof_index, numbers::invalid_dof_index, numbers::invalid_dof_index});
  std::vector<char> owned(static_cast<std::size_t>(n), 0);
  for (const auto& cell : p.solid->dof_handler().active_cell_iterators()) {
    if (cell->is_artificial()) continue;
    const auto& vm = p.vmap[cell->active_cell_index()];
    for (unsigned v = 0; v < cell->n_vertices(); ++v) {
      auto& d = node_dofs[vm[v]];
      for (unsigned c = 0; c < 3; ++c) d[c] = cell->vertex_dof_index(v, c);
      owned[vm[v]] = p.solid->locally_owned_dofs().is_element(d[0]) ? 1 : 0;
    }
  }
  const ContactRule rule = p.ro.degree == 1 ? ContactRule::Vertices : ContactRule::FacePoints;
  p.contact = std::make_unique<RigidContact>(p.cfg.contact, p.cfg.file, p.mesh, std::move(node_dofs),
                                             std::move(owned), p.comm, rule);
  p.contact->start(*p.solid, 0.0, p.cfg.solver.t_end,
                   std::vector<double>(3 * static_cast<std::size_t>(n), 0.0));
  p.solid->set_nodal_constraints(p.contact.get());
}

Problem::Problem(const CaseConfig& config, const ReferenceOptions& options, MPI_Comm communicator,
                 std::ostream* log)
    : cfg(config),
      ro(options),
      comm(communicator),
      rank(Utilities::MPI::this_mpi_process(comm)),
      n_ranks(Utilities::MPI::n_mpi_processes(comm)),
      hex(ro.cells == CellType::Hex) {
  check_supported(cfg, ro, n_ranks);
  mesh = load_case_mesh(cfg.mesh, report, repaired);
  build_coarse(*this);
  material = reference_material(cfg, ro);
  const ViscoelasticSpec& vs = cfg.material.viscoelastic;
  if (vs.enabled)
    prony = PronySeries::make(vs.convention, vs.weights, vs.taus, vs.integration, vs.relaxation);
  // The fast model's p2_mean_dilatation element: the same F-bar form (solid.cpp, "Mean dilatation").
  const Discretisation disc{!hex, static_cast<unsigned>(ro.degree),
                            cfg.mesh.element == ElementKind::P2MeanDilatation};
  solid = std::make_unique<Solid>(comm, coarse, disc, material, prony, newton_parameters(cfg, ro), log);
  vmap = coarse_vertex_map(*solid, coarse);
  add_dirichlet(*this);
  add_loads(*this);
  solid->finalize_setup();
  for (const auto& pr : cfg.output.probes) probe_nodes.push_back(probe_node(nodes(), pr, cfg.file));
  if (cfg.contact.enabled) add_contact(*this);
}

/// "mean_dilatation" (F-bar per cell) or "standard": the reference's volumetric form.
std::string volumetric_name(const Problem& p) {
  return p.solid->discretisation().mean_dilatation ? "mean_dilatation" : "standard";
}

/// Vertex values in node order, gathered from the DoF owners.
std::vector<double> vertex_displacements(const Problem& p) {
  std::vector<double> U(3 * static_cast<std::size_t>(p.n_nodes()), 0.0);
  const auto& u = p.solid->solution();
  for (const auto& cell : p.solid->dof_handler().active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    const auto& vm = p.vmap[cell->active_cell_index()];
    for (unsigned v = 0; v < cell->n_vertices(); ++v)
      for (unsigned c = 0; c < 3; ++c) {
        const global_dof_index d = cell->vertex_dof_index(v, c);
        if (p.solid->locally_owned_dofs().is_element(d)) U[3 * vm[v] + c] = u[d];
      }
  }
  Utilities::MPI::sum(U, p.comm, U);
  return U;
}

/// The result directory: rank 0 owns it (the others get nullptr); every rank learns the staging
/// path, and an error opening it stops every rank.
std::unique_ptr<RunOutput> open_output(const Problem& p, const RunOptions& opt, std::string& staging) {
  std::unique_ptr<RunOutput> out;
  std::string error;
  if (p.rank == 0) {
    try {
      out = std::make_unique<RunOutput>(fs::path(opt.results_root) / reference_result_name(p.cfg, p.ro),
                                        opt.log);
      staging = out->staging_dir().string();
      out->file("vtu/.keep");  // creates vtu/
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  error = Utilities::MPI::broadcast(p.comm, error, 0);
  if (!error.empty()) throw Error(error);
  staging = Utilities::MPI::broadcast(p.comm, staging, 0);
  return out;
}

/// manifest.json (the case plus the reference's own options) and mesh_report.json.
void write_inputs(const RunOutput& out, const Problem& p, const RunOptions& opt) {
  const ReferenceOptions& ro = p.ro;
  ManifestInput mi;
  mi.command_line = opt.command_line;
  mi.config = effective_case_json(p.cfg);
  mi.config["reference"] = {{"degree", ro.degree},
                            {"volumetric", volumetric_name(p)},
                            {"law", to_string(ro.law.value_or(p.cfg.material.law))},
                            {"cells", to_string(ro.cells)},
                            {"linear_solver", to_string(ro.linear_solver)},
                            {"newton_rtol", ro.newton_rtol},
                            {"mpi_ranks", p.n_ranks},
                            {"time_integration", to_string(ro.time_integration)}};
  if (ro.time_integration == TimeIntegration::Ida) {
    mi.config["reference"]["ida_rtol"] = ro.ida_rtol;
    mi.config["reference"]["ida_atol"] = ro.ida_atol;
  }
  mi.input_files.push_back(p.cfg.mesh.file);
  if (fs::exists(p.cfg.file)) mi.input_files.push_back(p.cfg.file);
  out.write_json("manifest.json", make_manifest(mi));
  out.write_json("mesh_report.json", mesh_report_json(p.report));
}

/// The recorder of the problem's conditions and probes.
Recorder make_recorder(const Problem& p) {
  std::vector<std::string> conditions, probes;
  for (int k = 0; k < p.solid->n_conditions(); ++k) conditions.push_back(p.solid->condition_name(k));
  for (const auto& pr : p.cfg.output.probes) probes.push_back(pr.name);
  return Recorder(conditions, probes, p.probe_nodes);
}

/// Records the steps of a run on every rank (the quantities are sums over ranks): the scalar series
/// (core::Recorder), and at field frames displacement.h5 (rank 0) and vtu/ (every rank its piece).
class StepRecorder {
 public:
  StepRecorder(const Problem& p, const RunOutput* out, std::string staging)
      : p_(p), staging_(std::move(staging)), rec_(make_recorder(p)) {
    if (out) rec_.open_displacements(out->file("displacement.h5"));
  }

  void record(int step, double t, int newton_its, bool write_fields) {
    const Solid& solid = *p_.solid;
    const double jmin = solid.min_volume_ratio();
    if (!(jmin > 0.0)) {
      std::ostringstream m;
      m << "reference: an element inverted at t = " << t << " (step " << step << ", smallest det F " << jmin
        << ")";
      throw Error(m.str());
    }
    const auto reac = solid.reactions(t);
    Recorder::StepValues s;
    s.elastic_energy = solid.elastic_energy();
    const std::vector<double> U = vertex_displacements(p_);
    for (Index i = 0; i < p_.n_nodes(); ++i)
      s.max_displacement = std::max(
          s.max_displacement,
          std::sqrt(U[3 * i] * U[3 * i] + U[3 * i + 1] * U[3 * i + 1] + U[3 * i + 2] * U[3 * i + 2]));
    s.time = t;
    s.kinetic_energy = 0.0;
    s.min_volume_ratio = jmin;
    s.newton_iterations = newton_its;
    for (const auto& r : reac) s.reactions.push_back({r[0], r[1], r[2]});
    for (Index n : p_.probe_nodes) {
      const std::size_t i = 3 * static_cast<std::size_t>(n);
      s.probes.push_back({U[i], U[i + 1], U[i + 2]});
    }
    if (p_.contact) {
      contact_ = p_.contact->outputs(solid.solution(), t);
      for (const ContactBodyOutput& b : contact_)
        s.contact.push_back(series_names::contact_values(b, b.max_pressure));
    }
    rec_.record(s);
    if (!write_fields) return;
    const int frame = rec_.field_frames();
    rec_.add_field_frame(t, U);
    if (p_.cfg.output.vtu) write_vtu(t, frame);
  }

  /// Writes timeseries.h5, closes displacement.h5 and writes result.pvd (rank 0).
  void close(const RunOutput& out) {
    rec_.write_timeseries(out.file("timeseries.h5"), {{"case", p_.cfg.name}, {"model", "reference"}});
    rec_.close_displacements("vertex values");
    if (!pvd_.empty()) {
      std::ofstream pvd_file(out.file("result.pvd"));
      DataOutBase::write_pvd_record(pvd_file, pvd_);
    }
    fs::remove(out.file("vtu/.keep"));
  }

  const Recorder& recorder() const { return rec_; }
  /// The contact outputs of the last recorded step (one per body; empty without contact).
  const std::vector<ContactBodyOutput>& contact() const { return contact_; }

 private:
  /// The displacement, volume ratio, von Mises stress and MPI subdomain of frame `frame`.
  void write_vtu(double t, int frame) {
    const Solid& solid = *p_.solid;
    Vector<float> jcell, vm, subdomain(solid.triangulation().n_active_cells());
    solid.cell_fields(jcell, vm);
    for (const auto& cell : solid.triangulation().active_cell_iterators())
      if (cell->is_locally_owned()) subdomain[cell->active_cell_index()] = static_cast<float>(p_.rank);
    DataOut<3> data_out;
    data_out.attach_dof_handler(solid.dof_handler());
    std::vector<DataComponentInterpretation::DataComponentInterpretation> interp(
        3, DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(solid.solution(), std::vector<std::string>(3, "displacement"),
                             DataOut<3>::type_dof_data, interp);
    data_out.add_data_vector(jcell, "volume_ratio");
    data_out.add_data_vector(vm, "von_mises");
    data_out.add_data_vector(subdomain, "subdomain");
    data_out.build_patches(solid.mapping(), static_cast<unsigned>(p_.ro.degree));
    const std::string pvtu =
        data_out.write_vtu_with_pvtu_record(staging_ + "/vtu/", "step", frame, p_.comm, 5, 0);
    pvd_.emplace_back(t, "vtu/" + pvtu);
  }

  const Problem& p_;
  std::string staging_;
  Recorder rec_;
  std::vector<ContactBodyOutput> contact_;
  std::vector<std::pair<double, std::string>> pvd_;
};

/// What the stepping reports for summary.json.
struct SteppingReport {
  nlohmann::json per_step = nlohmann::json::array();
  long newton = 0, linear = 0, cutbacks = 0;
  double assembly_seconds = 0.0, solve_seconds = 0.0, newton_seconds = 0.0;
  nlohmann::json ida;           ///< IDA runs only
  std::vector<int> outer;       ///< contact: outer (multiplier-update) iterations per step
  std::vector<double> natural;  ///< contact: natural complementarity residual at the end of each step, m
};

bool field_step(const CaseConfig& cfg, int k) { return k % cfg.output.every == 0 || k == cfg.solver.steps; }

/// Fixed load (or time) steps t = t_end k / steps, each solved by Solid::advance.
SteppingReport step_fixed(Problem& p, StepRecorder& rec) {
  const CaseConfig& cfg = p.cfg;
  const int n_steps = cfg.solver.steps;
  SteppingReport r;
  rec.record(0, 0.0, 0, true);
  for (int k = 1; k <= n_steps; ++k) {
    const double t0 = cfg.solver.t_end * (k - 1) / n_steps, t1 = cfg.solver.t_end * k / n_steps;
    const StepStats st = p.solid->advance(t0, t1);
    r.newton += st.newton_iterations;
    r.linear += st.linear_iterations;
    r.cutbacks += st.cutbacks;
    r.assembly_seconds += st.assembly_seconds;
    r.solve_seconds += st.solve_seconds;
    r.newton_seconds += st.newton_seconds;
    r.per_step.push_back({{"step", k},
                          {"t", t1},
                          {"newton_iterations", st.newton_iterations},
                          {"linear_iterations", st.linear_iterations},
                          {"cutbacks", st.cutbacks},
                          {"sub_increments", st.sub_increments},
                          {"at_roundoff", st.at_roundoff},
                          {"backtracks", st.backtracks},
                          {"assembly_seconds", st.assembly_seconds},
                          {"solve_seconds", st.solve_seconds},
                          {"newton_seconds", st.newton_seconds},
                          {"residuals", st.residuals}});
    if (p.contact) {
      r.outer.push_back(st.outer_iterations);
      r.natural.push_back(p.contact->natural_residual());
      r.per_step.back()["outer_iterations"] = st.outer_iterations;
    }
    rec.record(k, t1, st.newton_iterations, field_step(cfg, k));
    // A safe point for SIGINT/SIGTERM; every rank agrees, so all stop at the same step.
    const int sig = Utilities::MPI::max(pending_interrupt(), p.comm);
    if (sig != 0)
      throw Interrupted(sig, signal_name(sig) + " received at t = " + std::to_string(t1) + " (step " +
                                 std::to_string(k) + " of " + std::to_string(n_steps) + ")");
  }
  return r;
}

/// The IDA summary block: tolerances, counters and timings.
nlohmann::json ida_summary(const IdaParameters& ip, const IdaStats& st, const QuasiStaticDae& dae) {
  return {{"rtol", ip.rtol},
          {"atol_displacement_m", ip.atol_u},
          {"atol_internal_variables_Pa", ip.atol_z},
          {"steps", st.steps},
          {"step_attempts", st.step_attempts},
          {"residual_evaluations", st.residual_evaluations},
          {"newton_iterations", st.newton_iterations},
          {"jacobian_setups", st.jacobian_setups},
          {"recoverable_failures", st.recoverable_failures},
          {"output_projection_iterations", st.projection_iterations},
          {"output_projection_seconds", st.projection_seconds},
          {"internal_variables", dae.size() - dae.n_dofs()},
          {"residual_seconds", st.residual_seconds},
          {"jacobian_seconds", st.jacobian_seconds},
          {"solve_seconds", st.solve_seconds},
          {"counting",
           "steps and attempts are counted in the callbacks (deal.II 9.4 keeps IDA's "
           "memory private); Newton iterations = linear solves, initial values included"}};
}

/// The same problem as a DAE integrated by IDA (ida_dae.hpp), output at the fixed-step times.
SteppingReport step_ida(Problem& p, StepRecorder& rec, std::ostream* log) {
  const CaseConfig& cfg = p.cfg;
  const int n_steps = cfg.solver.steps;
  SteppingReport r;
  const auto ida_start = std::chrono::steady_clock::now();
  QuasiStaticDae dae(*p.solid);
  IdaParameters ip;
  const double diag = (p.report.bbox_max - p.report.bbox_min).norm();
  ip.rtol = p.ro.ida_rtol;
  ip.atol_u = p.ro.ida_atol > 0.0 ? p.ro.ida_atol : 1e-3 * p.ro.ida_rtol * diag;
  ip.atol_z = ip.atol_u * cfg.material.young / diag;
  ip.linear_solver = p.ro.linear_solver;
  IdaStats before;
  const IdaStats st =
      dae.integrate(0.0, cfg.solver.t_end, n_steps, ip, [&](int k, double t, const Vector<double>& y) {
        dae.apply_state(y);
        const IdaStats& now = dae.stats();
        const long its = now.newton_iterations - before.newton_iterations;
        if (k > 0)
          r.per_step.push_back(
              {{"step", k},
               {"t", t},
               {"newton_iterations", its},
               {"ida_steps", now.steps - before.steps},
               {"ida_step_attempts", now.step_attempts - before.step_attempts},
               {"residual_evaluations", now.residual_evaluations - before.residual_evaluations},
               {"jacobian_setups", now.jacobian_setups - before.jacobian_setups}});
        if (log && k > 0)
          *log << "    t = " << t << ": IDA " << now.step_attempts - before.step_attempts
               << " step attempts, " << its << " Newton iterations, "
               << now.jacobian_setups - before.jacobian_setups << " Jacobian setups\n";
        before = now;
        rec.record(k, t, k == 0 ? 0 : static_cast<int>(its), k == 0 || field_step(cfg, k));
      });
  r.newton = st.newton_iterations;
  r.assembly_seconds = st.residual_seconds + st.jacobian_seconds;
  r.solve_seconds = st.solve_seconds;
  r.newton_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - ida_start).count();
  r.ida = ida_summary(ip, st, dae);
  if (log)
    *log << "reference: IDA " << st.steps << " steps (" << st.step_attempts << " attempts), "
         << st.residual_evaluations << " residuals, " << st.newton_iterations << " Newton iterations, "
         << st.jacobian_setups << " Jacobian setups\n";
  return r;
}

/// summary.json: the case, mesh, material, discretisation, solver and the recorder's common blocks.
/// The contact block of the summary: the enforcement and each body's final outputs, with the fast
/// model's keys (tmlab run and the reference summaries read alike).
nlohmann::json contact_summary(const Problem& p, const std::vector<ContactBodyOutput>& last,
                               const SteppingReport& r) {
  nlohmann::json bodies = nlohmann::json::array();
  for (std::size_t b = 0; b < last.size(); ++b) {
    const ContactBodyOutput& o = last[b];
    const ContactBodySpec& spec = p.cfg.contact.bodies[b];
    bodies.push_back({{"name", o.name},
                      {"type", to_string(spec.shape)},
                      {"mode", to_string(spec.mode)},
                      {"final_position_m", {o.position.x(), o.position.y(), o.position.z()}},
                      {"final_force_N", {o.force.x(), o.force.y(), o.force.z()}},
                      {"final_moment_Nm", {o.moment.x(), o.moment.y(), o.moment.z()}},
                      {"final_area_m2", o.area},
                      {"final_radius_m", o.radius_equivalent},
                      {"final_radius_max_m", o.radius_max},
                      {"final_active_nodes", o.active_nodes},
                      {"final_max_pressure_Pa", o.max_pressure},
                      {"final_max_penetration_m", o.max_penetration},
                      {"final_complementarity_Nm", o.complementarity},
                      {"final_min_multiplier_N", o.min_multiplier}});
  }
  return {{"scheme", "augmented_lagrangian_static"},
          {"method", to_string(p.cfg.contact.method)},
          {"rule", to_string(p.contact->rule())},
          {"gap_tol_m", p.contact->gap_tol()},
          {p.contact->rule() == ContactRule::Vertices ? "stiffness_N_per_m" : "stiffness_Pa_per_m",
           p.contact->stiffness()},
          {"outer_iterations_per_step", r.outer},
          {"natural_residual_per_step_m", r.natural},
          {"bodies", bodies}};
}

nlohmann::json summarise(const Problem& p, const Recorder& rec, const SteppingReport& r, double wall,
                         const std::vector<ContactBodyOutput>& contact) {
  const CaseConfig& cfg = p.cfg;
  const ReferenceOptions& ro = p.ro;
  nlohmann::json summary = {{"case", cfg.name},
                            {"description", cfg.description},
                            {"model", "reference"},
                            {"mesh",
                             {{"file", cfg.mesh.file},
                              {"points", p.n_nodes()},
                              {"tets", p.hex ? 0 : p.mesh.num_tets()},
                              {"cells", p.coarse.n_active_cells()},
                              {"cell_type", p.hex ? "hex" : "tet"},
                              {"volume_m3", p.report.total_volume},
                              {"orientation_repaired", p.repaired}}},
                            {"material",
                             {{"law", p.material.name()},
                              {"E", cfg.material.young},
                              {"nu", cfg.material.poisson},
                              {"density", cfg.material.density},
                              {"lambda", p.material.lambda},
                              {"mu", p.material.mu}}},
                            {"discretisation",
                             {{"element", p.hex ? "FE_Q" : "FE_SimplexP"},
                              {"degree", ro.degree},
                              {"volumetric", volumetric_name(p)},
                              {"n_dofs", p.solid->n_dofs()},
                              {"mpi_ranks", p.n_ranks}}},
                            {"solver",
                             {{"type", "static"},
                              {"load_steps", cfg.solver.steps},
                              {"newton_iterations", r.newton},
                              {"linear_iterations", r.linear},
                              {"cutbacks", r.cutbacks},
                              {"linear_solver", to_string(ro.linear_solver)},
                              {"newton_rtol", ro.newton_rtol},
                              {"assembly_seconds", r.assembly_seconds},
                              {"solve_seconds", r.solve_seconds},
                              {"newton_seconds", r.newton_seconds},
                              {"steps", r.per_step},
                              {"time_integration", to_string(ro.time_integration)}}},
                            {"plots", "skipped"},
                            {"run_seconds", wall}};
  summary.update(rec.summary_blocks());
  const ViscoelasticSpec& vs = cfg.material.viscoelastic;
  if (vs.enabled)
    summary["material"]["viscoelastic"] = {{"convention", to_string(vs.convention)},
                                           {"weights", vs.weights},
                                           {"taus", vs.taus},
                                           {"alpha", p.prony->alpha},
                                           {"integration", to_string(vs.integration)},
                                           {"relaxation", to_string(vs.relaxation)},
                                           {"history", "pk2"}};
  if (ro.time_integration == TimeIntegration::Ida) summary["solver"]["ida"] = r.ida;
  if (p.contact) summary["contact"] = contact_summary(p, contact, r);  // top level, as the fast model
  return summary;
}

void require_mpi() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised)
    throw Error(
        "the deal.II reference needs MPI: create a tmlab::ref::MpiSession in main() before running it");
}

}  // namespace

RunResult run_reference_case(const CaseConfig& cfg, const RunOptions& opt, const ReferenceOptions& ro) {
  require_mpi();
  const auto wall0 = std::chrono::steady_clock::now();
  const MPI_Comm comm = ro.serial ? MPI_COMM_SELF : MPI_COMM_WORLD;
  const bool root = Utilities::MPI::this_mpi_process(comm) == 0;
  std::ostream* log = root ? opt.log : nullptr;
  Problem p(cfg, ro, comm, log);
  std::string staging;
  const std::unique_ptr<RunOutput> out = open_output(p, opt, staging);
  try {
    if (root) write_inputs(*out, p, opt);
    StepRecorder rec(p, out.get(), staging);
    if (log)
      *log << "reference: " << cfg.name << ", " << p.material.name() << ", " << (p.hex ? "Q" : "P")
           << ro.degree << (p.solid->discretisation().mean_dilatation ? " mean dilatation" : "") << ", "
           << p.solid->n_dofs() << " DoFs, " << p.n_ranks << " rank(s), " << to_string(ro.linear_solver)
           << " solver\n";
    const SteppingReport r =
        ro.time_integration == TimeIntegration::Ida ? step_ida(p, rec, log) : step_fixed(p, rec);
    nlohmann::json summary;
    if (root) {
      rec.close(*out);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
      summary = summarise(p, rec.recorder(), r, wall, rec.contact());
      out->finalize(summary);
    }
    const std::string text = Utilities::MPI::broadcast(comm, root ? summary.dump() : std::string(), 0);
    const std::string dir = (fs::path(opt.results_root) / reference_result_name(cfg, ro)).string();
    return {dir, nlohmann::json::parse(text)};
  } catch (const std::exception& e) {
    if (out) out->abandon(e);
    throw;
  }
}

}  // namespace tmlab::ref
