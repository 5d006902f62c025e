// Model checks: properties the viscoelastic model must have whatever the mesh or load.
//
//   model.objectivity   a rigid rotation of a relaxing body rotates its forces (objective PK2 history)
//                       and does not for the seed's nodal-force history (documented, asserted)
//   model.dissipation   dissipation >= 0 on every step of random histories, every variant; the energy
//                       balance W_ext = Psi + D closes at second order in dt (objective history)
//   model.volume_creep  under hydrostatic pressure the volume creeps with full relaxation (towards the
//                       long-term compliance) and stays put with deviatoric relaxation
#include "verification/checks/check_support.hpp"

#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/dirichlet.hpp"
#include "tensormass/system/external_loads.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>

namespace tmlab::verify {

namespace {

using tm::PronySeries;
using tm::StVenantKirchhoff;
using tm::VecX;
using tm::ViscoelasticOptions;
using tm::ViscoelasticStVK;
using Hist = ViscoelasticOptions::History;
using Integ = ViscoelasticOptions::Integration;
using Relax = ViscoelasticOptions::Relaxation;

constexpr double kPi = 3.14159265358979323846;
const Integ kSchemes[] = {Integ::Midpoint, Integ::ExactLinear, Integ::BackwardEuler};

StVenantKirchhoff material(ConfigReader& p) {
  const double nu = p.require<double>("poisson");
  if (!(nu > -1.0 && nu < 0.5)) throw p.error("poisson", "must be in (-1, 0.5)");
  return StVenantKirchhoff::from_young_poisson(p.positive("young"), nu);
}

PronySeries prony(ConfigReader& p) {
  return PronySeries::from_long_term(p.require<std::vector<double>>("alpha"),
                                     p.require<std::vector<double>>("tau"));
}

std::string variant(const ViscoelasticOptions& o) {
  return ViscoelasticOptions::to_string(o.history) + "/" + ViscoelasticOptions::to_string(o.integration) +
         "/" + ViscoelasticOptions::to_string(o.relaxation);
}

// ------------------------------------------------------------------ model.objectivity
// Stretch the body over [0, 1], hold to 1.5 (part-way through relaxation), then rotate it rigidly
// by `angle` about (1,2,3) over [1.5, 1.8] while holding the body-frame stretch. The final forces
// must equal the unrotated body's forces rotated by R (objectivity of the history).
Measurements objectivity(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const Mesh mesh = mesh_from_parameters(ctx, p.child("mesh"));
  const StVenantKirchhoff mat = material(p);
  const PronySeries series = prony(p);
  const double angle_end = p.require<double>("angle");
  const double stretch = p.positive("stretch");
  p.finish();
  const Vec3 axis = Vec3(1.0, 2.0, 3.0).normalized();
  const VecX d = smooth_random_displacement(mesh, stretch, 17);
  const std::vector<double> times{0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.6, 1.7, 1.8};
  auto angle = [&](double t) { return t <= 1.5 ? 0.0 : std::min((t - 1.5) / 0.3, 1.0) * angle_end; };
  auto displacement = [&](double t, bool rotate) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(rotate ? angle(t) : 0.0, axis).toRotationMatrix();
    VecX u(3 * mesh.num_points());
    for (Index i = 0; i < mesh.num_points(); ++i)
      u.segment<3>(3 * i) = R * (mesh.points[i] + std::min(t, 1.0) * d.segment<3>(3 * i)) - mesh.points[i];
    return u;
  };
  const Eigen::Matrix3d R_end = Eigen::AngleAxisd(angle_end, axis).toRotationMatrix();
  Measurements m;
  double objective_worst = 0.0, seed_least = 1e300;
  for (Hist h : {Hist::Pk2, Hist::NodalForce}) {
    for (Integ scheme : kSchemes) {
      const ViscoelasticOptions opt{h, scheme, Relax::Full};
      ViscoelasticStVK rot(mesh, mat, series, opt), ref(mesh, mat, series, opt);
      double t_prev = 0.0;
      for (double t : times) {
        rot.begin_step(t - t_prev);
        ref.begin_step(t - t_prev);
        rot.commit_step(displacement(t, true));
        ref.commit_step(displacement(t, false));
        t_prev = t;
      }
      VecX f_rot, f_ref;
      rot.internal_force(displacement(times.back(), true), f_rot);
      ref.internal_force(displacement(times.back(), false), f_ref);
      double spurious = 0.0, scale = 0.0;
      for (Index i = 0; i < mesh.num_points(); ++i) {
        spurious = std::max(spurious, (f_rot.segment<3>(3 * i) - R_end * f_ref.segment<3>(3 * i)).norm());
        scale = std::max(scale, f_ref.segment<3>(3 * i).norm());
      }
      const double rel = spurious / scale;
      m.set("spurious_" + variant(opt), rel);
      if (h == Hist::Pk2)
        objective_worst = std::max(objective_worst, rel);
      else
        seed_least = std::min(seed_least, rel);
    }
  }
  m.set("objective_spurious_force", objective_worst);
  m.set("seed_spurious_force", seed_least);
  return m;
}

// ------------------------------------------------------------------ model.dissipation
Measurements dissipation(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const Mesh mesh = mesh_from_parameters(ctx, p.child("mesh"));
  const StVenantKirchhoff mat = material(p);
  const PronySeries series = prony(p);
  const int random_steps = p.get<int>("random_steps", 60);
  const double amp = p.positive("displacement");
  const auto steps = p.require<std::vector<int>>("balance_steps");
  p.finish();
  Measurements m;
  // (1) random histories: every variant, random dt and random fields
  double min_rel = 1e300;
  int negative = 0;
  for (Hist h : {Hist::NodalForce, Hist::Pk2})
    for (Integ s : kSchemes)
      for (Relax r : {Relax::Full, Relax::Deviatoric}) {
        if (h == Hist::NodalForce && r == Relax::Deviatoric) continue;
        ViscoelasticStVK model(mesh, mat, series, {h, s, r});
        std::mt19937 rng(12345);
        std::uniform_real_distribution<double> U(0.0, 1.0);
        for (int k = 1; k <= random_steps; ++k) {
          const double dt = 0.01 + 0.8 * U(rng);
          model.begin_step(dt);
          model.commit_step((2.0 * U(rng) - 1.0) * smooth_random_displacement(mesh, amp, 100 + unsigned(k)));
          const double d = model.step_dissipation();
          if (d < 0.0) ++negative;
          min_rel = std::min(min_rel, d / std::max(model.total_dissipation() / k, 1e-300));
        }
      }
  m.set("min_step_dissipation_rel", min_rel);
  m.set("negative_steps", negative);
  // (2) energy balance on a smooth history u(t) = sin(pi t / 2) u_1, t in [0, 2], objective PK2:
  // external work (trapezoidal on the committed forces) = stored energy + dissipation, to O(dt^2).
  const VecX shape = smooth_random_displacement(mesh, amp, 3);
  Series bal;
  bal.x_label = "dt [s]";
  bal.y_label = "|W_ext - Psi - D| / W_ext";
  for (int n : steps) {
    ViscoelasticStVK model(mesh, mat, series, {Hist::Pk2, Integ::ExactLinear, Relax::Full});
    VecX u_prev = VecX::Zero(shape.size()), f_prev = VecX::Zero(shape.size()), f;
    double work = 0.0;
    const double dt = 2.0 / n;
    for (int k = 1; k <= n; ++k) {
      const VecX u = std::sin(0.5 * kPi * k * dt) * shape;
      model.begin_step(dt);
      model.commit_step(u);
      model.internal_force(u, f);
      work += 0.5 * (f + f_prev).dot(u - u_prev);
      u_prev = u;
      f_prev = f;
    }
    const double stored = model.committed_elastic_energy() + model.committed_branch_energy();
    bal.x.push_back(dt);
    bal.y.push_back(std::abs(work - stored - model.total_dissipation()) / work);
  }
  m.series["energy_balance_pk2"] = bal;
  return m;
}

// ------------------------------------------------------------------ model.volume_creep
double deformed_volume(const Mesh& mesh, const VecX& u) {
  double v = 0.0;
  for (const Tet& t : mesh.tets) {
    Vec3 x[4];
    for (int q = 0; q < 4; ++q) x[q] = mesh.points[t[q]] + u.segment<3>(3 * t[q]);
    v += (x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0])) / 6.0;
  }
  return v;
}

