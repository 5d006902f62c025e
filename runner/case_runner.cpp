#include "runner/case_runner.hpp"

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
#include "core/results/checkpoint.hpp"
#include "core/results/recorder.hpp"
#include "core/results/run_output.hpp"
#include "core/results/series_names.hpp"
#include "tensormass/contact/contact_checks.hpp"
#include "tensormass/contact/contact_config.hpp"
#include "tensormass/contact/contact_implicit.hpp"
#include "tensormass/contact/contact_solver.hpp"
#include "tensormass/contact/kinematic_contact.hpp"
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/materials/law_factory.hpp"
#include "tensormass/solvers/explicit_dynamics.hpp"
#include "tensormass/solvers/implicit_dynamics.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/viscoelastic/viscoelastic_law.hpp"
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
#include <optional>
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
  void save(CheckpointData& d) const;
  void restore(const CheckpointData& d);
  /// `fallbacks`: the solves of a "cholmod" run that met a tangent that is not positive definite
  /// and used LDL^T (since the start or the resume of the run; -1: not known).
  nlohmann::json json(const SolverSpec& s, int fallbacks = -1) const {
    int roundoff_steps = 0, max_its = 0;
    for (bool b : roundoff_) roundoff_steps += b ? 1 : 0;
    for (int i : iterations_) max_its = std::max(max_its, i);
    nlohmann::json j = {{"line_search", to_string(s.line_search)},
                        {"linear", s.linear == SolverSpec::Linear::Cholmod ? "cholmod" : "ldlt"},
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
    if (s.linear == SolverSpec::Linear::Cholmod && fallbacks >= 0) j["linear_fallbacks_to_ldlt"] = fallbacks;
    return j;
  }

 private:
  std::vector<int> iterations_, cutbacks_, sub_increments_, backtracks_;
  std::vector<double> residual_, target_;
  std::vector<bool> roundoff_;
  std::vector<std::vector<double>> history_;
};

/// The elastic model a case asks for; `visco` is set when it is a viscoelastic one. tensor_mass and
/// tl_oracle are St Venant-Kirchhoff models (the paper's and its oracle): another law is refused
/// with the name of the model that runs it, hyperelastic_tl (HyperelasticTL, any law).
std::unique_ptr<ElasticModel> make_model(const CaseConfig& cfg, const Mesh& mesh,
                                         const StVenantKirchhoff& material, const Law& law,
                                         const ViscoelasticBase*& visco) {
  if (cfg.material.law != MaterialLaw::StVK && cfg.model != CaseModel::HyperelasticTL)
    throw Error(
        cfg.file + ": key 'model': '" + to_string(cfg.model) + "' is " +
        (cfg.model == CaseModel::TensorMass ? "the paper's St Venant-Kirchhoff tensor-mass model"
                                            : "the St Venant-Kirchhoff oracle") +
        "; material.law '" + to_string(cfg.material.law) +
        "' runs on the F-based kernel: set \"model\": \"hyperelastic_tl\" (or --model hyperelastic_tl)");
  const ViscoelasticSpec& vs = cfg.material.viscoelastic;
  if (vs.enabled) {
    // Prony-series viscoelasticity; the law's parameters (material.E for St VK) are the long-term ones.
    if (cfg.model == CaseModel::TlOracle)
      throw Error(
          cfg.file +
          ": key 'model': the tl_oracle kernel is elastic only; use tensor_mass or hyperelastic_tl for "
          "a viscoelastic material");
    const PronySeries prony = vs.convention == PronyConvention::Instantaneous
                                  ? PronySeries::from_instantaneous(vs.weights, vs.taus)
                                  : PronySeries::from_long_term(vs.weights, vs.taus);
    ViscoelasticOptions vo;
    vo.history = vs.history;
    vo.integration = vs.integration;
    vo.relaxation = vs.relaxation;
    if (cfg.model == CaseModel::HyperelasticTL) {
      // The objective scheme on any law (history pk2, relaxation full; the class refuses the rest).
      std::unique_ptr<ViscoelasticHyperelastic> vm;
      try {
        vm = std::make_unique<ViscoelasticHyperelastic>(mesh, law, prony, vo);
      } catch (const Error& e) {
        throw Error(cfg.file + ": key 'material.viscoelastic' (model hyperelastic_tl): " + e.what());
      }
      visco = vm.get();
      return vm;
    }
    auto vm = std::make_unique<ViscoelasticStVK>(mesh, material, prony, vo);
    visco = vm.get();
    return vm;
  }
  if (cfg.model == CaseModel::HyperelasticTL) return std::make_unique<HyperelasticTL>(mesh, law);
  if (cfg.model == CaseModel::TlOracle) return std::make_unique<TotalLagrangianStVK>(mesh, material);
  return std::make_unique<TensorMassStVK>(mesh, material);
}

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

/// The problem a case describes: mesh (read, scaled and checked: an inverted or degenerate tet stops
/// the run here), material, model, constraints, loads and probes. Built in place and never moved:
/// the model, loads and system refer to the mesh.
struct Problem {
  explicit Problem(const CaseConfig& config)
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
  Problem(const Problem&) = delete;
  Problem& operator=(const Problem&) = delete;

  const CaseConfig& cfg;
  MeshReport report;
  int repaired = 0;
  Mesh mesh;
  double size;                 ///< bounding-box diagonal, m
  StVenantKirchhoff material;  ///< the small-strain St VK (the law of tensor_mass and tl_oracle)
  Law law;                     ///< the case's law (hyperelastic_tl; St VK as `material` otherwise)
  /// The model when it is viscoelastic (ViscoelasticStVK or ViscoelasticHyperelastic), else null.
  const ViscoelasticBase* visco = nullptr;
  std::unique_ptr<ElasticModel> model;
  TotalLagrangianStVK fields_kernel;  // per-tet F for output (geometry only: the stress is the law's)
  VecX node_mass;
  std::vector<DirichletCondition> conditions;
  ExternalLoads loads;
  MechanicalSystem system;
  std::vector<Index> probe_nodes;
};

/// The per-tet output fields of a displacement u: volume ratio J, Green strain E, Cauchy stress
/// sigma = F S F^T / J of the case's law (S = dW/dE; for a viscoelastic material the long-term
/// stress) and its von Mises value.
struct CellFields {
  std::vector<double> jratio, von_mises;
  std::vector<Eigen::Matrix3d> strain, cauchy;
};

