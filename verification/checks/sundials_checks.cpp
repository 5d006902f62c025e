// Checks against SUNDIALS (error-controlled references of the semi-discrete model) and against the
// exact hereditary integral.
//
//   sundials.dynamic_order       fixed-step implicit dynamics + Prony recursion vs CVODE (rtol 1e-10) on
//                                the semi-discrete viscoelastic ODE: error at t_end as dt halves
//   sundials.quasistatic_order   fixed-step static solver + recursion vs IDA (rtol 1e-10) on the
//                                quasi-static DAE (creep of a cube under a ramped traction)
//   sundials.hereditary_recursion each recursion against the exact hereditary integral (Gauss-Legendre
//                                convolution) of a smooth prescribed driver, as dt halves
#include "verification/checks/check_support.hpp"

#include "reference_fem/sundials/ode_references.hpp"
#include "reference_fem/sundials/sundials_adapter.hpp"
#include "tensormass/solvers/implicit_dynamics.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/dirichlet.hpp"
#include "tensormass/system/external_loads.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"
#include "tensormass/viscoelastic/hereditary_integral.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include "core/base/format.hpp"
#include "core/config/implicit_scheme.hpp"
#include "core/constitutive/prony.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <ostream>

namespace tmlab::verify {

namespace {

using tm::PronySeries;
using tm::StVenantKirchhoff;
using tm::VecX;
using tm::ViscoelasticOptions;
using tm::ViscoelasticStVK;
using Integ = ViscoelasticOptions::Integration;

/// The measurements of an order check against a SUNDIALS reference, starting with the reference's
/// steps and largest displacement; logs the reference's effort (with its linear iterations when
/// `linear`).
Measurements reference_measurements(const CheckContext& ctx, const std::string& integrator, double rtol,
                                    const tm::IntegratorStats& stats, double scale, bool linear) {
  ctx.log << "  " << integrator << " rtol " << rtol << ": " << stats.steps << " steps, "
          << stats.nonlinear_iterations << " Newton";
  if (linear) ctx.log << ", " << stats.linear_iterations << " linear iterations";
  ctx.log << "\n";
  Measurements m;
  m.set("reference_steps", double(stats.steps));
  m.set("reference_max_displacement", scale);
  return m;
}

/// An empty error series against the step dt.
Series dt_series(const std::string& y_label) {
  Series s;
  s.x_label = "dt [s]";
  s.y_label = y_label;
  return s;
}

/// A Prony recursion named in parameter `key` (core/constitutive/prony.hpp's names).
Integ scheme_from(const ConfigReader& p, const std::string& key, const std::string& name) {
  if (const auto i = prony_integration_from_string(name)) return *i;
  throw p.error(key, "recursion '" + name + "' must be " + choice_list(prony_integration_names()));
}

/// "newmark+exact_linear" -> (Newmark, ExactLinear): the implicit scheme by core/config's names,
/// the recursion by core/constitutive's.
std::pair<tm::ImplicitScheme, Integ> combination(const ConfigReader& p, const std::string& s) {
  const auto plus = s.find('+');
  if (plus == std::string::npos) throw p.error("schemes", "'" + s + "' must read <time scheme>+<recursion>");
  const std::string ts = s.substr(0, plus);
  const std::optional<ImplicitScheme> scheme = implicit_scheme_from_string(ts);
  if (!scheme)
    throw p.error("schemes",
                  "time scheme '" + ts + "' must be " + choice_list(enum_names(kImplicitSchemeNames)));
  return {*scheme, scheme_from(p, "schemes", s.substr(plus + 1))};
}

// ------------------------------------------------------------------ sundials.dynamic_order
// A beam [0, 2L] x [0, L]^2 clamped at x = 0, set swinging by an initial transverse velocity
// v_z = v0 x / 2L, relaxing with one Prony term: u(t_end) from the fixed-step model against CVODE.
Measurements dynamic_order(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const double L = p.positive("size");
  const auto cells = p.require<std::vector<int>>("cells");
  const double nu = p.require<double>("poisson");
  const StVenantKirchhoff mat = StVenantKirchhoff::from_young_poisson(p.positive("young"), nu);
  const PronySeries prony = PronySeries::from_long_term(p.require<std::vector<double>>("alpha"),
                                                        p.require<std::vector<double>>("tau"));
  const double rho = p.positive("density");
  const double v0_tip = p.positive("tip_velocity");
  const double t_end = p.positive("t_end");
  const double rtol = p.positive("reference_rtol");
  const auto dts = p.require<std::vector<double>>("dt");
  const auto schemes = p.require<std::vector<std::string>>("schemes");
  std::vector<std::pair<tm::ImplicitScheme, Integ>> combos;
  for (const auto& s : schemes) combos.push_back(combination(p, s));
  p.finish();
  if (cells.size() != 3)
    throw Error(ctx.vcase.spec_file().string() + ": key 'parameters.cells': three counts");

  const Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3(2 * L, L, L), cells[0], cells[1], cells[2]);
  const VecX node_mass = tm::lumped_node_mass(mesh, rho);
  tm::DirichletCondition clamp;
  clamp.name = "clamp";
  clamp.nodes = plane_nodes(mesh, 0, 0.0);
  const tm::DirichletSet bc(mesh.num_points(), {clamp});
  VecX v0 = VecX::Zero(3 * mesh.num_points());
  for (Index i = 0; i < mesh.num_points(); ++i) v0[3 * i + 2] = v0_tip * mesh.points[i].x() / (2 * L);
  const ViscoelasticOptions base{ViscoelasticOptions::History::Pk2, Integ::ExactLinear,
                                 ViscoelasticOptions::Relaxation::Full};

