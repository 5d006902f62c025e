// The FE-rig forward model (fe_rig.hpp explains the choices).
#include "calibration/fit/fe_rig.hpp"

#include "calibration/fit/surrogates.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/config/time_function.hpp"
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

#include <cmath>

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

class FeRigModel final : public ForwardModel {
 public:
  FeRigModel(const ms::DataSet& d, ModelSpec spec, FeRigOptions o) : spec_(std::move(spec)), opt_(o) {
    if (opt_.substeps < 1) throw Error("fe_rig: substeps must be >= 1");
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
      const double shift = rigs::data_rig_time_shift(d, k);
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
    const bool stvk = spec_.law == "stvk";
    std::string m =
        stvk ? (spec_.prony_terms ? "the viscoelastic tensor-mass model (ViscoelasticStVK, pk2)"
                                  : "the tensor-mass model (TensorMassStVK)")
             : (spec_.prony_terms ? "ViscoelasticHyperelastic (pk2) on the " + spec_.law + " law"
                                  : "the F-based P1 element (HyperelasticTL) with the " + spec_.law + " law");
    return "FE rig: " + m + " on the generated " + rigs::rig_test_name(rigs_.front()->spec.test) + " rig (" +
           std::to_string(rigs_.size()) + " test(s), " + std::to_string(tets_) + " tets in all" +
           (opt_.mesh_builder ? ", study mesh" : "") + "), quasi-static, " + std::to_string(opt_.substeps) +
           " load step(s) per sample" +
           (indentation_ ? ", augmented-Lagrangian frictionless contact" : ", prescribed platen face");
  }
  double jacobian_step() const override { return 1e-6; }

  std::vector<double> predict(const std::vector<double>& x) const override {
    const tm::Law law = build_law(spec_, x);
    const auto [young, nu] = small_strain_young_poisson(spec_, x);
    (void)nu;
    const auto [moduli, taus] = prony_terms(spec_, x);
    std::vector<double> out;
    for (const auto& r : rigs_) {
      const std::vector<double> f = simulate(*r, law, young, moduli, taus);
      out.insert(out.end(), f.begin(), f.end());
    }
    return out;
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

  std::vector<double> simulate(const TestRig& r, const tm::Law& law, double young,
                               const std::vector<double>& moduli, const std::vector<double>& taus) const {
    std::unique_ptr<tm::ElasticModel> model = make_model(r.mesh, law, young, moduli, taus);
    tm::MechanicalSystem sys(*model, tm::lumped_dof_mass(r.node_mass),
                             tm::DirichletSet(r.mesh.num_points(), r.conditions),
                             tm::ExternalLoads(r.mesh, r.node_mass));
    tm::NewtonOptions no;
    no.rtol = opt_.newton_rtol;
    no.max_iterations = 40;
    tm::VecX u = tm::VecX::Zero(sys.num_dofs());
    std::unique_ptr<tm::ContactStaticSolver> contact;
    std::unique_ptr<tm::StaticSolver> platen;
    if (r.bodies.empty())
      platen = std::make_unique<tm::StaticSolver>(sys, no);
    else
      contact =
          std::make_unique<tm::ContactStaticSolver>(sys, r.mesh, r.bodies, tm::ContactOptions{}, no, 0.0, u);
    std::vector<double> f;
    f.reserve(r.sample_times.size());
    double t = 0.0;
    tm::VecX fint;
    for (const double ts : r.sample_times) {
      // `substeps` load steps up to the sample (none for a sample at t = 0: the rest state).
      if (ts > t) {
        const int n = opt_.substeps;
        for (int s = 1; s <= n; ++s) {
          const double t0 = t + (ts - t) * (s - 1) / n, t1 = s == n ? ts : t + (ts - t) * s / n;
          if (contact)
            contact->advance(t0, t1, u);
          else
            platen->advance(t0, t1, u);
        }
        t = ts;
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

  ModelSpec spec_;
  FeRigOptions opt_;
  std::vector<std::unique_ptr<TestRig>> rigs_;
  bool indentation_ = false;
  std::size_t nodes_ = 0, tets_ = 0;
};

}  // namespace

std::unique_ptr<ForwardModel> make_fe_rig_model(const ms::DataSet& d, const ModelSpec& spec,
                                                const FeRigOptions& o) {
  if (d.tests.empty()) throw Error(d.meta.name + ": the data set has no tests");
  return std::make_unique<FeRigModel>(d, spec, o);
}

Problem make_fe_rig_problem(const ms::DataSet& d, const ModelSpec& spec,
                            const std::vector<std::pair<std::string, double>>& fixes,
                            const std::vector<std::pair<std::string, double>>& weights, const FeRigOptions& o,
                            std::string* why_no_surrogate) {
  Problem pr = make_data_problem(d, spec, fixes, weights);
  pr.model = make_fe_rig_model(d, spec, o);
  try {
    pr.global_model = make_surrogate_model(d, spec);
  } catch (const Error& e) {
    if (why_no_surrogate) *why_no_surrogate = e.what();
  }
  return pr;
}

}  // namespace tmlab::fit