CellFields cell_fields(const Problem& p, const VecX& u) {
  const std::size_t n = p.mesh.tets.size();
  CellFields c{std::vector<double>(n), std::vector<double>(n), std::vector<Eigen::Matrix3d>(n),
               std::vector<Eigen::Matrix3d>(n)};
  for (Index t2 = 0; t2 < p.mesh.num_tets(); ++t2) {
    const Eigen::Matrix3d F = p.fields_kernel.deformation_gradient(t2, u);
    const Eigen::Matrix3d E = 0.5 * (F.transpose() * F - Eigen::Matrix3d::Identity());
    const Eigen::Matrix3d S = p.law.pk2_stress(E);
    const double J = F.determinant();
    const Eigen::Matrix3d sigma = F * S * F.transpose() / J;
    const Eigen::Matrix3d dev = sigma - sigma.trace() / 3.0 * Eigen::Matrix3d::Identity();
    c.jratio[t2] = J;
    c.strain[t2] = E;
    c.cauchy[t2] = sigma;
    c.von_mises[t2] = std::sqrt(1.5 * dev.cwiseProduct(dev).sum());
  }
  return c;
}

/// The recorder of the problem's conditions and probes.
Recorder make_recorder(const Problem& p) {
  std::vector<std::string> conditions, probes;
  for (const auto& c : p.conditions) conditions.push_back(c.name);
  for (const auto& pr : p.cfg.output.probes) probes.push_back(pr.name);
  return Recorder(conditions, probes, p.probe_nodes);
}

/// Records the steps of a run: the scalar series (core::Recorder), the work of the loads and
/// supports, and at field frames displacement.h5, fields.xdmf and vtu/.
class StepRecorder {
 public:
  StepRecorder(const Problem& p, const RunOutput& out)
      : p_(p),
        out_(out),
        rec_(make_recorder(p)),
        f_applied_prev_(VecX::Zero(p.system.num_dofs())),
        u_prev_(VecX::Zero(p.system.num_dofs())) {
    if (p.cfg.output.xdmf) xdmf_ = std::make_unique<XdmfTimeSeries>(out.file("fields.xdmf"), p.mesh);
    if (p.cfg.output.vtu) pvd_ = std::make_unique<PvdWriter>(out.file("result.pvd"));
    // Nodal displacements at every field frame, in mesh node order: what `tmlab compare` diffs
    // against the deal.II reference (which writes the same file).
    rec_.open_displacements(out.file("displacement.h5"));
  }

  /// Records the scalar series of one step and, when asked, the fields.
  void record(int step, double t, const VecX& u, const VecX& v, int newton_its, bool write_fields) {
    rec_.record(values(step, t, u, v, newton_its));
    if (write_fields) fields(t, u, v);
  }

  /// Writes timeseries.h5 and closes the field files.
  void close() {
    rec_.write_timeseries(out_.file("timeseries.h5"), {{"case", p_.cfg.name}});
    rec_.close_displacements("");
    if (xdmf_) xdmf_->close();
    if (pvd_) pvd_->write();
  }

  const Recorder& recorder() const { return rec_; }
  double external_work() const { return external_work_; }
  /// The contact outputs recorded with every later step (the contact solver's own state, which
  /// must outlive the recording): the per-body series, the nodal contact forces in the work of
  /// the loads, and the contact pressure field.
  void set_contact(const std::vector<ContactBodyState>* states) { contact_ = states; }

  /// Checkpoints: the series so far, the work bookkeeping and every field frame (t, u, v); restore()
  /// rewrites the field files by replaying the frames, so they never depend on the interrupted files.
  void save(CheckpointData& d) const;
  void restore(const CheckpointData& d);

 private:
  Recorder::StepValues values(int step, double t, const VecX& u, const VecX& v, int newton_its) {
    const auto [jmin, jtet] = min_volume_ratio(p_.mesh, u);
    if (!(jmin > 0.0)) {
      std::ostringstream m;
      m << p_.mesh.tet_name(jtet) << " inverted at t = " << t << " (step " << step << ", volume ratio "
        << jmin << "): the load is beyond what the " << p_.law.name()
        << " tet mesh survives; reduce the load or refine the mesh";
      throw Error(m.str());
    }
    p_.model->internal_force(u, fint_);
    p_.system.loads().assemble(u, t, fext_);
    const VecX r = fint_ - fext_;
    // Work of the loads and supports on the body, by the trapezoidal rule over the recorded steps:
    // W += 1/2 (F_n + F_{n+1}) . (u_{n+1} - u_n), F = f_ext + reactions (exact for quasi-static
    // runs; in dynamics the reactions leave out the inertia of the prescribed nodes).
    VecX f_applied = fext_;
    for (Index d : p_.system.bc().dofs()) f_applied[d] += r[d];
    if (contact_) add_contact_forces(*contact_, f_applied);
    external_work_ += 0.5 * (f_applied_prev_ + f_applied).dot(u - u_prev_);
    f_applied_prev_ = f_applied;
    u_prev_ = u;
    Recorder::StepValues s;
    s.time = t;
    for (Index i = 0; i < p_.mesh.num_points(); ++i)
      s.max_displacement = std::max(s.max_displacement, u.segment<3>(3 * i).norm());
    // Stored energy: the elastic energy, or for a viscoelastic material the long-term spring plus
    // the Maxwell-branch energies of the committed state (the same definition as the deal.II
    // reference); dissipation is the model's own count.
    if (const ViscoelasticBase* m = p_.visco) {
      s.elastic_energy = m->committed_elastic_energy() + m->committed_branch_energy();
      s.extras = {{series_names::kSpringEnergy, "J", m->committed_elastic_energy()},
                  {series_names::kBranchEnergy, "J", m->committed_branch_energy()},
                  {series_names::kDissipatedEnergy, "J", m->total_dissipation()},
                  {series_names::kStepDissipation, "J", m->step_dissipation()}};
    } else {
      s.elastic_energy = p_.model->energy(u);
    }
    s.extras.push_back({series_names::kExternalWork, "J", external_work_});
    s.kinetic_energy = 0.5 * v.dot(p_.system.mass().cwiseProduct(v));
    s.min_volume_ratio = jmin;
    s.newton_iterations = newton_its;
    for (std::size_t k = 0; k < p_.conditions.size(); ++k) {
      const Vec3 rk = p_.system.bc().resultant(k, r);
      s.reactions.push_back({rk.x(), rk.y(), rk.z()});
    }
    for (Index n : p_.probe_nodes) {
      const Vec3 up = u.segment<3>(3 * n);
      s.probes.push_back({up.x(), up.y(), up.z()});
    }
    if (contact_)
      for (const ContactBodyState& b : *contact_) s.contact.push_back(contact_values(b));
    return s;
  }

  static series_names::ContactValues contact_values(const ContactBodyState& b) {
    double max_pressure = 0.0;
    for (double pr : b.pressure) max_pressure = std::max(max_pressure, pr);
    return series_names::contact_values(b, max_pressure);
  }

  /// The contact forces on the sample's nodes, added to f.
  static void add_contact_forces(const std::vector<ContactBodyState>& states, VecX& f) {
    for (const ContactBodyState& b : states)
      for (std::size_t i = 0; i < b.nodes.size(); ++i)
        f.segment<3>(3 * static_cast<Eigen::Index>(b.nodes[i])) += b.nodal_force[i];
  }