/// Hydrostatic dead pressure on the outer faces of the cube [0, L]^3 (symmetry rollers at 0),
/// applied in the first step and held; the volume change at t_end relative to the first step.
Measurements volume_creep(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const double L = p.positive("size");
  const int n = p.get<int>("cells", 2);
  const StVenantKirchhoff mat = material(p);
  const PronySeries series = prony(p);
  const double pressure = p.positive("pressure");
  const double dt = p.positive("dt"), t_end = p.positive("t_end");
  p.finish();
  if (series.size() != 1)
    throw Error(ctx.vcase.spec_file().string() + ": key 'parameters.alpha': one Prony term expected");
  const Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Constant(L), n, n, n);
  Measurements m;
  double dev_drift = 0.0, full_ratio = 1e300;
  for (Integ scheme : kSchemes)
    for (Relax relax : {Relax::Full, Relax::Deviatoric}) {
      ViscoelasticStVK model(mesh, mat, series, {Hist::Pk2, scheme, relax});
      const VecX node_mass = tm::lumped_node_mass(mesh, 1000.0);
      tm::ExternalLoads loads(mesh, node_mass);
      std::vector<tm::DirichletCondition> bc;
      for (int a = 0; a < 3; ++a) {
        loads.add(
            tm::SurfacePressure{"p", plane_faces(mesh, a, L), pressure, false, TimeFunction::ramp(0.0, dt)});
        tm::DirichletCondition c;
        c.name = std::string("sym") + "xyz"[a];
        c.nodes = plane_nodes(mesh, a, 0.0);
        c.components = {a == 0, a == 1, a == 2};
        bc.push_back(c);
      }
      tm::MechanicalSystem sys(model, tm::lumped_dof_mass(node_mass), tm::DirichletSet(mesh.num_points(), bc),
                               loads);
      tm::StaticSolver solver(sys, tm::NewtonOptions{40, 1e-12, 1e-14});
      VecX u = VecX::Zero(sys.num_dofs());
      const double V0 = L * L * L;
      double dv_first = 0.0, dv = 0.0;
      const int steps = static_cast<int>(std::lround(t_end / dt));
      for (int k = 1; k <= steps; ++k) {
        solver.advance((k - 1) * dt, k * dt, u);
        dv = deformed_volume(mesh, u) - V0;
        if (k == 1) dv_first = dv;
      }
      const double ratio = dv / dv_first;
      m.set("volume_ratio_" + variant({Hist::Pk2, scheme, relax}), ratio);
      if (relax == Relax::Deviatoric)
        dev_drift = std::max(dev_drift, std::abs(ratio - 1.0));
      else
        full_ratio = std::min(full_ratio, ratio);
    }
  // Small-strain three-parameter solid in creep: creep compliance J(t) = (1 + a) - a exp(-t/tau_c)
  // (times 1/E_0, tau_c = tau (1 + a)) for a step load; for the load ramped over [0, dt] and held,
  // J_r(t) = (1/dt) int_0^dt J(t - s) ds = (1 + a) - a (tau_c/dt) exp(-t/tau_c) (exp(dt/tau_c) - 1).
  const double a = series.alpha(0), tc = series.tau(0) * (1.0 + a);
  auto J_ramp = [&](double t) { return (1.0 + a) - a * (tc / dt) * std::exp(-t / tc) * std::expm1(dt / tc); };
  const double closed = J_ramp(t_end) / J_ramp(dt);
  const double exact_linear =
      m.metrics.at("volume_ratio_" + variant({Hist::Pk2, Integ::ExactLinear, Relax::Full}));
  m.set("deviatoric_volume_drift", dev_drift);
  m.set("full_volume_ratio_min", full_ratio);
  m.set("full_volume_ratio_small_strain", closed);
  m.set("full_volume_ratio_rel_diff", std::abs(exact_linear - closed) / closed);
  return m;
}

}  // namespace

void register_model_checks(CheckRegistry& registry) {
  registry.add({{"model.objectivity", objectivity},
                {"model.dissipation", dissipation},
                {"model.volume_creep", volume_creep}});
}

}  // namespace tmlab::verify
