// The FE-rig forward model (rig_forward_model.hpp explains the choices).
#include "calibration/fit/rig_forward_model.hpp"

#include "calibration/fit/surrogates.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/config/time_function.hpp"
#include "core/constitutive/law_catalogue.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/contact/contact_config.hpp"
#include "tensormass/contact/contact_solver.hpp"
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"
#include "tensormass/viscoelastic/viscoelastic_law.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include <atomic>
#include <cmath>
#include <memory>

namespace tmlab::fit {

namespace {

namespace ms = tmlab::measured;

/// One test as a rig: the mesh, its Dirichlet conditions (from the rig's case-file boundary, so the
/// in-process rig and `tmlab rig` are the same fixture), the indenter, the load-step times.
struct TestRig {
  rigs::RigSpec spec;
  Mesh mesh;
  tm::VecX node_mass;
  std::vector<DirichletCondition> conditions;
  std::size_t top = 0;  ///< the condition of the top platen (platen tests)
  std::vector<tm::RigidBody> bodies;
  std::vector<double> sample_times;  ///< rig time of each data sample
};

std::vector<DirichletCondition> conditions_of(const nlohmann::json& boundary, const Mesh& mesh,
                                              const std::string& where) {
  std::vector<DirichletCondition> out;
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    const nlohmann::json& b = boundary[i];
    const std::string w = where + ": boundary[" + std::to_string(i) + "]";
    DirichletCondition c;
    c.name = b.at("name").get<std::string>();
    c.nodes = select_nodes(mesh, NodeSelector::from_json(b.at("nodes"), w + ".nodes"));
    if (c.nodes.empty()) throw Error(w + " '" + c.name + "' selects no nodes");
    const std::string comps = b.at("components").get<std::string>();
    c.components = {comps.find('x') != std::string::npos, comps.find('y') != std::string::npos,
                    comps.find('z') != std::string::npos};
    if (b.contains("value")) c.value = Vec3(b["value"][0], b["value"][1], b["value"][2]);
    if (b.contains("function")) c.function = TimeFunction::from_json(b["function"], w + ".function");
    out.push_back(std::move(c));
  }
  return out;
}

/// The state of one prediction, per test and sample: the displacements and (contact rigs) the
/// committed contact state (multipliers, candidates) after the load step that reached the sample.
struct RigForwardModelState final : WarmStart {
  std::vector<std::vector<tm::VecX>> u;
  std::vector<std::vector<std::vector<double>>> contact;
};

/// The mean K_0 zz-diagonal over the top-face nodes within the contact radius at peak depth of the
/// indenter's axis (RigForwardModelOptions::contact_stiffness_factor), N/m.
double patch_stiffness(const TestRig& r, const tm::MechanicalSystem& sys) {
  const rigs::RigSpec& s = r.spec;
  const double rc = s.indenter == rigs::IndenterShape::Sphere
                        ? std::sqrt(s.indenter_radius * s.history.peak())
                        : s.indenter_radius;
  double ztop = -1e300;
  for (const Vec3& x : r.mesh.points) ztop = std::max(ztop, x.z());
  const tm::VecX diag = sys.reference_tangent().diagonal();
  double sum = 0.0;
  int n = 0;
  for (Index i = 0; i < r.mesh.num_points(); ++i) {
    const Vec3& x = r.mesh.points[std::size_t(i)];
    if (std::abs(x.z() - ztop) <= 1e-9 * s.height &&
        std::hypot(x.x() - s.cx, x.y() - s.cy) <= rc * (1 + 1e-9)) {
      sum += diag[3 * Eigen::Index(i) + 2];
      ++n;
    }
  }
  if (n == 0 || !(sum > 0.0))
    throw Error("fe_rig: no top-face node within the contact radius " + significant(rc, 3) +
                " m of the indenter (contact_stiffness_factor needs one)");
  return sum / n;
}

class RigForwardModel final : public ForwardModel {
 public:
  RigForwardModel(const ms::DataSet& d, ModelSpec spec, RigForwardModelOptions o)
      : spec_(std::move(spec)), opt_(o) {
    if (opt_.substeps < 1) throw Error("fe_rig: substeps must be >= 1");
    if (opt_.newton_max_iterations < 1) throw Error("fe_rig: newton_max_iterations must be >= 1");
    if (!(opt_.jacobian_step > 0.0 && opt_.jacobian_step < 0.1))
      throw Error("fe_rig: jacobian_step must lie in (0, 0.1)");
    for (std::size_t k = 0; k < d.tests.size(); ++k) {
      auto r = std::make_unique<TestRig>();
      r->spec = rigs::rig_from_data(d, k, opt_.mesh);
      r->mesh = opt_.mesh_builder ? opt_.mesh_builder(r->spec) : rigs::rig_mesh(r->spec);
      r->node_mass = tm::lumped_node_mass(r->mesh, 1000.0);  // inertia plays no part in a static solve
      const nlohmann::json c = rigs::rig_case(r->spec, "in-process.msh");
      const std::string where = d.meta.name + " test " + std::to_string(k + 1) + " rig";
      r->conditions = conditions_of(c.at("boundary"), r->mesh, where);
      for (std::size_t i = 0; i < r->conditions.size(); ++i)
        if (r->conditions[i].name == "top_platen") r->top = i;
      if (c.contains("contact")) r->bodies = tm::parse_contact_section(c["contact"], where).bodies;
      const double shift = rigs::rig_from_data_time_shift(d, k);
      const ms::Test& t = d.tests[k];
      for (std::size_t i = 0; i < t.size(); ++i) r->sample_times.push_back(t.time_s[i] - t.time_s[0] + shift);
      indentation_ = r->spec.test == rigs::RigTest::Indentation;
      nodes_ += std::size_t(r->mesh.num_points());
      tets_ += std::size_t(r->mesh.num_tets());
      rigs_.push_back(std::move(r));
    }
  }
  std::string name() const override { return "fe_rig"; }
  std::string description() const override {
    const bool stvk = law_descriptor(spec_.law).tensor_mass;
    const std::string law = to_string(spec_.law);
    std::string m =
        stvk ? (spec_.prony_terms ? "the viscoelastic tensor-mass model (ViscoelasticStVK, pk2)"
                                  : "the tensor-mass model (TensorMassStVK)")
             : (spec_.prony_terms ? "ViscoelasticHyperelastic (pk2) on the " + law + " law"
                                  : "the F-based P1 element (HyperelasticTL) with the " + law + " law");
    return "FE rig: " + m + " on the generated " + rigs::rig_test_name(rigs_.front()->spec.test) + " rig (" +
           std::to_string(rigs_.size()) + " test(s), " + std::to_string(tets_) + " tets in all" +
           (opt_.mesh_builder ? ", study mesh" : "") + "), quasi-static, " + std::to_string(opt_.substeps) +
           " load step(s) per sample" +
           (indentation_ ? ", augmented-Lagrangian frictionless contact" : ", prescribed platen face");
  }
  double jacobian_step() const override { return opt_.jacobian_step; }