  /// The nodal contact pressure of all bodies (0 off contact), Pa.
  std::vector<double> contact_pressure() const {
    std::vector<double> pr(static_cast<std::size_t>(p_.mesh.num_points()), 0.0);
    for (const ContactBodyState& b : *contact_)
      for (std::size_t i = 0; i < b.nodes.size(); ++i)
        pr[static_cast<std::size_t>(b.nodes[i])] += b.pressure[i];
    return pr;
  }

  /// Fields: displacement, velocity; per tet volume ratio, Green strain, Cauchy stress, von Mises.
  /// `pressure`: the contact pressure of a frame replayed from a checkpoint (null: the current one).
  void fields(double t, const VecX& u, const VecX& v, const std::vector<double>* pressure = nullptr) {
    const std::vector<double> pc = !contact_  ? std::vector<double>{}
                                   : pressure ? *pressure
                                              : contact_pressure();
    frames_p_.insert(frames_p_.end(), pc.begin(), pc.end());
    frames_t_.push_back(t);
    frames_u_.insert(frames_u_.end(), u.data(), u.data() + u.size());
    frames_v_.insert(frames_v_.end(), v.data(), v.data() + v.size());
    const int frame = rec_.field_frames();
    rec_.add_field_frame(t, std::vector<double>(u.data(), u.data() + u.size()));
    const CellFields c = cell_fields(p_, u);
    const auto disp = as_vec3(u), vel = as_vec3(v);
    std::vector<double> umag(disp.size());
    for (std::size_t i = 0; i < disp.size(); ++i) umag[i] = disp[i].norm();
    if (xdmf_) {
      xdmf_->begin_step(t);
      xdmf_->add_point_vector("displacement", disp);
      xdmf_->add_point_vector("velocity", vel);
      xdmf_->add_cell_scalar("volume_ratio", c.jratio);
      xdmf_->add_cell_scalar("von_mises", c.von_mises);
      xdmf_->add_cell_tensor("green_strain", c.strain);
      xdmf_->add_cell_tensor("cauchy_stress", c.cauchy);
      if (contact_) xdmf_->add_point_scalar("contact_pressure", pc);
      xdmf_->flush();
    }
    if (pvd_) {
      VtuWriter w(p_.mesh);
      w.set_displacement(disp);
      w.add_point_vector("displacement", disp);
      w.add_point_scalar("displacement_magnitude", umag);
      w.add_point_vector("velocity", vel);
      w.add_cell_scalar("volume_ratio", c.jratio);
      w.add_cell_scalar("von_mises", c.von_mises);
      w.add_cell_tensor("green_strain", c.strain);
      w.add_cell_tensor("cauchy_stress", c.cauchy);
      if (contact_) w.add_point_scalar("contact_pressure", pc);
      char name[64];
      std::snprintf(name, sizeof name, "vtu/step_%05d.vtu", frame);
      w.write(out_.file(name));
      pvd_->add(t, out_.file(name));
    }
  }

  const Problem& p_;
  const RunOutput& out_;
  Recorder rec_;
  std::unique_ptr<XdmfTimeSeries> xdmf_;
  std::unique_ptr<PvdWriter> pvd_;
  VecX fint_, fext_;
  double external_work_ = 0.0;
  VecX f_applied_prev_, u_prev_;
  const std::vector<ContactBodyState>* contact_ = nullptr;
  std::vector<double> frames_t_, frames_u_, frames_v_;  ///< every field frame so far (checkpoints)
  std::vector<double> frames_p_;                        ///< and its contact pressure (contact runs)
};

/// After every recorded step: progress, and a safe point at which SIGINT/SIGTERM stop the run.
class Progress {
 public:
  Progress(const CaseConfig& cfg, std::ostream* log) : n_steps_(cfg.solver.steps) {
    if (!log) return;
    ProgressOptions po;
    po.label = cfg.name;
    reporter_ = std::make_unique<ProgressReporter>(n_steps_, po);
  }
  void operator()(int step, double t) {
    if (reporter_) reporter_->update(step, t);
    check_interrupt("at t = " + std::to_string(t) + " s (step " + std::to_string(step) + " of " +
                    std::to_string(n_steps_) + ")");
  }
  void finish() {
    if (reporter_) reporter_->finish();
  }

 private:
  int n_steps_;
  std::unique_ptr<ProgressReporter> reporter_;
};

/// Displacement u and velocity v of the run, advanced by the stepping functions.
struct State {
  VecX u, v;
};

// ---- Checkpoints (issue 12, core/results/checkpoint.hpp) --------------------------------------

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

class ContactLog;

/// The contact objects of a contact run's loop (null: not in this loop), checkpointed besides the
/// LoopState: the committed contact state (multipliers, active candidates, glued nodes and anchors;
/// the bodies' positions follow from t), the outputs of the last step, and the summary's log.
struct ContactLoop {
  ContactStaticSolver* augmented = nullptr;  ///< static, and implicit dynamics' contact()
  KinematicContact* kinematic = nullptr;     ///< explicit
  ContactImplicitDynamics* implicit = nullptr;
  ContactLog* log = nullptr;
};
void save_contact(CheckpointData& d, const ContactLoop& c);
void restore_contact(const CheckpointData& d, const LoopState& loop, const ContactLoop& c);

/// The run's checkpoint, <result dir>/.incomplete/checkpoint.h5: written at step boundaries when
/// the schedule says so and when a stop was requested; read back by --resume, which restores the
/// state so that the finished result is identical bit for bit to an uninterrupted run.
class RunCheckpoint {
 public:
  RunCheckpoint(const Problem& p, const fs::path& dir, const RunOptions& opt)
      : p_(p),
        path_(dir / RunOutput::kStaging / "checkpoint.h5"),
        fingerprint_(effective_case_json(p.cfg)),
        clock_(opt.checkpoints),
        log_(opt.log) {
    if (opt.resume) resume_ = read_checkpoint(path_, "run", fingerprint_);
  }
  bool resuming() const { return resume_.has_value(); }

  /// After the loop's integrator is initialised: restores the saved state (model, integrator,
  /// loop, recorder and field files) and returns the last completed step (0 when not resuming).
  int restore(StepRecorder& rec, const LoopState& loop, const ContactLoop* contact = nullptr) {
    if (!resume_) return 0;
    const CheckpointData& d = *resume_;
    const int step = static_cast<int>(d.integer("step"));
    loop.t = d.scalar("t");
    loop.s.u = as_vec(d.doubles("u"));
    loop.s.v = as_vec(d.doubles("v"));
    p_.model->restore_committed_state(d.doubles("model.committed"));
    if (loop.central)
      loop.central->restore(loop.t, d.integer("explicit.steps"), loop.s.u,
                            as_vec(d.doubles("explicit.v_half")), loop.s.v);
    if (loop.implicit) loop.implicit->restore(loop.t, loop.s.u, loop.s.v, as_vec(d.doubles("implicit.a")));
    if (loop.newton) loop.newton->restore(d);
    if (loop.total_newton) *loop.total_newton = d.integer("total_newton");
    if (loop.total_cutbacks) *loop.total_cutbacks = d.integer("total_cutbacks");
    if (contact) restore_contact(d, loop, *contact);
    rec.restore(d);
    last_step_ = step;
    if (log_)
      *log_ << "tmlab: resuming '" << p_.cfg.name << "' after step " << step << " (t = " << loop.t
            << ") from " << path_.string() << "\n";
    resume_.reset();  // the memory of the frames is not needed twice
    return step;
  }

