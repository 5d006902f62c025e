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
//   * gravity: body force rho g, integrated consistently (for P1 the same as lumped nodal masses).
#include "reference_fem/dealii/reference_runner.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/config/dirichlet_conditions.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"
#include "core/results/run_output.hpp"
#include "core/results/series_names.hpp"
#include "core/results/series_table.hpp"
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
  if (ro.cells == "hex") s += "-hex";
  if (ro.degree == 2) s += "-p2";
  if (ro.time_integration == "ida") s += "-ida";
  return s;
}

RunResult run_reference_case(const CaseConfig& cfg, const RunOptions& opt, const ReferenceOptions& ro) {
  {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised)
      throw Error(
          "the deal.II reference needs MPI: create a tmlab::ref::MpiSession in main() before running it");
  }
  const auto wall0 = std::chrono::steady_clock::now();
  const MPI_Comm comm = ro.serial ? MPI_COMM_SELF : MPI_COMM_WORLD;
  const unsigned rank = Utilities::MPI::this_mpi_process(comm),
                 n_ranks = Utilities::MPI::n_mpi_processes(comm);
  const bool root = rank == 0;
  std::ostream* log = root ? opt.log : nullptr;

  // ---- What the reference does not do: say so instead of silently doing something else. ----
  if (cfg.solver.type != SolverSpec::Type::Static)
    throw Error(cfg.file +
                ": key 'solver.type': the deal.II reference solves quasi-static problems only (got a dynamic "
                "solver)");
  const ViscoelasticSpec& vs = cfg.material.viscoelastic;
  if (vs.enabled && vs.history == PronyHistory::NodalForce)
    throw Error(
        cfg.file +
        ": key 'material.viscoelastic': the deal.II reference implements only the objective "
        "form (history on the PK2 stress, 'history': 'pk2' or 'scheme': 'objective'); the seed's "
        "nodal_force history is not objective (docs/seed-errata.md) and has no continuum counterpart");
  if (ro.degree != 1 && ro.degree != 2)
    throw Error("reference: degree must be 1 or 2 (got " + std::to_string(ro.degree) + ")");
  if (ro.cells != "tet" && ro.cells != "hex") throw Error("reference: cells must be 'tet' or 'hex'");
  if (vs.enabled && vs.relaxation == PronyRelaxation::Deviatoric && ro.law != "stvk")
    throw Error(
        "reference: deviatoric relaxation S_dev = 2 mu dev(E) is defined for St Venant-Kirchhoff only (law "
        "'" +
        ro.law + "')");
  const bool use_ida = ro.time_integration == "ida";
  if (!use_ida && ro.time_integration != "fixed_step")
    throw Error("reference: time_integration must be 'fixed_step' or 'ida' (got '" + ro.time_integration +
                "')");
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
    if (ro.linear_solver != "direct" && ro.linear_solver != "direct_klu")
      throw Error(
          "reference: the IDA time integration needs a direct linear solver ('direct' or "
          "'direct_klu'; got '" +
          ro.linear_solver + "')");
  }
  for (const auto& l : cfg.loads)
    if (l.type == LoadSpec::Type::Pressure && l.follower)
      throw Error(cfg.file + ": load '" + l.name +
                  "': follower pressure is not supported by the reference (dead loads only)");

  // ---- Geometry: the tmlab mesh (every rank), checked like the tensor-mass runner does. ----
  MeshReport report;
  int repaired = 0;
  Mesh mesh = load_case_mesh(cfg.mesh, report, repaired);

  // The coarse triangulation: vertex i = tmlab node i and cell c = tet c (tet mode), or the
  // bounding box cut into hexahedra (hex mode; the node set is then the hex vertices).
  Triangulation<3> coarse;
  Mesh hex_nodes;
  const bool hex = ro.cells == "hex";
  if (!hex) {
    std::vector<Point<3>> pts(mesh.points.size());
    for (std::size_t i = 0; i < pts.size(); ++i)
      pts[i] = Point<3>(mesh.points[i].x(), mesh.points[i].y(), mesh.points[i].z());
    std::vector<std::array<unsigned, 4>> tets(mesh.tets.size());
    for (std::size_t c = 0; c < tets.size(); ++c)
      for (int a = 0; a < 4; ++a) tets[c][a] = static_cast<unsigned>(mesh.tets[c][a]);
    build_tet_triangulation(pts, tets, coarse);
  } else {
    const Point<3> lo(report.bbox_min.x(), report.bbox_min.y(), report.bbox_min.z());
    const Point<3> hi(report.bbox_max.x(), report.bbox_max.y(), report.bbox_max.z());
    GridGenerator::subdivided_hyper_rectangle(
        coarse, {ro.hex_subdivisions[0], ro.hex_subdivisions[1], ro.hex_subdivisions[2]}, lo, hi);
    for (const auto& v : coarse.get_vertices()) hex_nodes.points.emplace_back(v[0], v[1], v[2]);
  }
  const Mesh& nodes = hex ? hex_nodes : mesh;
  const Index n_nodes = nodes.num_points();

  // ---- Material, viscoelasticity, solver. ----
  const Material material =
      Material::make(ro.law, cfg.material.young, cfg.material.poisson, ro.yeoh_c20_ratio, ro.yeoh_c30_ratio);
  std::optional<PronySeries> prony;
  if (vs.enabled)
    prony = PronySeries::make(vs.convention, vs.weights, vs.taus, vs.integration, vs.relaxation);
  NewtonParameters np;
  np.max_iterations = cfg.solver.max_iterations;
  np.rtol = ro.newton_rtol;
  np.atol = cfg.solver.atol;
  np.line_search = cfg.solver.line_search;
  np.max_cutbacks = cfg.solver.max_cutbacks;
  np.linear_solver = ro.linear_solver;
  Solid solid(comm, coarse, Discretisation{!hex, static_cast<unsigned>(ro.degree)}, material, prony, np, log);
  const auto vmap = coarse_vertex_map(solid, coarse);  // (cell, vertex) -> node
  const auto& fe = solid.fe();
  const unsigned n_local = fe.n_dofs_per_cell();
  std::vector<global_dof_index> dofs(n_local);

  // ---- Dirichlet conditions: node-level ownership and conflicts by the rule both models share
  // (core/config/dirichlet_conditions.hpp); DoFs on edges and faces (P2, Q2) follow the condition
  // that selects all of their entity's vertices. ----
  std::vector<DirichletCondition> conditions;
  std::vector<std::vector<char>> selected(cfg.boundary.size(), std::vector<char>(n_nodes, 0));
  for (std::size_t k = 0; k < cfg.boundary.size(); ++k) {
    const auto& b = cfg.boundary[k];
    DirichletCondition c{b.name, select_nodes(nodes, b.nodes), b.components, b.value, b.function};
    if (c.nodes.empty())
      throw Error(cfg.file + ": boundary[" + std::to_string(k) + "] '" + b.name + "' selects no nodes");
    for (Index n : c.nodes) selected[k][n] = 1;
    conditions.push_back(std::move(c));
    solid.add_condition(b.name, b.function);
  }
  const std::vector<int> owner = dirichlet_dof_owners(n_nodes, conditions);
  // Per local DoF: component and the cell vertices of its entity (the same for every cell).
  std::vector<unsigned> comp(n_local);
  for (unsigned i = 0; i < n_local; ++i) comp[i] = fe.system_to_component_index(i).first;
  for (const auto& cell : solid.dof_handler().active_cell_iterators()) {
    if (cell->is_artificial()) continue;
    cell->get_dof_indices(dofs);
    const auto& vm = vmap[cell->active_cell_index()];
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

  // ---- Loads. ----
  for (std::size_t li = 0; li < cfg.loads.size(); ++li) {
    const auto& l = cfg.loads[li];
    const std::string where = cfg.file + ": loads[" + std::to_string(li) + "] '" + l.name + "'";
    const int lf = solid.add_load_function(l.function);
    if (l.type == LoadSpec::Type::NodalForce) {
      const auto sel = select_nodes(nodes, l.selector);
      if (sel.empty()) throw Error(where + " selects no nodes");
      std::vector<char> in(n_nodes, 0);
      for (Index n : sel) in[n] = 1;
      const Vec3 per_node = l.vector / static_cast<double>(sel.size());
      std::set<global_dof_index> done;
      for (const auto& cell : solid.dof_handler().active_cell_iterators()) {
        if (!cell->is_locally_owned()) continue;
        const auto& vm = vmap[cell->active_cell_index()];
        for (unsigned v = 0; v < cell->n_vertices(); ++v) {
          if (!in[vm[v]]) continue;
          for (unsigned c = 0; c < 3; ++c) {
            const global_dof_index d = cell->vertex_dof_index(v, c);
            if (solid.locally_owned_dofs().is_element(d) && done.insert(d).second)
              solid.add_point_force(d, lf, per_node[static_cast<int>(c)]);
          }
        }
      }
    } else if (l.type == LoadSpec::Type::Pressure || l.type == LoadSpec::Type::Traction) {
      std::set<std::vector<Index>> keys;
      std::vector<char> in;
      if (!hex) {
        for (const Tri& t : select_faces(mesh, l.selector)) {
          std::vector<Index> key(t.begin(), t.end());
          std::sort(key.begin(), key.end());
          keys.insert(key);
        }
      } else {
        in.assign(n_nodes, 0);
        for (Index n : select_nodes(nodes, l.selector)) in[n] = 1;
      }
      long found = 0;
      for (const auto& cell : solid.dof_handler().active_cell_iterators()) {
        if (!cell->is_locally_owned()) continue;
        const auto& vm = vmap[cell->active_cell_index()];
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
          if (!hex)
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
      found = Utilities::MPI::sum(found, comm);
      if (found == 0) throw Error(where + " selects no boundary faces");
      if (!hex && found != static_cast<long>(keys.size()))
        throw Error(where + ": " + std::to_string(keys.size() - found) +
                    " selected faces are not boundary faces of the mesh");
    } else {
      Tensor<1, 3> rho_g;
      for (unsigned c = 0; c < 3; ++c) rho_g[c] = cfg.material.density * l.vector[static_cast<int>(c)];
      solid.add_body_force([rho_g](const Point<3>&) { return rho_g; }, lf);
    }
  }
  solid.finalize_setup();

  std::vector<Index> probe_nodes;
  for (const auto& p : cfg.output.probes) probe_nodes.push_back(probe_node(nodes, p, cfg.file));

  // Vertex values in node order, gathered from the DoF owners.
  auto vertex_displacements = [&]() {
    std::vector<double> U(3 * static_cast<std::size_t>(n_nodes), 0.0);
    const auto& u = solid.solution();
    for (const auto& cell : solid.dof_handler().active_cell_iterators()) {
      if (!cell->is_locally_owned()) continue;
      const auto& vm = vmap[cell->active_cell_index()];
      for (unsigned v = 0; v < cell->n_vertices(); ++v)
        for (unsigned c = 0; c < 3; ++c) {
          const global_dof_index d = cell->vertex_dof_index(v, c);
          if (solid.locally_owned_dofs().is_element(d)) U[3 * vm[v] + c] = u[d];
        }
    }
    Utilities::MPI::sum(U, comm, U);
    return U;
  };

  // ---- Result directory: rank 0 owns it; the others learn the staging path. ----
  std::unique_ptr<RunOutput> out;
  std::string staging, error;
  const std::string result_name = reference_result_name(cfg, ro);
  if (root) {
    try {
      out = std::make_unique<RunOutput>(fs::path(opt.results_root) / result_name, opt.log);
      staging = out->staging_dir().string();
      out->file("vtu/.keep");  // creates vtu/
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  error = Utilities::MPI::broadcast(comm, error, 0);
  if (!error.empty()) throw Error(error);
  staging = Utilities::MPI::broadcast(comm, staging, 0);

  try {
    std::unique_ptr<H5File> disp_h5;
    if (root) {
      ManifestInput mi;
      mi.command_line = opt.command_line;
      mi.config = effective_case_json(cfg);
      mi.config["reference"] = {{"degree", ro.degree},
                                {"law", ro.law},
                                {"cells", ro.cells},
                                {"linear_solver", ro.linear_solver},
                                {"newton_rtol", ro.newton_rtol},
                                {"mpi_ranks", n_ranks},
                                {"time_integration", ro.time_integration}};
      if (use_ida) {
        mi.config["reference"]["ida_rtol"] = ro.ida_rtol;
        mi.config["reference"]["ida_atol"] = ro.ida_atol;
      }
      mi.input_files.push_back(cfg.mesh.file);
      if (fs::exists(cfg.file)) mi.input_files.push_back(cfg.file);
      out->write_json("manifest.json", make_manifest(mi));
      out->write_json("mesh_report.json", mesh_report_json(report));
      disp_h5 = std::make_unique<H5File>(H5File::create(out->file("displacement.h5")));
    }

    SeriesTable table;
    std::vector<std::pair<double, std::string>> pvd;
    int field_frames = 0;
    double jmin_overall = 1.0;
    auto record = [&](int step, double t, int newton_its, bool write_fields) {
      const double jmin = solid.min_volume_ratio();
      if (!(jmin > 0.0)) {
        std::ostringstream m;
        m << "reference: an element inverted at t = " << t << " (step " << step << ", smallest det F " << jmin
          << ")";
        throw Error(m.str());
      }
      jmin_overall = std::min(jmin_overall, jmin);
      const auto reac = solid.reactions(t);
      const double energy = solid.elastic_energy();
      const std::vector<double> U = vertex_displacements();
      double umax = 0.0;
      for (Index i = 0; i < n_nodes; ++i)
        umax = std::max(
            umax, std::sqrt(U[3 * i] * U[3 * i] + U[3 * i + 1] * U[3 * i + 1] + U[3 * i + 2] * U[3 * i + 2]));
      table.add("time", "s", t);
      table.add("max_displacement", "m", umax);
      table.add("elastic_energy", "J", energy);
      table.add("kinetic_energy", "J", 0.0);
      table.add("min_volume_ratio", "1", jmin);
      table.add("newton_iterations", "1", newton_its);
      for (int k = 0; k < solid.n_conditions(); ++k) {
        const std::string& n = solid.condition_name(k);
        series_names::add_vector(table, series_names::reaction(n), "N", reac[k][0], reac[k][1], reac[k][2]);
      }
      for (std::size_t k = 0; k < probe_nodes.size(); ++k) {
        const std::size_t i = 3 * static_cast<std::size_t>(probe_nodes[k]);
        const std::string& n = cfg.output.probes[k].name;
        series_names::add_vector(table, series_names::probe(n), "m", U[i], U[i + 1], U[i + 2]);
      }
      if (!write_fields) return;
      if (root) {
        disp_h5->append_row("/u", U);
        disp_h5->append("/time", t);
      }
      if (cfg.output.vtu) {
        Vector<float> jcell, vm, subdomain(solid.triangulation().n_active_cells());
        solid.cell_fields(jcell, vm);
        for (const auto& cell : solid.triangulation().active_cell_iterators())
          if (cell->is_locally_owned()) subdomain[cell->active_cell_index()] = static_cast<float>(rank);
        DataOut<3> data_out;
        data_out.attach_dof_handler(solid.dof_handler());
        std::vector<DataComponentInterpretation::DataComponentInterpretation> interp(
            3, DataComponentInterpretation::component_is_part_of_vector);
        data_out.add_data_vector(solid.solution(), std::vector<std::string>(3, "displacement"),
                                 DataOut<3>::type_dof_data, interp);
        data_out.add_data_vector(jcell, "volume_ratio");
        data_out.add_data_vector(vm, "von_mises");
        data_out.add_data_vector(subdomain, "subdomain");
        data_out.build_patches(solid.mapping(), static_cast<unsigned>(ro.degree));
        const std::string pvtu =
            data_out.write_vtu_with_pvtu_record(staging + "/vtu/", "step", field_frames, comm, 5, 0);
        pvd.emplace_back(t, "vtu/" + pvtu);
      }
      ++field_frames;
    };

    // ---- Load (or time) stepping. ----
    const int n_steps = cfg.solver.steps;
    const double t_end = cfg.solver.t_end;
    nlohmann::json per_step = nlohmann::json::array();
    long total_newton = 0, total_linear = 0, total_cutbacks = 0;
    double total_assembly = 0.0, total_solve = 0.0, total_newton_s = 0.0;
    if (log)
      *log << "reference: " << cfg.name << ", " << material.name() << ", " << (hex ? "Q" : "P") << ro.degree
           << ", " << solid.n_dofs() << " DoFs, " << n_ranks << " rank(s), " << ro.linear_solver
           << " solver\n";
    nlohmann::json ida_summary;
    if (!use_ida) {
      record(0, 0.0, 0, true);
      for (int k = 1; k <= n_steps; ++k) {
        const double t0 = t_end * (k - 1) / n_steps, t1 = t_end * k / n_steps;
        const StepStats st = solid.advance(t0, t1);
        total_newton += st.newton_iterations;
        total_linear += st.linear_iterations;
        total_cutbacks += st.cutbacks;
        total_assembly += st.assembly_seconds;
        total_solve += st.solve_seconds;
        total_newton_s += st.newton_seconds;
        per_step.push_back({{"step", k},
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
        record(k, t1, st.newton_iterations, k % cfg.output.every == 0 || k == n_steps);
        // A safe point for SIGINT/SIGTERM; every rank agrees, so all stop at the same step.
        const int sig = Utilities::MPI::max(pending_interrupt(), comm);
        if (sig != 0)
          throw Interrupted(sig, signal_name(sig) + " received at t = " + std::to_string(t1) + " (step " +
                                     std::to_string(k) + " of " + std::to_string(n_steps) + ")");
      }
    } else {
      // The same problem as a DAE integrated by IDA (ida_dae.hpp), output at the fixed-step times.
      const auto ida_start = std::chrono::steady_clock::now();
      QuasiStaticDae dae(solid);
      IdaParameters ip;
      const double diag = (report.bbox_max - report.bbox_min).norm();
      ip.rtol = ro.ida_rtol;
      ip.atol_u = ro.ida_atol > 0.0 ? ro.ida_atol : 1e-3 * ro.ida_rtol * diag;
      ip.atol_z = ip.atol_u * cfg.material.young / diag;
      ip.linear_solver = ro.linear_solver;
      IdaStats before;
      const IdaStats st =
          dae.integrate(0.0, t_end, n_steps, ip, [&](int k, double t, const Vector<double>& y) {
            dae.apply_state(y);
            const IdaStats& now = dae.stats();
            const long its = now.newton_iterations - before.newton_iterations;
            if (k > 0)
              per_step.push_back(
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
            record(k, t, k == 0 ? 0 : static_cast<int>(its),
                   k == 0 || k % cfg.output.every == 0 || k == n_steps);
          });
      total_newton = st.newton_iterations;
      total_assembly = st.residual_seconds + st.jacobian_seconds;
      total_solve = st.solve_seconds;
      total_newton_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - ida_start).count();
      ida_summary = {{"rtol", ip.rtol},
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
      if (log)
        *log << "reference: IDA " << st.steps << " steps (" << st.step_attempts << " attempts), "
             << st.residual_evaluations << " residuals, " << st.newton_iterations << " Newton iterations, "
             << st.jacobian_setups << " Jacobian setups\n";
    }

    nlohmann::json summary;
    if (root) {
      H5File h5 = H5File::create(out->file("timeseries.h5"));
      for (const auto& s : table.series()) {
        h5.write("/series/" + s.name, s.values, {s.values.size()});
        h5.set_attribute("/series/" + s.name, "unit", s.unit);
      }
      h5.set_attribute("/", "case", cfg.name);
      h5.set_attribute("/", "model", "reference");
      h5.close();
      disp_h5->set_attribute("/u", "unit", "m");
      disp_h5->set_attribute(
          "/u", "layout",
          "rows: field frames; columns: 3*node + component (tmlab node order; vertex values)");
      disp_h5->close();
      if (!pvd.empty()) {
        std::ofstream pvd_file(out->file("result.pvd"));
        DataOutBase::write_pvd_record(pvd_file, pvd);
      }
      fs::remove(out->file("vtu/.keep"));

      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
      summary = {{"case", cfg.name},
                 {"description", cfg.description},
                 {"model", "reference"},
                 {"mesh",
                  {{"file", cfg.mesh.file},
                   {"points", n_nodes},
                   {"tets", hex ? 0 : mesh.num_tets()},
                   {"cells", coarse.n_active_cells()},
                   {"cell_type", hex ? "hex" : "tet"},
                   {"volume_m3", report.total_volume},
                   {"orientation_repaired", repaired}}},
                 {"material",
                  {{"law", material.name()},
                   {"E", cfg.material.young},
                   {"nu", cfg.material.poisson},
                   {"density", cfg.material.density},
                   {"lambda", material.lambda},
                   {"mu", material.mu}}},
                 {"discretisation",
                  {{"element", hex ? "FE_Q" : "FE_SimplexP"},
                   {"degree", ro.degree},
                   {"n_dofs", solid.n_dofs()},
                   {"mpi_ranks", n_ranks}}},
                 {"solver",
                  {{"type", "static"},
                   {"load_steps", n_steps},
                   {"newton_iterations", total_newton},
                   {"linear_iterations", total_linear},
                   {"cutbacks", total_cutbacks},
                   {"linear_solver", ro.linear_solver},
                   {"newton_rtol", ro.newton_rtol},
                   {"assembly_seconds", total_assembly},
                   {"solve_seconds", total_solve},
                   {"newton_seconds", total_newton_s},
                   {"steps", per_step},
                   {"time_integration", ro.time_integration}}},
                 {"final_time", table.last("time")},
                 {"max_displacement_m", table.last("max_displacement")},
                 {"elastic_energy_J", table.last("elastic_energy")},
                 {"min_volume_ratio", jmin_overall},
                 {"min_volume_ratio_over", "all recorded steps, t = 0 included"},
                 {"field_frames", field_frames},
                 {"plots", "skipped"},
                 {"run_seconds", wall}};
      if (vs.enabled)
        summary["material"]["viscoelastic"] = {{"convention", to_string(vs.convention)},
                                               {"weights", vs.weights},
                                               {"taus", vs.taus},
                                               {"alpha", prony->alpha},
                                               {"integration", to_string(vs.integration)},
                                               {"relaxation", to_string(vs.relaxation)},
                                               {"history", "pk2"}};
      if (use_ida) summary["solver"]["ida"] = ida_summary;
      nlohmann::json reac = nlohmann::json::object();
      for (int k = 0; k < solid.n_conditions(); ++k) {
        const std::string& n = solid.condition_name(k);
        reac[n] = series_names::last_vector(table, series_names::reaction(n));
      }
      summary["final_reactions_N"] = reac;
      nlohmann::json probes = nlohmann::json::object();
      for (std::size_t k = 0; k < probe_nodes.size(); ++k) {
        const std::string& n = cfg.output.probes[k].name;
        probes[n] = {{"node", probe_nodes[k]},
                     {"displacement_m", series_names::last_vector(table, series_names::probe(n))}};
      }
      summary["probes"] = probes;
      out->finalize(summary);
    }
    const std::string text = Utilities::MPI::broadcast(comm, root ? summary.dump() : std::string(), 0);
    const std::string dir = (fs::path(opt.results_root) / result_name).string();
    return {dir, nlohmann::json::parse(text)};
  } catch (const std::exception& e) {
    if (out) out->abandon(e);
    throw;
  }
}

}  // namespace tmlab::ref