  std::vector<double> predict(const std::vector<double>& x) const override {
    return predict_warm(x, nullptr, nullptr);
  }

  std::vector<double> predict_warm(const std::vector<double>& x, const WarmStart* from,
                                   std::shared_ptr<const WarmStart>* keep) const override {
    const tm::Law law = build_law(spec_, x);
    const auto [young, nu] = small_strain_young_poisson(spec_, x);
    (void)nu;
    const auto [moduli, taus] = prony_terms(spec_, x);
    const auto* start = dynamic_cast<const RigForwardModelState*>(from);
    if (start && start->u.size() != rigs_.size()) start = nullptr;
    auto state = keep ? std::make_shared<RigForwardModelState>() : nullptr;
    std::vector<double> out;
    for (std::size_t k = 0; k < rigs_.size(); ++k) {
      Trajectory tr;
      if (start) {
        tr.from_u = &start->u[k];
        tr.from_contact = &start->contact[k];
      }
      std::vector<double> f;
      try {
        f = simulate(*rigs_[k], law, young, moduli, taus, tr, state != nullptr);
      } catch (const Error&) {
        if (!start) throw;
        tr = Trajectory{};  // a warm start that does not converge: the cold solve decides
        f = simulate(*rigs_[k], law, young, moduli, taus, tr, state != nullptr);
      }
      out.insert(out.end(), f.begin(), f.end());
      if (state) {
        state->u.push_back(std::move(tr.u));
        state->contact.push_back(std::move(tr.contact));
      }
    }
    ++effort_.solves;
    if (start) ++effort_.warm;
    if (keep) *keep = std::move(state);
    return out;
  }