  /// At a step boundary, after the step is recorded: writes the checkpoint when it is due or a
  /// stop was requested (SIGINT/SIGTERM; the loop's safe point throws right after).
  void after_step(int step, const StepRecorder& rec, const LoopState& loop,
                  const ContactLoop* contact = nullptr) {
    if (!(pending_interrupt() != 0 || clock_.due(step))) return;
    CheckpointData d;
    d.put_int("step", step);
    d.put_scalar("t", loop.t);
    d.put("u", as_std(loop.s.u));
    d.put("v", as_std(loop.s.v));
    d.put("model.committed", p_.model->committed_state());
    if (loop.central) {
      d.put_int("explicit.steps", loop.central->steps());
      d.put("explicit.v_half", as_std(loop.central->half_step_velocity()));
    }
    if (loop.implicit) d.put("implicit.a", as_std(loop.implicit->acceleration()));
    if (loop.newton) loop.newton->save(d);
    if (loop.total_newton) d.put_int("total_newton", *loop.total_newton);
    if (loop.total_cutbacks) d.put_int("total_cutbacks", *loop.total_cutbacks);
    if (contact) save_contact(d, *contact);
    rec.save(d);
    write_checkpoint(path_, "run", fingerprint_, d);
    clock_.mark();
    last_step_ = step;
  }

  /// For the INTERRUPTED marker: where the checkpoint is and how to continue.
  std::string where() const {
    if (last_step_ < 0) return "; no checkpoint was written: run again without --resume";
    return "; checkpoint after step " + std::to_string(last_step_) + " in " + path_.string() +
           ": continue with the same command and --resume";
  }
  /// The run is complete: its result directory holds no checkpoint.
  void remove() const { remove_checkpoint(path_); }

 private:
  static std::vector<double> as_std(const VecX& x) { return {x.data(), x.data() + x.size()}; }
  static VecX as_vec(const std::vector<double>& x) {
    return Eigen::Map<const VecX>(x.data(), static_cast<Eigen::Index>(x.size()));
  }

  const Problem& p_;
  fs::path path_;
  nlohmann::json fingerprint_;
  CheckpointClock clock_;
  std::ostream* log_;
  std::optional<CheckpointData> resume_;
  int last_step_ = -1;
};

void NewtonLog::save(CheckpointData& d) const {
  auto ints = [](const auto& v) { return std::vector<std::int64_t>(v.begin(), v.end()); };
  d.put("newton.iterations", ints(iterations_));
  d.put("newton.cutbacks", ints(cutbacks_));
  d.put("newton.sub_increments", ints(sub_increments_));
  d.put("newton.backtracks", ints(backtracks_));
  d.put("newton.roundoff", ints(roundoff_));
  d.put("newton.residual", residual_);
  d.put("newton.target", target_);
  std::vector<double> flat;
  std::vector<std::int64_t> lengths;
  for (const auto& h : history_) {
    flat.insert(flat.end(), h.begin(), h.end());
    lengths.push_back(static_cast<std::int64_t>(h.size()));
  }
  d.put("newton.history", flat);
  d.put("newton.history_lengths", lengths);
}

void NewtonLog::restore(const CheckpointData& d) {
  auto ints = [&](const char* name) {
    const auto& v = d.ints(name);
    return std::vector<int>(v.begin(), v.end());
  };
  iterations_ = ints("newton.iterations");
  cutbacks_ = ints("newton.cutbacks");
  sub_increments_ = ints("newton.sub_increments");
  backtracks_ = ints("newton.backtracks");
  roundoff_.clear();
  for (const auto b : d.ints("newton.roundoff")) roundoff_.push_back(b != 0);
  residual_ = d.doubles("newton.residual");
  target_ = d.doubles("newton.target");
  history_.clear();
  const auto& flat = d.doubles("newton.history");
  std::size_t at = 0;
  for (const auto n : d.ints("newton.history_lengths")) {
    if (n < 0 || at + static_cast<std::size_t>(n) > flat.size())
      throw Error(d.source() + ": inconsistent Newton history; run without --resume");
    history_.emplace_back(flat.begin() + static_cast<std::ptrdiff_t>(at),
                          flat.begin() + static_cast<std::ptrdiff_t>(at + static_cast<std::size_t>(n)));
    at += static_cast<std::size_t>(n);
  }
}

void StepRecorder::save(CheckpointData& d) const {
  nlohmann::json names = nlohmann::json::array();
  const auto& series = rec_.table().series();
  for (std::size_t i = 0; i < series.size(); ++i) {
    names.push_back({series[i].name, series[i].unit});
    d.put("series." + std::to_string(i), series[i].values);
  }
  d.put_text("series.names", names.dump());
  d.put_scalar("work.external", external_work_);
  d.put("work.f_applied_prev",
        std::vector<double>(f_applied_prev_.data(), f_applied_prev_.data() + f_applied_prev_.size()));
  d.put("work.u_prev", std::vector<double>(u_prev_.data(), u_prev_.data() + u_prev_.size()));
  d.put("frames.t", frames_t_);
  d.put("frames.u", frames_u_);
  d.put("frames.v", frames_v_);
  if (contact_) d.put("frames.contact_pressure", frames_p_);
}

void StepRecorder::restore(const CheckpointData& d) {
  const nlohmann::json names = nlohmann::json::parse(d.text("series.names"));
  SeriesTable table;
  for (std::size_t i = 0; i < names.size(); ++i)
    for (const double v : d.doubles("series." + std::to_string(i)))
      table.add(names[i][0].get<std::string>(), names[i][1].get<std::string>(), v);
  rec_.restore_series(std::move(table));
  external_work_ = d.scalar("work.external");
  const auto& fp = d.doubles("work.f_applied_prev");
  const auto& up = d.doubles("work.u_prev");
  f_applied_prev_ = Eigen::Map<const VecX>(fp.data(), static_cast<Eigen::Index>(fp.size()));
  u_prev_ = Eigen::Map<const VecX>(up.data(), static_cast<Eigen::Index>(up.size()));
  // The field files again, frame by frame, exactly as the interrupted run wrote them.
  const auto& ft = d.doubles("frames.t");
  const auto& fu = d.doubles("frames.u");
  const auto& fv = d.doubles("frames.v");
  const std::size_t n = static_cast<std::size_t>(p_.system.num_dofs());
  const std::size_t np = static_cast<std::size_t>(p_.mesh.num_points());
  const std::vector<double> none;
  const auto& fpc = contact_ ? d.doubles("frames.contact_pressure") : none;
  if (fu.size() != ft.size() * n || fv.size() != ft.size() * n || (contact_ && fpc.size() != ft.size() * np))
    throw Error(d.source() + ": field frames of the wrong size (another mesh?); run without --resume");
  for (std::size_t f = 0; f < ft.size(); ++f) {
    const auto off = static_cast<std::ptrdiff_t>(f * n);
    const VecX u = Eigen::Map<const VecX>(fu.data() + off, static_cast<Eigen::Index>(n));
    const VecX v = Eigen::Map<const VecX>(fv.data() + off, static_cast<Eigen::Index>(n));
    if (!contact_) {
      fields(ft[f], u, v);
      continue;
    }
    const std::vector<double> pc(fpc.begin() + static_cast<std::ptrdiff_t>(f * np),
                                 fpc.begin() + static_cast<std::ptrdiff_t>((f + 1) * np));
    fields(ft[f], u, v, &pc);
  }
}

