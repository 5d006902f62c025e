#include "tensormass/runner/case_runner.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/base/process.hpp"
#include "core/base/progress.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/io/vtu_writer.hpp"
#include "core/io/xdmf_writer.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"
#include "core/results/run_output.hpp"
#include "core/results/series_names.hpp"
#include "core/results/series_table.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/solvers/explicit_dynamics.hpp"
#include "tensormass/solvers/implicit_dynamics.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <sstream>

namespace tmlab::tm {

namespace fs = std::filesystem;

namespace {

/// Smallest deformed-to-rest volume ratio J over all tets, and where it occurs.
std::pair<double, Index> min_volume_ratio(const Mesh& mesh, const VecX& u) {
  double jmin = std::numeric_limits<double>::infinity();
  Index where = -1;
  for (Index t = 0; t < mesh.num_tets(); ++t) {
    Vec3 x[4], X[4];
    for (int a = 0; a < 4; ++a) {
      X[a] = mesh.points[mesh.tets[t][a]];
      x[a] = X[a] + u.segment<3>(3 * mesh.tets[t][a]);
    }
    const double v0 = (X[1] - X[0]).dot((X[2] - X[0]).cross(X[3] - X[0]));
    const double v = (x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0]));
    const double j = v / v0;
    if (j < jmin) {
      jmin = j;
      where = t;
    }
  }
  return {jmin, where};
}

std::vector<Vec3> as_vec3(const VecX& u) {
  std::vector<Vec3> out(static_cast<std::size_t>(u.size() / 3));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = u.segment<3>(3 * static_cast<Eigen::Index>(i));
  return out;
}

/// The iteration history of a run, one entry per step, for summary.json ("solver.newton"):
/// iterations, cut-backs, sub-increments, backtracks, the final |R| and its target, whether the
/// step stopped at round-off, and the residual history of the last (sub-)increment.
class NewtonLog {
 public:
  void add(const NewtonResult& last, int iterations, int cutbacks, int sub_increments, bool at_roundoff) {
    iterations_.push_back(iterations);
    cutbacks_.push_back(cutbacks);
    sub_increments_.push_back(sub_increments);
    backtracks_.push_back(last.backtracks);
    residual_.push_back(last.residual_final);
    target_.push_back(last.target);
    roundoff_.push_back(at_roundoff);
    history_.push_back(last.history);
  }
  nlohmann::json json(const SolverSpec& s) const {
    int roundoff_steps = 0, max_its = 0;
    for (bool b : roundoff_) roundoff_steps += b ? 1 : 0;
    for (int i : iterations_) max_its = std::max(max_its, i);
    return {{"line_search", to_string(s.line_search)},
            {"rtol", s.rtol},
            {"atol", s.atol},
            {"max_iterations", s.max_iterations},
            {"max_iterations_in_a_step", max_its},
            {"steps_at_roundoff", roundoff_steps},
            {"per_step",
             {{"iterations", iterations_},
              {"cutbacks", cutbacks_},
              {"sub_increments", sub_increments_},
              {"backtracks_last_solve", backtracks_},
              {"residual_final", residual_},
              {"residual_target", target_},
              {"at_roundoff", roundoff_},
              {"residual_history_last_solve", history_}}}};
  }

 private:
  std::vector<int> iterations_, cutbacks_, sub_increments_, backtracks_;
  std::vector<double> residual_, target_;
  std::vector<bool> roundoff_;
  std::vector<std::vector<double>> history_;
};
}  // namespace

NewtonOptions newton_options(const SolverSpec& s) {
  NewtonOptions o;
  o.max_iterations = s.max_iterations;
  o.rtol = s.rtol;
  o.atol = s.atol;
  o.line_search = s.line_search;
  return o;
}