  RigForwardModelSize size() const { return {rigs_.size(), nodes_, tets_, opt_.mesh}; }

  RigForwardModelEffort counts() const {
    return {effort_.solves.load(), effort_.warm.load(),  effort_.steps.load(),
            effort_.newton.load(), effort_.outer.load(), effort_.cutbacks.load()};
  }

  std::string effort() const override {
    const RigForwardModelEffort e = counts();
    const double n = double(std::max(1L, e.solves));
    auto per = [n](long v) { return significant(double(v) / n, 3); };
    return std::to_string(e.solves) + " FE solves (" + std::to_string(e.warm) +
           " warm-started), per solve: " + per(e.steps) + " load steps, " + per(e.newton) +
           " Newton iterations, " + per(e.outer) + " contact outer iterations, " + per(e.cutbacks) +
           " cut-backs";
  }

 private:
  std::unique_ptr<tm::ElasticModel> make_model(const Mesh& mesh, const tm::Law& law, double young,
                                               const std::vector<double>& moduli,
                                               const std::vector<double>& taus) const {
    if (moduli.empty()) {
      if (const auto* stvk = law.get_if<tm::StVenantKirchhoff>())
        return std::make_unique<tm::TensorMassStVK>(mesh, *stvk);
      return std::make_unique<tm::HyperelasticTL>(mesh, law);
    }
    std::vector<double> alpha;
    for (const double e : moduli) alpha.push_back(e / young);  // long-term normalised weights
    const tm::PronySeries prony = tm::PronySeries::from_long_term(alpha, taus);
    tm::ViscoelasticOptions vo;  // pk2 history, midpoint recursion, full relaxation
    vo.energy_bookkeeping = false;
    if (const auto* stvk = law.get_if<tm::StVenantKirchhoff>())
      return std::make_unique<tm::ViscoelasticStVK>(mesh, *stvk, prony, vo);
    return std::make_unique<tm::ViscoelasticHyperelastic>(mesh, law, prony, vo);
  }

  /// A warm start's source (one test's displacements and contact states per sample, or none) and
  /// the trajectory this solve records.
  struct Trajectory {
    const std::vector<tm::VecX>* from_u = nullptr;
    const std::vector<std::vector<double>>* from_contact = nullptr;
    std::vector<tm::VecX> u;
    std::vector<std::vector<double>> contact;
  };