bool field_step(const CaseConfig& cfg, int k) { return k % cfg.output.every == 0 || k == cfg.solver.steps; }

/// Static load stepping: solver.steps increments of the load factor t = t_end k / steps.
nlohmann::json step_static(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                           RunCheckpoint& ck) {
  const CaseConfig& cfg = p.cfg;
  const int n_steps = cfg.solver.steps;
  StaticSolver solver(p.system, newton_options(cfg.solver), cfg.solver.max_cutbacks);
  NewtonLog newton_log;
  long total_newton = 0, total_cutbacks = 0;
  double t = 0.0;
  const LoopState loop{s, t, &newton_log, &total_newton, &total_cutbacks, nullptr, nullptr};
  for (int k = ck.restore(rec, loop) + 1; k <= n_steps; ++k) {
    const double t0 = cfg.solver.t_end * (k - 1) / n_steps, t1 = cfg.solver.t_end * k / n_steps;
    const StaticStepReport rep = solver.advance(t0, t1, s.u);
    total_newton += rep.newton_iterations;
    total_cutbacks += rep.cutbacks;
    newton_log.add(rep.newton, rep.newton_iterations, rep.cutbacks, rep.sub_increments, rep.at_roundoff);
    rec.record(k, t1, s.u, s.v, rep.newton_iterations, field_step(cfg, k));
    t = t1;
    ck.after_step(k, rec, loop);
    progress(k, t1);
  }
  return {{"type", "static"},
          {"load_steps", n_steps},
          {"newton_iterations", total_newton},
          {"cutbacks", total_cutbacks},
          {"newton", newton_log.json(cfg.solver, solver.linear_solver().fallbacks())}};
}

/// Explicit central differences; the series at most every steps/4000 steps, the fields as asked.
/// The summary's solver block of an explicit run: the step, the stability estimate, the damping.
nlohmann::json explicit_summary(const CaseConfig& cfg, const StabilityEstimate& st) {
  return {{"type", "explicit"},
          {"scheme", "central_difference"},
          {"dt", cfg.solver.dt},
          {"steps", cfg.solver.steps},
          {"dt_critical_estimate", st.dt_critical},
          {"dt_guaranteed", st.dt_guaranteed},
          {"omega_max", st.omega_max},
          {"damping", {{"alpha", cfg.solver.damping_alpha}, {"beta", cfg.solver.damping_beta}}}};
}

nlohmann::json step_explicit(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                             RunCheckpoint& ck) {
  const CaseConfig& cfg = p.cfg;
  const int n_steps = cfg.solver.steps;
  const double dt = cfg.solver.dt;
  CentralDifference integ(p.system, dt, cfg.solver.check_stability);
  integ.set_displacement_limit(10.0 * p.size);
  integ.initialize(0.0, s.u, s.v);
  const int series_every = std::max(1, n_steps / 4000);
  double t = 0.0;
  const LoopState loop{s, t, nullptr, nullptr, nullptr, &integ, nullptr};
  for (int k = ck.restore(rec, loop) + 1; k <= n_steps; ++k) {
    integ.step(t, dt);
    t = integ.time();
    const bool fields = field_step(cfg, k);
    if (fields || k % series_every == 0) {
      s.u = integ.displacement();
      s.v = integ.velocity();
      rec.record(k, t, s.u, s.v, 0, fields);
      ck.after_step(k, rec, loop);
      progress(k, t);
    }
  }
  return explicit_summary(cfg, integ.stability());
}

/// Implicit dynamics (backward Euler or Newmark), steps of solver.dt up to t_end.
nlohmann::json step_implicit(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                             RunCheckpoint& ck) {
  const CaseConfig& cfg = p.cfg;
  const int n_steps = cfg.solver.steps;
  const ImplicitScheme scheme = cfg.solver.scheme;
  ImplicitDynamics integ(p.system, scheme, newton_options(cfg.solver));
  NewtonLog newton_log;
  long total_newton = 0;
  integ.initialize(0.0, s.u, s.v);
  double t = 0.0;
  const LoopState loop{s, t, &newton_log, &total_newton, nullptr, nullptr, &integ};
  for (int k = ck.restore(rec, loop) + 1; k <= n_steps; ++k) {
    const double dt = std::min(cfg.solver.dt, cfg.solver.t_end - t);
    const NewtonResult nr = integ.step(t, dt);
    t = integ.time();
    total_newton += nr.iterations;
    newton_log.add(nr, nr.iterations, 0, 1, nr.at_roundoff);
    s.u = integ.displacement();
    s.v = integ.velocity();
    rec.record(k, t, s.u, s.v, nr.iterations, field_step(cfg, k));
    ck.after_step(k, rec, loop);
    progress(k, t);
  }
  return {{"type", "implicit"},
          {"scheme", to_string(cfg.solver.scheme)},
          {"dt", cfg.solver.dt},
          {"steps", n_steps},
          {"newton_iterations", total_newton},
          {"newton", newton_log.json(cfg.solver, integ.linear_solver().fallbacks())},
          {"damping", {{"alpha", cfg.solver.damping_alpha}, {"beta", cfg.solver.damping_beta}}}};
}

// ---- Contact (docs/contact.md): the same stepping with the case's rigid bodies. Each function sets
// up its contact object (surface and grid built once, the rig checked against the mesh), records
// t = 0 and steps; the contact state changes only inside the solver's accepted steps.