  // ---- reference: CVODE (BDF, Newton, GMRES with the exact Jacobian action) on y = [u, v, z]
  VecX ref;
  tm::IntegratorStats stats;
  {
    ViscoelasticStVK model(mesh, mat, prony, base);
    tm::MechanicalSystem sys(model, tm::lumped_dof_mass(node_mass), bc, tm::ExternalLoads(mesh, node_mass));
    tm::TensorMassViscoelasticOde ode(mesh, mat, prony, base, sys);
    tm::OdeOptions o;
    o.rtol = rtol;
    o.linear = tm::LinearSolverKind::Spgmr;
    // absolute tolerances 1e-3 rtol of each component's scale: u ~ v0 t_end, v ~ v0, z ~ E * strain
    const double u_scale = v0_tip * t_end, strain = u_scale / L;
    o.atol_vector = ode.absolute_tolerances(1e-3 * rtol * u_scale, 1e-3 * rtol * v0_tip,
                                            1e-3 * rtol * mat.young() * strain);
    tm::OdeIntegrator integ(ode, tm::OdeMethod::CvodeBdf, o, 0.0,
                            ode.initial_state(0.0, VecX::Zero(ode.num_dofs()), v0));
    VecX y;
    integ.advance(t_end, y);
    stats = integ.stats();
    ref = ode.displacement(t_end, y);
  }
  const double scale = ref.lpNorm<Eigen::Infinity>();
  Measurements m = reference_measurements(ctx, "CVODE", rtol, stats, scale, true);
  for (std::size_t c = 0; c < combos.size(); ++c) {
    Series s = dt_series("max |u - u_CVODE| / max |u_CVODE| at t_end");
    for (double dt : dts) {
      ViscoelasticOptions opt = base;
      opt.integration = combos[c].second;
      ViscoelasticStVK model(mesh, mat, prony, opt);
      tm::MechanicalSystem sys(model, tm::lumped_dof_mass(node_mass), bc, tm::ExternalLoads(mesh, node_mass));
      tm::ImplicitDynamics im(sys, combos[c].first, tm::NewtonOptions{40, 1e-11, 1e-15});
      im.initialize(0.0, VecX::Zero(v0.size()), v0);
      const int n = static_cast<int>(std::lround(t_end / dt));
      if (std::abs(n * dt - t_end) > 1e-9 * t_end)
        throw Error(ctx.vcase.spec_file().string() + ": key 'parameters.dt': " + std::to_string(dt) +
                    " does not divide t_end");
      for (int k = 0; k < n; ++k)
        if (!im.step(k * dt, dt).converged)
          throw Error("Newton failed at step " + std::to_string(k) + ", dt " + std::to_string(dt));
      s.x.push_back(dt);
      s.y.push_back((im.displacement() - ref).lpNorm<Eigen::Infinity>() / scale);
    }
    m.series[schemes[c]] = s;
  }
  return m;
}

// ------------------------------------------------------------------ sundials.quasistatic_order
// Cube [0, L]^3 with symmetry rollers at 0, nominal traction T on x = L (consistent nodal loads) on a
// C1 ramp over [0, t_ramp], held; one Prony term. Quasi-static: the static solver + recursion
// against IDA on the DAE (equilibrium algebraic, internal variables differential).
Measurements quasistatic_order(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const double L = p.positive("size");
  const int n = p.get<int>("cells", 2);
  const StVenantKirchhoff mat =
      StVenantKirchhoff::from_young_poisson(p.positive("young"), p.require<double>("poisson"));
  const PronySeries prony = PronySeries::from_long_term(p.require<std::vector<double>>("alpha"),
                                                        p.require<std::vector<double>>("tau"));
  const double traction = p.positive("traction");
  const double t_ramp = p.positive("t_ramp"), t_end = p.positive("t_end"), dt_out = p.positive("dt_output");
  const double rtol = p.positive("reference_rtol");
  const int levels = p.get<int>("levels", 4);
  const auto names = p.require<std::vector<std::string>>("recursions");
  std::vector<Integ> recursions;
  for (const auto& s : names) recursions.push_back(scheme_from(p, "recursions", s));
  p.finish();

  const Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Constant(L), n, n, n);
  const VecX node_mass = tm::lumped_node_mass(mesh, 1000.0);
  std::vector<tm::DirichletCondition> bc;
  for (int a = 0; a < 3; ++a) {
    tm::DirichletCondition c;
    c.name = std::string("sym") + "xyz"[a];
    c.nodes = plane_nodes(mesh, a, 0.0);
    c.components = {a == 0, a == 1, a == 2};
    bc.push_back(c);
  }
  // consistent nodal loads of a uniform traction on the x = L face: area / 3 per triangle vertex
  NodeSelector right;
  right.kind = NodeSelector::Kind::Plane;
  right.axis = 0;
  right.value = L;
  right.tol = 1e-12;
  tm::ExternalLoads loads(mesh, node_mass);
  tm::SurfaceTraction tr;
  tr.name = "pull";
  tr.faces = select_faces(mesh, right);
  tr.traction = Vec3(traction, 0.0, 0.0);
  tr.function = TimeFunction::smooth_ramp(0.0, t_ramp);
  loads.add(tr);
  const ViscoelasticOptions base{ViscoelasticOptions::History::Pk2, Integ::ExactLinear,
                                 ViscoelasticOptions::Relaxation::Full};
  const int outputs = static_cast<int>(std::lround(t_end / dt_out));