  std::vector<double> simulate(const TestRig& r, const tm::Law& law, double young,
                               const std::vector<double>& moduli, const std::vector<double>& taus,
                               Trajectory& tr, bool record) const {
    std::unique_ptr<tm::ElasticModel> model = make_model(r.mesh, law, young, moduli, taus);
    tm::MechanicalSystem sys(*model, tm::lumped_dof_mass(r.node_mass),
                             tm::DirichletSet(r.mesh.num_points(), r.conditions),
                             tm::ExternalLoads(r.mesh, r.node_mass));
    tm::NewtonOptions no;
    no.rtol = opt_.newton_rtol;
    no.max_iterations = opt_.newton_max_iterations;
    // The fits evaluate the rig from several threads at once (multi-start, Jacobian columns), and
    // CHOLMOD's supernodal factorisation through the serial OpenBLAS gave results that differ in the
    // last bits between concurrent and serial runs (test ShallowSphereIndentationIsCloseToHertzAndThreadSafe,
    // 2026-12-02): the fits keep Eigen's LDL^T, thread safe and deterministic, until that is understood.
    no.linear_solver = tm::NewtonLinearSolver::Direct;
    tm::VecX u = tm::VecX::Zero(sys.num_dofs());
    std::unique_ptr<tm::ContactStaticSolver> contact;
    std::unique_ptr<tm::StaticSolver> platen;
    bool frictionless = true;
    if (r.bodies.empty()) {
      platen = std::make_unique<tm::StaticSolver>(sys, no);
    } else {
      tm::ContactOptions co;
      if (opt_.contact_stiffness_factor > 0.0)
        co.stiffness = opt_.contact_stiffness_factor * patch_stiffness(r, sys);
      contact = std::make_unique<tm::ContactStaticSolver>(sys, r.mesh, r.bodies, co, no, 0.0, u);
      for (const auto& b : r.bodies) frictionless = frictionless && b.mode == tm::ContactMode::Frictionless;
    }
    // A warm start is used only when it matches this rig (same samples, same DOFs).
    const std::size_t ns = r.sample_times.size();
    const bool warm = tr.from_u && tr.from_u->size() == ns && tr.from_contact &&
                      tr.from_contact->size() == ns && (ns == 0 || tr.from_u->front().size() == u.size());
    std::vector<double> f;
    f.reserve(ns);
    double t = 0.0;
    tm::VecX fint;
    for (std::size_t i = 0; i < ns; ++i) {
      const double ts = r.sample_times[i];
      // `substeps` load steps up to the sample (none for a sample at t = 0: the rest state).
      if (ts > t) {
        const int n = opt_.substeps;
        for (int s = 1; s <= n; ++s) {
          const double t0 = t + (ts - t) * (s - 1) / n, t1 = s == n ? ts : t + (ts - t) * s / n;
          // Warm start (one load step per sample): the iterations begin at the source's solution at
          // this sample. The model's history is its own (committed at each accepted step); for
          // frictionless bodies the committed multipliers are only the Uzawa loop's starting values.
          if (warm && n == 1) {
            u = (*tr.from_u)[i];
            if (contact && frictionless)
              contact->restore_committed_state((*tr.from_contact)[i], contact->state());
          }
          if (contact && !frictionless) {
            const tm::ContactStepReport cr = contact->advance(t0, t1, u);
            count(cr.solver.newton_iterations, cr.outer_iterations_total, cr.solver.cutbacks);
          } else {
            load_step(sys, platen.get(), contact.get(), t0, t1, u);
          }
        }
        t = ts;
      }
      if (record) {
        tr.u.push_back(u);
        tr.contact.push_back(contact ? contact->committed_state() : std::vector<double>{});
      }
      if (contact) {
        f.push_back(contact->state().empty() ? 0.0 : contact->state().front().force.z());
      } else {
        // Reaction of the top face (r = f_int - f_ext; the sample pushes the platen up: -r_z).
        model->internal_force(u, fint);
        f.push_back(-sys.bc().resultant(r.top, fint).z());
      }
    }
    return f;
  }