RunResult run_case(const CaseConfig& cfg, const RunOptions& opt) {
  const auto wall0 = std::chrono::steady_clock::now();
  std::ostream* log = opt.log;

  // ---- Geometry: read, scale, check. An inverted or degenerate tet stops the run here. ----
  MeshReport report;
  int repaired = 0;
  Mesh mesh = load_case_mesh(cfg.mesh, report, repaired);
  const double size = (report.bbox_max - report.bbox_min).norm();

  // ---- Material and elastic model. ----
  const StVenantKirchhoff material =
      StVenantKirchhoff::from_young_poisson(cfg.material.young, cfg.material.poisson);
  std::unique_ptr<ElasticModel> model;
  const ViscoelasticStVK* visco = nullptr;
  const ViscoelasticSpec& vs = cfg.material.viscoelastic;
  if (vs.enabled) {
    // Prony-series viscoelasticity on the tensor-mass model; material.E is the long-term modulus.
    if (cfg.model == CaseModel::TlOracle)
      throw Error(
          cfg.file +
          ": key 'model': the tl_oracle kernel is elastic only; use tensor_mass for a viscoelastic material");
    const PronySeries prony = vs.convention == PronyConvention::Instantaneous
                                  ? PronySeries::from_instantaneous(vs.weights, vs.taus)
                                  : PronySeries::from_long_term(vs.weights, vs.taus);
    ViscoelasticOptions vo;
    vo.history = vs.history;
    vo.integration = vs.integration;
    vo.relaxation = vs.relaxation;
    auto vm = std::make_unique<ViscoelasticStVK>(mesh, material, prony, vo);
    visco = vm.get();
    model = std::move(vm);
  } else if (cfg.model == CaseModel::TlOracle) {
    model = std::make_unique<TotalLagrangianStVK>(mesh, material);
  } else {
    model = std::make_unique<TensorMassStVK>(mesh, material);
  }
  const TotalLagrangianStVK fields_kernel(mesh, material);  // per-tet F, E, S for output

  // ---- Boundary conditions and loads from the node/face selectors. ----
  const VecX node_mass = lumped_node_mass(mesh, cfg.material.density);
  std::vector<DirichletCondition> conditions;
  for (std::size_t i = 0; i < cfg.boundary.size(); ++i) {
    const auto& b = cfg.boundary[i];
    DirichletCondition c{b.name, select_nodes(mesh, b.nodes), b.components, b.value, b.function};
    if (c.nodes.empty())
      throw Error(cfg.file + ": boundary[" + std::to_string(i) + "] '" + b.name + "' selects no nodes");
    conditions.push_back(std::move(c));
  }
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
  const MechanicalSystem system(*model, lumped_dof_mass(node_mass),
                                DirichletSet(mesh.num_points(), conditions), loads,
                                RayleighDamping{cfg.solver.damping_alpha, cfg.solver.damping_beta});
  if (system.bc().dofs().empty() && cfg.solver.type == SolverSpec::Type::Static)
    throw Error(cfg.file + ": a static run needs boundary conditions that stop rigid motion (none given)");

  std::vector<Index> probe_nodes;
  for (const auto& p : cfg.output.probes) probe_nodes.push_back(probe_node(mesh, p, cfg.file));

  // ---- Result directory (staged; summary.json only when everything succeeded). ----
  RunOutput out(fs::path(opt.results_root) / cfg.name, log);
  try {
    ManifestInput mi;
    mi.command_line = opt.command_line;
    mi.config = effective_case_json(cfg);
    mi.input_files.push_back(cfg.mesh.file);
    if (fs::exists(cfg.file)) mi.input_files.push_back(cfg.file);
    out.write_json("manifest.json", make_manifest(mi));
    out.write_json("mesh_report.json", mesh_report_json(report));

    std::unique_ptr<XdmfTimeSeries> xdmf;
    if (cfg.output.xdmf) xdmf = std::make_unique<XdmfTimeSeries>(out.file("fields.xdmf"), mesh);
    std::unique_ptr<PvdWriter> pvd;
    if (cfg.output.vtu) pvd = std::make_unique<PvdWriter>(out.file("result.pvd"));
    // Nodal displacements at every field frame, in mesh node order: what `tmlab compare` diffs
    // against the deal.II reference (which writes the same file).
    H5File disp_h5 = H5File::create(out.file("displacement.h5"));

    SeriesTable table;
    VecX u = VecX::Zero(system.num_dofs());
    VecX v = VecX::Zero(system.num_dofs());
    VecX fint, fext;
    long total_newton = 0, total_cutbacks = 0;
    int field_frames = 0;
    double jmin_overall = 1.0;
    // Work of the loads and supports on the body, by the trapezoidal rule over the recorded steps:
    // W += 1/2 (F_n + F_{n+1}) . (u_{n+1} - u_n), F = f_ext + reactions (exact for quasi-static
    // runs; in dynamics the reactions leave out the inertia of the prescribed nodes).
    double external_work = 0.0;
    VecX f_applied_prev = VecX::Zero(system.num_dofs()), u_prev = VecX::Zero(system.num_dofs());

    // Writes the scalar series of one step and, when asked, the fields.
    auto record = [&](int step, double t, int newton_its, bool write_fields) {
      const auto [jmin, jtet] = min_volume_ratio(mesh, u);
      if (!(jmin > 0.0)) {
        std::ostringstream m;
        m << mesh.tet_name(jtet) << " inverted at t = " << t << " (step " << step << ", volume ratio " << jmin
          << "): the load is beyond what the St Venant-Kirchhoff tet mesh survives; reduce the load or "
             "refine the mesh";
        throw Error(m.str());
      }
      jmin_overall = std::min(jmin_overall, jmin);
      model->internal_force(u, fint);
      system.loads().assemble(u, t, fext);
      const VecX r = fint - fext;
      VecX f_applied = fext;
      for (Index d : system.bc().dofs()) f_applied[d] += r[d];
      external_work += 0.5 * (f_applied_prev + f_applied).dot(u - u_prev);
      f_applied_prev = f_applied;
      u_prev = u;
      double umax = 0.0;
      for (Index i = 0; i < mesh.num_points(); ++i) umax = std::max(umax, u.segment<3>(3 * i).norm());
      table.add("time", "s", t);
      table.add("max_displacement", "m", umax);
      // Stored energy: the elastic energy, or for a viscoelastic material the long-term spring plus
      // the Maxwell-branch energies of the committed state (the same definition as the deal.II
      // reference); dissipation is the model's own count.
      table.add(
          "elastic_energy", "J",
          visco ? visco->committed_elastic_energy() + visco->committed_branch_energy() : model->energy(u));
      if (visco) {
        table.add("spring_energy", "J", visco->committed_elastic_energy());
        table.add("branch_energy", "J", visco->committed_branch_energy());
        table.add("dissipated_energy", "J", visco->total_dissipation());
        table.add("step_dissipation", "J", visco->step_dissipation());
      }
      table.add("external_work", "J", external_work);
      table.add("kinetic_energy", "J", 0.5 * v.dot(system.mass().cwiseProduct(v)));
      table.add("min_volume_ratio", "1", jmin);
      table.add("newton_iterations", "1", newton_its);
      for (std::size_t k = 0; k < conditions.size(); ++k) {
        const Vec3 rk = system.bc().resultant(k, r);
        series_names::add_vector(table, series_names::reaction(conditions[k].name), "N", rk.x(), rk.y(),
                                 rk.z());
      }
      for (std::size_t k = 0; k < probe_nodes.size(); ++k) {
        const Vec3 up = u.segment<3>(3 * probe_nodes[k]);
        const std::string& n = cfg.output.probes[k].name;
        series_names::add_vector(table, series_names::probe(n), "m", up.x(), up.y(), up.z());
      }
      if (!write_fields) return;
      disp_h5.append_row("/u", std::vector<double>(u.data(), u.data() + u.size()));
      disp_h5.append("/time", t);
      // Fields: displacement, velocity; per tet volume ratio, Green strain, Cauchy stress, von Mises.
      std::vector<double> jratio(mesh.tets.size()), vm(mesh.tets.size());
      std::vector<Eigen::Matrix3d> strain(mesh.tets.size()), cauchy(mesh.tets.size());
      for (Index t2 = 0; t2 < mesh.num_tets(); ++t2) {
        const Eigen::Matrix3d F = fields_kernel.deformation_gradient(t2, u);
        const Eigen::Matrix3d E = 0.5 * (F.transpose() * F - Eigen::Matrix3d::Identity());
        const Eigen::Matrix3d S = material.pk2_stress(E);
        const double J = F.determinant();
        const Eigen::Matrix3d sigma = F * S * F.transpose() / J;
        const Eigen::Matrix3d dev = sigma - sigma.trace() / 3.0 * Eigen::Matrix3d::Identity();
        jratio[t2] = J;
        strain[t2] = E;
        cauchy[t2] = sigma;
        vm[t2] = std::sqrt(1.5 * dev.cwiseProduct(dev).sum());
      }
      const auto disp = as_vec3(u), vel = as_vec3(v);
      std::vector<double> umag(disp.size());
      for (std::size_t i = 0; i < disp.size(); ++i) umag[i] = disp[i].norm();
      if (xdmf) {
        xdmf->begin_step(t);
        xdmf->add_point_vector("displacement", disp);
        xdmf->add_point_vector("velocity", vel);
        xdmf->add_cell_scalar("volume_ratio", jratio);
        xdmf->add_cell_scalar("von_mises", vm);
        xdmf->add_cell_tensor("green_strain", strain);
        xdmf->add_cell_tensor("cauchy_stress", cauchy);
        xdmf->flush();
      }
      if (pvd) {
        VtuWriter w(mesh);
        w.set_displacement(disp);
        w.add_point_vector("displacement", disp);
        w.add_point_scalar("displacement_magnitude", umag);
        w.add_point_vector("velocity", vel);
        w.add_cell_scalar("volume_ratio", jratio);
        w.add_cell_scalar("von_mises", vm);
        w.add_cell_tensor("green_strain", strain);
        w.add_cell_tensor("cauchy_stress", cauchy);
        char name[64];
        std::snprintf(name, sizeof name, "vtu/step_%05d.vtu", field_frames);
        w.write(out.file(name));
        pvd->add(t, out.file(name));
      }
      ++field_frames;
    };

    const int n_steps = cfg.solver.steps;
    const double t_end = cfg.solver.t_end;
    std::unique_ptr<ProgressReporter> reporter;
    if (log) {
      ProgressOptions po;
      po.label = cfg.name;
      reporter = std::make_unique<ProgressReporter>(n_steps, po);
    }
    // After every recorded step: progress, and a safe point at which SIGINT/SIGTERM stop the run.
    auto progress = [&](int step, double t) {
      if (reporter) reporter->update(step, t);
      check_interrupt("at t = " + std::to_string(t) + " s (step " + std::to_string(step) + " of " +
                      std::to_string(n_steps) + ")");
    };

    nlohmann::json solver_info;
    record(0, 0.0, 0, true);
    if (cfg.solver.type == SolverSpec::Type::Static) {
      StaticSolver solver(system, newton_options(cfg.solver), cfg.solver.max_cutbacks);
      NewtonLog newton_log;
      for (int k = 1; k <= n_steps; ++k) {
        const double t0 = t_end * (k - 1) / n_steps, t1 = t_end * k / n_steps;
        const StaticStepReport rep = solver.advance(t0, t1, u);
        total_newton += rep.newton_iterations;
        total_cutbacks += rep.cutbacks;
        newton_log.add(rep.newton, rep.newton_iterations, rep.cutbacks, rep.sub_increments, rep.at_roundoff);
        record(k, t1, rep.newton_iterations, k % cfg.output.every == 0 || k == n_steps);
        progress(k, t1);
      }
      solver_info = {{"type", "static"},
                     {"load_steps", n_steps},
                     {"newton_iterations", total_newton},
                     {"cutbacks", total_cutbacks},
                     {"newton", newton_log.json(cfg.solver)}};
    } else if (cfg.solver.type == SolverSpec::Type::Explicit) {
      const double dt = cfg.solver.dt;
      CentralDifference integ(system, dt, cfg.solver.check_stability);
      integ.set_displacement_limit(10.0 * size);
      integ.initialize(0.0, u, v);
      const int series_every = std::max(1, n_steps / 4000);
      double t = 0.0;
      for (int k = 1; k <= n_steps; ++k) {
        integ.step(t, dt);
        t = integ.time();
        const bool fields = k % cfg.output.every == 0 || k == n_steps;
        if (fields || k % series_every == 0) {
          u = integ.displacement();
          v = integ.velocity();
          record(k, t, 0, fields);
          progress(k, t);
        }
      }
      const auto& st = integ.stability();
      solver_info = {{"type", "explicit"},
                     {"scheme", "central_difference"},
                     {"dt", dt},
                     {"steps", n_steps},
                     {"dt_critical_estimate", st.dt_critical},
                     {"dt_guaranteed", st.dt_guaranteed},
                     {"omega_max", st.omega_max},
                     {"damping", {{"alpha", cfg.solver.damping_alpha}, {"beta", cfg.solver.damping_beta}}}};
    } else {
      const ImplicitScheme scheme = cfg.solver.scheme;
      ImplicitDynamics integ(system, scheme, newton_options(cfg.solver));
      NewtonLog newton_log;
      integ.initialize(0.0, u, v);
      double t = 0.0;
      for (int k = 1; k <= n_steps; ++k) {
        const double dt = std::min(cfg.solver.dt, t_end - t);
        const NewtonResult nr = integ.step(t, dt);
        t = integ.time();
        total_newton += nr.iterations;
        newton_log.add(nr, nr.iterations, 0, 1, nr.at_roundoff);
        u = integ.displacement();
        v = integ.velocity();
        record(k, t, nr.iterations, k % cfg.output.every == 0 || k == n_steps);
        progress(k, t);
      }
      solver_info = {{"type", "implicit"},
                     {"scheme", to_string(cfg.solver.scheme)},
                     {"dt", cfg.solver.dt},
                     {"steps", n_steps},
                     {"newton_iterations", total_newton},
                     {"newton", newton_log.json(cfg.solver)},
                     {"damping", {{"alpha", cfg.solver.damping_alpha}, {"beta", cfg.solver.damping_beta}}}};
    }
    if (reporter) reporter->finish();

    // ---- Numbers: timeseries.h5 (one 1-D dataset per quantity, with its unit). ----
    {
      H5File h5 = H5File::create(out.file("timeseries.h5"));
      for (const auto& s : table.series()) {
        h5.write("/series/" + s.name, s.values, {s.values.size()});
        h5.set_attribute("/series/" + s.name, "unit", s.unit);
      }
      h5.set_attribute("/", "case", cfg.name);
      h5.close();
    }
    disp_h5.set_attribute("/u", "unit", "m");
    disp_h5.set_attribute("/u", "layout",
                          "rows: field frames; columns: 3*node + component (tmlab node order)");
    disp_h5.close();
    if (xdmf) xdmf->close();
    if (pvd) pvd->write();

    // ---- Plots (PNG through matplotlib; a missing python3/matplotlib is reported, not fatal). ----
    nlohmann::json plots = nlohmann::json::array();
    plots.push_back({{"file", "displacement.png"},
                     {"x", "time"},
                     {"y", {"max_displacement"}},
                     {"title", cfg.name + ": largest displacement"},
                     {"xlabel", "time [s]"},
                     {"ylabel", "displacement [m]"}});
    nlohmann::json reactions = nlohmann::json::array();
    for (const auto& c : conditions)
      reactions.push_back(series_names::component(series_names::reaction(c.name), "norm"));
    if (!reactions.empty())
      plots.push_back({{"file", "reaction.png"},
                       {"x", "time"},
                       {"y", reactions},
                       {"title", cfg.name + ": reaction forces"},
                       {"xlabel", "time [s]"},
                       {"ylabel", "|reaction| [N]"}});
    nlohmann::json energy_series = {"elastic_energy", "kinetic_energy", "external_work"};
    if (visco) {
      energy_series.push_back("spring_energy");
      energy_series.push_back("branch_energy");
      energy_series.push_back("dissipated_energy");
    }
    plots.push_back({{"file", "energy.png"},
                     {"x", "time"},
                     {"y", energy_series},
                     {"title", cfg.name + ": energies"},
                     {"xlabel", "time [s]"},
                     {"ylabel", "energy [J]"}});
    if (!probe_nodes.empty()) {
      nlohmann::json py = nlohmann::json::array();
      for (const auto& p : cfg.output.probes)
        py.push_back(series_names::component(series_names::probe(p.name), "norm"));
      plots.push_back({{"file", "probes.png"},
                       {"x", "time"},
                       {"y", py},
                       {"title", cfg.name + ": probe displacements"},
                       {"xlabel", "time [s]"},
                       {"ylabel", "|u| [m]"}});
    }
    out.write_json("plots.json", plots);
    std::string plot_status = "skipped";
    if (opt.plots && cfg.output.plots) {
      const fs::path script = fs::path(opt.tmlab_root) / "core" / "results" / "python" / "tmlab_plot.py";
      const ProcessStatus ps =
          run_python(script, {out.staging_dir().string()}, ProcessOutput::to_file(out.file("plots.log")));
      const int rc = ps.ok() ? 0 : 1;
      plot_status = rc == 0 ? "ok" : "failed (see plots.log)";
      if (rc != 0 && log)
        *log << "  warning: plotting failed (see plots.log); the numbers are in timeseries.h5\n";
    }

    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    nlohmann::json summary = {{"case", cfg.name},
                              {"description", cfg.description},
                              {"model", to_string(cfg.model)},
                              {"mesh",
                               {{"file", cfg.mesh.file},
                                {"points", mesh.num_points()},
                                {"tets", mesh.num_tets()},
                                {"volume_m3", report.total_volume},
                                {"orientation_repaired", repaired}}},
                              {"material",
                               {{"law", "stvk"},
                                {"E", cfg.material.young},
                                {"nu", cfg.material.poisson},
                                {"density", cfg.material.density},
                                {"lambda", material.lambda},
                                {"mu", material.mu}}},
                              {"solver", solver_info},
                              {"final_time", table.last("time")},
                              {"max_displacement_m", table.last("max_displacement")},
                              {"elastic_energy_J", table.last("elastic_energy")},
                              {"min_volume_ratio", jmin_overall},
                              {"min_volume_ratio_over", "all recorded steps, t = 0 included"},
                              {"field_frames", field_frames},
                              {"plots", plot_status},
                              {"run_seconds", wall}};
    nlohmann::json reac = nlohmann::json::object();
    for (const auto& c : conditions)
      reac[c.name] = series_names::last_vector(table, series_names::reaction(c.name));
    summary["final_reactions_N"] = reac;
    {
      // Energy balance: work in = stored (+ kinetic) + dissipated.
      const double stored = table.last("elastic_energy");
      const double kinetic = table.last("kinetic_energy");
      const double dissipated = visco ? visco->total_dissipation() : 0.0;
      summary["energy"] = {{"external_work_J", external_work},
                           {"stored_J", stored},
                           {"kinetic_J", kinetic},
                           {"total_dissipation_J", dissipated},
                           {"balance_residual_J", external_work - stored - kinetic - dissipated}};
    }
    if (visco)
      summary["viscoelastic"] = {{"history", to_string(vs.history)},
                                 {"integration", to_string(vs.integration)},
                                 {"relaxation", to_string(vs.relaxation)},
                                 {"prony_long_term", visco->prony().to_json()}};
    nlohmann::json probes = nlohmann::json::object();
    for (std::size_t k = 0; k < probe_nodes.size(); ++k) {
      const std::string& n = cfg.output.probes[k].name;
      probes[n] = {{"node", probe_nodes[k]},
                   {"displacement_m", series_names::last_vector(table, series_names::probe(n))}};
    }
    summary["probes"] = probes;
    out.finalize(summary);
    return {out.dir().string(), summary};
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
}

}  // namespace tmlab::tm