  std::vector<VecX> ref;
  tm::IntegratorStats stats;
  {
    ViscoelasticStVK model(mesh, mat, prony, base);
    tm::MechanicalSystem sys(model, tm::lumped_dof_mass(node_mass), tm::DirichletSet(mesh.num_points(), bc),
                             loads);
    tm::TensorMassQuasiStaticDae dae(mesh, mat, prony, base, sys);
    tm::DaeOptions o;
    o.rtol = rtol;
    const double u_scale = traction / mat.young() * L * 3.0;  // ~ the long-term stretch
    o.atol_vector = dae.absolute_tolerances(1e-3 * rtol * u_scale, 1e-3 * rtol * traction);
    tm::DaeIntegrator ida(dae, o, 0.0, dae.initial_state(0.0, VecX::Zero(dae.num_dofs())),
                          VecX::Zero(dae.size()));
    VecX y, yp;
    for (int k = 1; k <= outputs; ++k) {
      ida.advance(dt_out * k, y, yp);
      ref.push_back(y.head(dae.num_dofs()));
    }
    stats = ida.stats();
  }
  double scale = 0.0;
  for (const VecX& r : ref) scale = std::max(scale, r.lpNorm<Eigen::Infinity>());
  Measurements m = reference_measurements(ctx, "IDA", rtol, stats, scale, false);
  for (std::size_t r = 0; r < recursions.size(); ++r) {
    Series s = dt_series("max_t max |u - u_IDA| / max |u_IDA|");
    for (int level = 0; level < levels; ++level) {
      const int per = 1 << level;
      const double dt = dt_out / per;
      ViscoelasticOptions opt = base;
      opt.integration = recursions[r];
      ViscoelasticStVK model(mesh, mat, prony, opt);
      tm::MechanicalSystem sys(model, tm::lumped_dof_mass(node_mass), tm::DirichletSet(mesh.num_points(), bc),
                               loads);
      tm::StaticSolver solver(sys, tm::NewtonOptions{40, 1e-11, 1e-15});
      VecX u = VecX::Zero(sys.num_dofs());
      double e = 0.0;
      for (int k = 1; k <= outputs * per; ++k) {
        solver.advance((k - 1) * dt, k * dt, u);
        if (k % per == 0)
          e = std::max(e, (u - ref[static_cast<std::size_t>(k / per - 1)]).lpNorm<Eigen::Infinity>());
      }
      s.x.push_back(dt);
      s.y.push_back(e / scale);
    }
    m.series[names[r]] = s;
  }
  return m;
}