/// What the summary says about the contact enforcement and its bodies at the end.
class ContactLog {
 public:
  explicit ContactLog(const CaseConfig& cfg) : cfg_(cfg) {}
  void add(const ContactStepReport& r) {
    outer_.push_back(r.outer_iterations_total);
    natural_.push_back(r.natural_residual);
  }
  nlohmann::json json(const std::string& scheme, double eps, double gap_tol,
                      const std::vector<ContactBodyState>& final_state) const {
    nlohmann::json bodies = nlohmann::json::array();
    for (std::size_t b = 0; b < final_state.size(); ++b) {
      const ContactBodyState& st = final_state[b];
      const ContactBodySpec& spec = cfg_.contact.bodies[b];
      double pmax = 0.0;
      for (double pr : st.pressure) pmax = std::max(pmax, pr);
      bodies.push_back({{"name", st.name},
                        {"type", to_string(spec.shape)},
                        {"mode", to_string(spec.mode)},
                        {"final_position_m", {st.position.x(), st.position.y(), st.position.z()}},
                        {"final_force_N", {st.force.x(), st.force.y(), st.force.z()}},
                        {"final_moment_Nm", {st.moment.x(), st.moment.y(), st.moment.z()}},
                        {"final_area_m2", st.area},
                        {"final_radius_m", st.radius_equivalent},
                        {"final_radius_max_m", st.radius_max},
                        {"final_active_nodes", st.active_nodes},
                        {"final_max_pressure_Pa", pmax},
                        {"final_max_penetration_m", st.max_penetration}});
    }
    nlohmann::json j = {{"scheme", scheme}, {"gap_tol_m", gap_tol}, {"bodies", bodies}};
    if (eps > 0.0) {
      j["method"] = to_string(cfg_.contact.method);
      j["stiffness_N_per_m"] = eps;
      j["outer_iterations_per_step"] = outer_;
      j["natural_residual_per_step_m"] = natural_;
    }
    return j;
  }
  void save(CheckpointData& d) const {
    d.put("contact.log.outer", std::vector<std::int64_t>(outer_.begin(), outer_.end()));
    d.put("contact.log.natural", natural_);
  }
  void restore(const CheckpointData& d) {
    const auto& outer = d.ints("contact.log.outer");
    outer_.assign(outer.begin(), outer.end());
    natural_ = d.doubles("contact.log.natural");
  }

 private:
  const CaseConfig& cfg_;
  std::vector<int> outer_;
  std::vector<double> natural_;
};

/// The contact outputs of every body ("contact.out.<b>.*"), exactly.
void save_contact_outputs(CheckpointData& d, const std::vector<ContactBodyState>& states) {
  for (std::size_t b = 0; b < states.size(); ++b) {
    const ContactBodyState& st = states[b];
    const std::string at = "contact.out." + std::to_string(b) + ".";
    d.put_text(at + "name", st.name);
    std::vector<double> x;
    for (const Vec3* v : {&st.position, &st.force, &st.moment}) x.insert(x.end(), {v->x(), v->y(), v->z()});
    x.insert(x.end(), {st.area, st.radius_equivalent, st.radius_max, st.max_penetration, st.complementarity,
                       st.min_multiplier});
    d.put(at + "scalars", x);
    std::vector<std::int64_t> nodes{st.active_nodes};
    nodes.insert(nodes.end(), st.nodes.begin(), st.nodes.end());
    d.put(at + "nodes", nodes);
    std::vector<double> f;
    for (const Vec3& v : st.nodal_force) f.insert(f.end(), {v.x(), v.y(), v.z()});
    d.put(at + "nodal_force", f);
    d.put(at + "gap", st.gap);
    d.put(at + "pressure", st.pressure);
  }
}

std::vector<ContactBodyState> restore_contact_outputs(const CheckpointData& d, std::size_t n_bodies) {
  std::vector<ContactBodyState> states(n_bodies);
  for (std::size_t b = 0; b < n_bodies; ++b) {
    ContactBodyState& st = states[b];
    const std::string at = "contact.out." + std::to_string(b) + ".";
    st.name = d.text(at + "name");
    const auto& x = d.doubles(at + "scalars");
    const auto& nodes = d.ints(at + "nodes");
    const auto& f = d.doubles(at + "nodal_force");
    if (x.size() != 15 || nodes.empty() || f.size() != 3 * (nodes.size() - 1))
      throw Error(d.source() + ": inconsistent contact outputs; run without --resume");
    st.position = Vec3(x[0], x[1], x[2]);
    st.force = Vec3(x[3], x[4], x[5]);
    st.moment = Vec3(x[6], x[7], x[8]);
    st.area = x[9];
    st.radius_equivalent = x[10];
    st.radius_max = x[11];
    st.max_penetration = x[12];
    st.complementarity = x[13];
    st.min_multiplier = x[14];
    st.active_nodes = static_cast<int>(nodes[0]);
    st.nodes.assign(nodes.begin() + 1, nodes.end());
    for (std::size_t i = 0; i + 2 < f.size(); i += 3) st.nodal_force.emplace_back(f[i], f[i + 1], f[i + 2]);
    st.gap = d.doubles(at + "gap");
    st.pressure = d.doubles(at + "pressure");
  }
  return states;
}

void save_contact(CheckpointData& d, const ContactLoop& c) {
  if (c.augmented) {
    d.put("contact.committed", c.augmented->committed_state());
    save_contact_outputs(d, c.augmented->state());
  }
  if (c.kinematic) {
    d.put("contact.committed", c.kinematic->committed_state());
    save_contact_outputs(d, c.kinematic->state());
  }
  if (c.implicit)
    d.put("implicit.a",
          std::vector<double>(c.implicit->acceleration().data(),
                              c.implicit->acceleration().data() + c.implicit->acceleration().size()));
  if (c.log) c.log->save(d);
}

void restore_contact(const CheckpointData& d, const LoopState& loop, const ContactLoop& c) {
  try {
    if (c.augmented)
      c.augmented->restore_committed_state(d.doubles("contact.committed"),
                                           restore_contact_outputs(d, c.augmented->bodies().size()));
    if (c.kinematic)
      c.kinematic->restore_committed_state(d.doubles("contact.committed"),
                                           restore_contact_outputs(d, c.kinematic->bodies().size()));
  } catch (const Error& e) {
    throw Error(d.source() + ": " + e.what() + "; run without --resume");
  }
  if (c.implicit) {
    const auto& a = d.doubles("implicit.a");
    c.implicit->restore(loop.t, loop.s.u, loop.s.v,
                        Eigen::Map<const VecX>(a.data(), static_cast<Eigen::Index>(a.size())));
  }
  if (c.log) c.log->restore(d);
}