  /// One load step t0 -> t1 with the model's history advanced once, by dt = t1 - t0, however hard
  /// the step is to converge. A solve that fails is approached through intermediate targets
  /// (halving the remaining increment, up to kMaxCutbacks times), each solved from the last converged
  /// iterate with the trial history of a step from t0 to it and never committed: cut-backs find the
  /// starting iterate, they do not refine the time discretisation. (The solvers' advance() commits
  /// each sub-increment, which integrates the Prony history in smaller steps exactly where a step
  /// was hard: the forces then jump by up to ~1 % where a parameter change of 1e-6 adds or removes a
  /// cut-back, measured on the Section IV-A rig, and finite-difference Jacobians are spoilt.)
  /// Contact: frictionless bodies only (an intermediate accept() only changes the Uzawa loop's
  /// starting multipliers); bonded bodies use advance().
  void load_step(const tm::MechanicalSystem& sys, tm::StaticSolver* platen, tm::ContactStaticSolver* contact,
                 double t0, double t1, tm::VecX& u) const {
    const tm::InnerResidualFactory statics = [&sys](double t, const tm::VecX& u0) {
      return std::make_unique<tm::StaticResidual>(sys, t, u0);
    };
    double reached = t0, h = t1 - t0;
    int depth = 0;
    long newton = 0, outer = 0, cutbacks = 0;
    tm::VecX u_cur = u;
    for (;;) {
      const double s = (t1 - reached <= h * (1.0 + 1e-12)) ? t1 : reached + h;
      sys.model().begin_step(s - t0);
      tm::VecX u_try = u_cur;
      bool ok = false;
      try {
        if (contact) {
          tm::ContactStepReport r;
          ok = contact->solve(s, reached, u_try, r, statics);
          newton += r.solver.newton_iterations;
          outer += r.outer_iterations_total;
        } else {
          const tm::NewtonResult nr = platen->solve(s, u_try);
          newton += nr.iterations;
          ok = nr.converged;
        }
      } catch (const Error&) {
        ok = false;  // a non-finite residual in a too-large increment: approach it in smaller ones
      }
      if (ok) {
        u_cur.swap(u_try);
        if (contact) contact->accept(s, u_cur);
        reached = s;
        if (s == t1) break;
        if (depth > 0) {
          h *= 2.0;
          --depth;
        }
        continue;
      }
      if (depth >= kMaxCutbacks) {
        count(newton, outer, cutbacks);
        throw Error("fe_rig: the load step to t = " + significant(t1, 6) + " s did not converge after " +
                    std::to_string(kMaxCutbacks) + " cut-backs (reached t = " + significant(reached, 6) +
                    " s)");
      }
      h *= 0.5;
      ++depth;
      ++cutbacks;
    }
    sys.model().commit_step(u_cur);
    u.swap(u_cur);
    count(newton, outer, cutbacks);
  }

  void count(long newton, long outer, long cutbacks) const {
    ++effort_.steps;
    effort_.newton += newton;
    effort_.outer += outer;
    effort_.cutbacks += cutbacks;
  }

  static constexpr int kMaxCutbacks = 8;

  /// Solver effort summed over every prediction (effort()); counters only, safe across threads.
  struct Effort {
    std::atomic<long> solves{0}, warm{0}, steps{0}, newton{0}, outer{0}, cutbacks{0};
  };

  ModelSpec spec_;
  RigForwardModelOptions opt_;
  mutable Effort effort_;
  std::vector<std::unique_ptr<TestRig>> rigs_;
  bool indentation_ = false;
  std::size_t nodes_ = 0, tets_ = 0;
};

}  // namespace

RigForwardModelEffort rig_forward_model_effort(const ForwardModel& model) {
  const auto* fe = dynamic_cast<const RigForwardModel*>(&model);
  if (!fe) throw Error("rig_forward_model_effort: '" + model.name() + "' is not an FE-rig model");
  return fe->counts();
}

std::unique_ptr<ForwardModel> make_rig_forward_model(const ms::DataSet& d, const ModelSpec& spec,
                                                     const RigForwardModelOptions& o) {
  if (d.tests.empty()) throw Error(d.meta.name + ": the data set has no tests");
  return std::make_unique<RigForwardModel>(d, spec, o);
}

RigForwardModelSize rig_forward_model_size(const ForwardModel& model) {
  const auto* fe = dynamic_cast<const RigForwardModel*>(&model);
  if (!fe) throw Error("rig_forward_model_size: '" + model.name() + "' is not an FE-rig model");
  return fe->size();
}

Problem make_rig_forward_problem(const ms::DataSet& d, const ModelSpec& spec,
                                 const std::vector<std::pair<std::string, double>>& fixes,
                                 const std::vector<std::pair<std::string, double>>& weights,
                                 const RigForwardModelOptions& o, std::string* why_no_surrogate) {
  Problem pr = make_data_problem(d, spec, fixes, weights);
  pr.model = make_rig_forward_model(d, spec, o);
  try {
    pr.global_model = make_surrogate_model(d, spec);
  } catch (const Error& e) {
    if (why_no_surrogate) *why_no_surrogate = e.what();
  }
  return pr;
}

}  // namespace tmlab::fit