// ------------------------------------------------------------------ sundials.hereditary_recursion
// A smooth prescribed driver X_e(t) = sin(omega t) + 0.5 sin(2.7 omega t + 0.3) - 0.5 sin(0.3) (so
// X_e(0) = 0) with one Prony term: the recursion h^{n+1} = a h^n + c (X_e^{n+1} - X_e^n) (factors
// from recursion_factors, the code the model uses) against the exact
// h(t) = int_0^t exp(-(t-s)/tau) X_e'(s) ds (composite Gauss-Legendre, converged to round-off).
Measurements hereditary_recursion(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const double tau = p.positive("tau");
  const double omega = p.positive("omega");
  const double t_end = p.positive("t_end");
  const auto dts = p.require<std::vector<double>>("dt");
  const auto names = p.require<std::vector<std::string>>("recursions");
  std::vector<Integ> recursions;
  for (const auto& s : names) recursions.push_back(scheme_from(p, "recursions", s));
  p.finish();
  auto X = [&](double t) {
    return std::sin(omega * t) + 0.5 * std::sin(2.7 * omega * t + 0.3) - 0.5 * std::sin(0.3);
  };
  auto rate = [&](double s, VecX& out) {
    out.resize(1);
    out[0] = omega * std::cos(omega * s) + 1.35 * omega * std::cos(2.7 * omega * s + 0.3);
  };
  Measurements m;
  double quad_check = 0.0;
  for (std::size_t r = 0; r < recursions.size(); ++r) {
    Series s;
    s.x_label = "dt / tau";
    s.y_label = "max_n |h_n - h(t_n)| / max |h|";
    for (double dt : dts) {
      const int n = static_cast<int>(std::lround(t_end / dt));
      const tm::RecursionFactors f = tm::recursion_factors(recursions[r], dt, tau);
      double h = 0.0, err = 0.0, hmax = 0.0;
      for (int k = 1; k <= n; ++k) {
        h = f.a * h + f.c * (X(k * dt) - X((k - 1) * dt));
        const int panels = std::max(8, static_cast<int>(std::ceil(k * dt / std::min(tau, 1.0 / omega) * 4)));
        const double exact = tm::convolve_rate(rate, 1, tau, 0.0, k * dt, panels)[0];
        if (r == 0 && dt == dts.back() && k == n)
          quad_check = std::abs(exact - tm::convolve_rate(rate, 1, tau, 0.0, k * dt, 2 * panels)[0]);
        err = std::max(err, std::abs(h - exact));
        hmax = std::max(hmax, std::abs(exact));
      }
      s.x.push_back(dt / tau);
      s.y.push_back(err / hmax);
    }
    m.series[names[r]] = s;
  }
  m.set("quadrature_self_difference", quad_check);
  return m;
}

}  // namespace

void register_sundials_checks(CheckRegistry& registry) {
  registry.add({{"sundials.dynamic_order", dynamic_order},
                {"sundials.quasistatic_order", quasistatic_order},
                {"sundials.hereditary_recursion", hereditary_recursion}});
}

}  // namespace tmlab::verify