/// Static load stepping with contact (ContactStaticSolver: augmented Lagrangian or penalty around
/// the static Newton; a viscoelastic model's history advances once per accepted increment).
nlohmann::json step_static_contact(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                                   RunCheckpoint& ck) {
  const CaseConfig& cfg = p.cfg;
  const ContactSettings cs = contact_settings(cfg.contact, cfg.file);
  ContactStaticSolver solver(p.system, p.mesh, cs.bodies, cs.options, newton_options(cfg.solver), 0.0, s.u,
                             cfg.solver.max_cutbacks);
  check_contact_rig(p.mesh, solver.surface(), solver.bodies(), cs.options.max_initial_gap, 0.0,
                    cfg.solver.t_end, s.u);
  rec.set_contact(&solver.state());
  if (!ck.resuming()) rec.record(0, 0.0, s.u, s.v, 0, true);  // resumed: the checkpoint holds it
  const int n_steps = cfg.solver.steps;
  NewtonLog newton_log;
  ContactLog contact_log(cfg);
  long total_newton = 0, total_cutbacks = 0;
  double t = 0.0;
  const LoopState loop{s, t, &newton_log, &total_newton, &total_cutbacks, nullptr, nullptr};
  const ContactLoop contact{&solver, nullptr, nullptr, &contact_log};
  for (int k = ck.restore(rec, loop, &contact) + 1; k <= n_steps; ++k) {
    const double t0 = cfg.solver.t_end * (k - 1) / n_steps, t1 = cfg.solver.t_end * k / n_steps;
    const ContactStepReport rep = solver.advance(t0, t1, s.u);
    total_newton += rep.solver.newton_iterations;
    total_cutbacks += rep.solver.cutbacks;
    newton_log.add(rep.solver.newton, rep.solver.newton_iterations, rep.solver.cutbacks,
                   rep.solver.sub_increments, rep.solver.at_roundoff);
    contact_log.add(rep);
    rec.record(k, t1, s.u, s.v, rep.solver.newton_iterations, field_step(cfg, k));
    t = t1;
    ck.after_step(k, rec, loop, &contact);
    progress(k, t1);
  }
  return {{"type", "static"},
          {"load_steps", n_steps},
          {"newton_iterations", total_newton},
          {"cutbacks", total_cutbacks},
          {"newton", newton_log.json(cfg.solver, solver.linear_solver().fallbacks())},
          {"contact", contact_log.json("augmented_lagrangian_static", solver.stiffness(), solver.gap_tol(),
                                       solver.state())}};
}

/// Explicit central differences with kinematic contact (KinematicContact: penetrating nodes are
/// put back on the body after each predictor; no stiffness, so the stable step is the sample's).
nlohmann::json step_explicit_contact(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                                     RunCheckpoint& ck) {
  const CaseConfig& cfg = p.cfg;
  const int n_steps = cfg.solver.steps;
  const double dt = cfg.solver.dt;
  const ContactSettings cs = contact_settings(cfg.contact, cfg.file);
  CentralDifference integ(p.system, dt, cfg.solver.check_stability);
  integ.set_displacement_limit(10.0 * p.size);
  KinematicContact contact(p.system, p.mesh, cs.bodies, cs.options, 0.0, s.u);
  check_contact_rig(p.mesh, contact.surface(), contact.bodies(), cs.options.max_initial_gap, 0.0,
                    cfg.solver.t_end, s.u);
  rec.set_contact(&contact.state());
  if (!ck.resuming()) rec.record(0, 0.0, s.u, s.v, 0, true);  // resumed: the checkpoint holds it
  integ.initialize(0.0, s.u, s.v);
  const int series_every = std::max(1, n_steps / 4000);
  double t = 0.0;
  const LoopState loop{s, t, nullptr, nullptr, nullptr, &integ, nullptr};
  const ContactLoop ckc{nullptr, &contact, nullptr, nullptr};
  for (int k = ck.restore(rec, loop, &ckc) + 1; k <= n_steps; ++k) {
    integ.step(t, dt);
    t = integ.time();
    integ.correct(contact.correct(t, dt, integ.displacement()));
    const bool fields = field_step(cfg, k);
    if (fields || k % series_every == 0) {
      s.u = integ.displacement();
      s.v = integ.velocity();
      rec.record(k, t, s.u, s.v, 0, fields);
      ck.after_step(k, rec, loop, &ckc);
      progress(k, t);
    }
  }
  nlohmann::json j = explicit_summary(cfg, integ.stability());
  j["contact"] = ContactLog(cfg).json("kinematic_explicit", 0.0, contact.gap_tol(), contact.state());
  return j;
}

/// Implicit dynamics with contact (ContactImplicitDynamics: the augmented-Lagrangian loop around the
/// implicit step's Newton solve).
nlohmann::json step_implicit_contact(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                                     RunCheckpoint& ck) {
  const CaseConfig& cfg = p.cfg;
  const int n_steps = cfg.solver.steps;
  const ContactSettings cs = contact_settings(cfg.contact, cfg.file);
  ContactImplicitDynamics integ(p.system, p.mesh, cs.bodies, cs.options, cfg.solver.scheme,
                                newton_options(cfg.solver), cfg.solver.dt);
  integ.initialize(0.0, s.u, s.v);
  check_contact_rig(p.mesh, integ.contact().surface(), integ.contact().bodies(), cs.options.max_initial_gap,
                    0.0, cfg.solver.t_end, s.u);
  rec.set_contact(&integ.contact().state());
  if (!ck.resuming()) rec.record(0, 0.0, s.u, s.v, 0, true);  // resumed: the checkpoint holds it
  NewtonLog newton_log;
  ContactLog contact_log(cfg);
  long total_newton = 0;
  double t = 0.0;
  const LoopState loop{s, t, &newton_log, &total_newton, nullptr, nullptr, nullptr};
  const ContactLoop contact{&integ.contact(), nullptr, &integ, &contact_log};
  for (int k = ck.restore(rec, loop, &contact) + 1; k <= n_steps; ++k) {
    const double dt = std::min(cfg.solver.dt, cfg.solver.t_end - t);
    const ContactStepReport rep = integ.step(t, dt);
    t = integ.time();
    total_newton += rep.solver.newton_iterations;
    newton_log.add(rep.solver.newton, rep.solver.newton_iterations, 0, 1, rep.solver.at_roundoff);
    contact_log.add(rep);
    s.u = integ.displacement();
    s.v = integ.velocity();
    rec.record(k, t, s.u, s.v, rep.solver.newton_iterations, field_step(cfg, k));
    ck.after_step(k, rec, loop, &contact);
    progress(k, t);
  }
  return {{"type", "implicit"},
          {"scheme", to_string(cfg.solver.scheme)},
          {"dt", cfg.solver.dt},
          {"steps", n_steps},
          {"newton_iterations", total_newton},
          {"newton", newton_log.json(cfg.solver, integ.contact().linear_solver().fallbacks())},
          {"damping", {{"alpha", cfg.solver.damping_alpha}, {"beta", cfg.solver.damping_beta}}},
          {"contact", contact_log.json("augmented_lagrangian_implicit", integ.contact().stiffness(),
                                       integ.contact().gap_tol(), integ.contact().state())}};
}

/// Steps a case with a `contact` section (t = 0 recorded by the stepping function, once the
/// contact outputs exist).
nlohmann::json step_contact(const Problem& p, StepRecorder& rec, Progress& progress, State& s,
                            RunCheckpoint& ck) {
  if (p.cfg.solver.type == SolverSpec::Type::Static) return step_static_contact(p, rec, progress, s, ck);
  if (p.cfg.solver.type == SolverSpec::Type::Explicit) return step_explicit_contact(p, rec, progress, s, ck);
  return step_implicit_contact(p, rec, progress, s, ck);
}

/// Steps the case's solver from rest, recording t = 0 first; returns the summary's solver block.
nlohmann::json step(const Problem& p, StepRecorder& rec, std::ostream* log, RunCheckpoint& ck) {
  Progress progress(p.cfg, log);
  State s{VecX::Zero(p.system.num_dofs()), VecX::Zero(p.system.num_dofs())};
  if (p.cfg.contact.enabled) {
    nlohmann::json info = step_contact(p, rec, progress, s, ck);
    progress.finish();
    return info;
  }
  if (!ck.resuming()) rec.record(0, 0.0, s.u, s.v, 0, true);  // resumed: the checkpoint holds it
  nlohmann::json solver_info;
  if (p.cfg.solver.type == SolverSpec::Type::Static)
    solver_info = step_static(p, rec, progress, s, ck);
  else if (p.cfg.solver.type == SolverSpec::Type::Explicit)
    solver_info = step_explicit(p, rec, progress, s, ck);
  else
    solver_info = step_implicit(p, rec, progress, s, ck);
  progress.finish();
  return solver_info;
}

/// manifest.json and mesh_report.json.
void write_inputs(const RunOutput& out, const Problem& p, const RunOptions& opt) {
  ManifestInput mi;
  mi.command_line = opt.command_line;
  mi.config = effective_case_json(p.cfg);
  mi.input_files.push_back(p.cfg.mesh.file);
  if (fs::exists(p.cfg.file)) mi.input_files.push_back(p.cfg.file);
  out.write_json("manifest.json", make_manifest(mi));
  out.write_json("mesh_report.json", mesh_report_json(p.report));
}

/// plots.json, and the PNGs through matplotlib when asked (a missing python3/matplotlib is reported,
/// not fatal). Returns the summary's "plots" status.
std::string plot(const Problem& p, const RunOptions& opt, const RunOutput& out, const Recorder& rec) {
  out.write_json("plots.json", rec.plots(p.cfg.name));
  if (!opt.plots || !p.cfg.output.plots) return "skipped";
  const fs::path script = fs::path(opt.tmlab_root) / "core" / "results" / "python" / "tmlab_plot.py";
  const ProcessStatus ps =
      run_python(script, {out.staging_dir().string()}, ProcessOutput::to_file(out.file("plots.log")));
  if (ps.ok()) return "ok";
  if (opt.log) *opt.log << "  warning: plotting failed (see plots.log); the numbers are in timeseries.h5\n";
  return "failed (see plots.log)";
}

/// summary.json's material block: the law, its parameters as the case file gives them (the manifest's
/// effective configuration), the density, and the small-strain E, nu, lambda, mu of the law.
nlohmann::json material_summary(const Problem& p) {
  nlohmann::json m = effective_case_json(p.cfg)["material"];
  m.erase("viscoelastic");
  const LameConstants l = p.law.small_strain();
  m["E"] = p.cfg.material.young;
  m["nu"] = p.cfg.material.poisson;
  m["lambda"] = l.lambda;
  m["mu"] = l.mu;
  return m;
}

/// summary.json: the case, mesh, material, solver, the recorder's common blocks, the energy balance
/// (work in = stored + kinetic + dissipated) and the viscoelastic settings.
nlohmann::json summarise(const Problem& p, const StepRecorder& rec, const nlohmann::json& solver_info,
                         const std::string& plot_status, double wall) {
  const CaseConfig& cfg = p.cfg;
  nlohmann::json summary = {{"case", cfg.name},
                            {"description", cfg.description},
                            {"model", to_string(cfg.model)},
                            {"mesh",
                             {{"file", cfg.mesh.file},
                              {"points", p.mesh.num_points()},
                              {"tets", p.mesh.num_tets()},
                              {"volume_m3", p.report.total_volume},
                              {"orientation_repaired", p.repaired}}},
                            {"material", material_summary(p)},
                            {"solver", solver_info},
                            {"plots", plot_status},
                            {"run_seconds", wall}};
  summary.update(rec.recorder().summary_blocks());
  if (summary["solver"].contains("contact")) {  // the contact block at the top level
    summary["contact"] = summary["solver"]["contact"];
    summary["solver"].erase("contact");
  }
  const SeriesTable& table = rec.recorder().table();
  const double stored = table.last(series_names::kElasticEnergy);
  const double kinetic = table.last(series_names::kKineticEnergy);
  const double dissipated = p.visco ? p.visco->total_dissipation() : 0.0;
  const double work = rec.external_work();
  summary["energy"] = {{"external_work_J", work},
                       {"stored_J", stored},
                       {"kinetic_J", kinetic},
                       {"total_dissipation_J", dissipated},
                       {"balance_residual_J", work - stored - kinetic - dissipated}};
  if (p.visco) {
    const ViscoelasticSpec& vs = cfg.material.viscoelastic;
    summary["viscoelastic"] = {{"history", to_string(vs.history)},
                               {"integration", to_string(vs.integration)},
                               {"relaxation", to_string(vs.relaxation)},
                               {"prony_long_term", p.visco->prony().to_json()}};
  }
  return summary;
}

}  // namespace

NewtonOptions newton_options(const SolverSpec& s) {
  NewtonOptions o;
  o.max_iterations = s.max_iterations;
  o.rtol = s.rtol;
  o.atol = s.atol;
  o.line_search = s.line_search;
  o.linear_solver =
      s.linear == SolverSpec::Linear::Cholmod ? NewtonLinearSolver::Cholmod : NewtonLinearSolver::Direct;
  return o;
}

RunResult run_case(const CaseConfig& cfg, const RunOptions& opt) {
  const auto wall0 = std::chrono::steady_clock::now();
  const Problem p(cfg);
  // --resume: the checkpoint is read and checked before the result directory is touched, so a
  // refused resume leaves the interrupted run as it was.
  const fs::path dir = fs::path(opt.results_root) / cfg.name;
  RunCheckpoint ck(p, dir, opt);
  // The result directory is staged; summary.json only when everything succeeded.
  RunOutput out(dir, opt.log,
                opt.resume ? RunOutput::Previous::ResumeInterrupted : RunOutput::Previous::Discard);
  try {
    write_inputs(out, p, opt);
    StepRecorder rec(p, out);
    const nlohmann::json solver_info = step(p, rec, opt.log, ck);
    rec.close();
    ck.remove();  // a complete result holds no checkpoint
    const std::string plot_status = plot(p, opt, out, rec.recorder());
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    const nlohmann::json summary = summarise(p, rec, solver_info, plot_status, wall);
    out.finalize(summary);
    return {out.dir().string(), summary};
  } catch (const Interrupted& e) {
    const Interrupted stopped(e.signal(), e.what() + ck.where());
    out.abandon(stopped);
    throw stopped;
  } catch (const std::exception& e) {
    out.abandon(e);
    throw;
  }
}

}  // namespace tmlab::tm
