// Analytic checks of the Prony time stepping (label `analytic`): the viscoelastic tensor-mass model
// on a homogeneous cube against the exact hereditary integrals of polynomial drivers
// (verification/numerics/exp_moments.hpp), every scheme at every time step.
//
//   analytic.prony_relaxation        Prony (standard linear solid) relaxation under a smooth strain ramp
//   analytic.prony_creep             creep of the standard linear solid under a smooth stress ramp
//
// Every function measures and returns Measurements; the tolerances and their reasons live in the
// cases' verify.json (verification/cases/analytic-*/).
#include "verification/checks/analytic_support.hpp"
#include "verification/checks/builtin_checks.hpp"
#include "verification/checks/check_support.hpp"

#include "core/base/error.hpp"
#include "core/base/stopwatch.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/viscoelastic/prony_series.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"
#include "verification/numerics/exp_moments.hpp"
#include "verification/numerics/polynomial.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

namespace tmlab::verify {

namespace {

using namespace analytic;
using numerics::hereditary;
using numerics::Poly;
using numerics::poly_add;
using numerics::poly_eval;
using numerics::poly_mul;
using numerics::smooth_ramp_poly;

// ==== Prony relaxation and creep: exact hereditary integrals of polynomial drivers ============

struct PronyParams {
  tm::StVenantKirchhoff material;
  double size = 0.0;
  int cells = 1;
  double perturb = 0.0;
  std::vector<double> alpha, tau;
  double ramp_time = 1.0, t_end = 3.0, output_interval = 0.1;
  std::vector<double> dts;
  std::vector<std::string> schemes;
  tm::ViscoelasticOptions::History history = tm::ViscoelasticOptions::History::Pk2;
  tm::NewtonOptions newton;
};

PronyParams read_prony(ConfigReader& p) {
  PronyParams r;
  r.material = read_material(p);
  r.size = p.positive("size");
  r.cells = p.require<int>("cells");
  if (r.cells < 1) throw p.error("cells", "must be >= 1");
  r.perturb = p.positive("perturb_fraction", 0.0, true);
  {
    ConfigReader pr = p.child("prony");
    r.alpha = pr.require<std::vector<double>>("alpha");
    r.tau = pr.require<std::vector<double>>("tau");
    pr.finish();
    try {
      (void)tm::PronySeries::from_long_term(r.alpha, r.tau);
    } catch (const Error& e) {
      throw p.error("prony", e.what());
    }
  }
  r.ramp_time = p.positive("ramp_time");
  r.t_end = p.positive("t_end");
  if (r.t_end <= r.ramp_time) throw p.error("t_end", "must exceed ramp_time (a hold phase follows the ramp)");
  r.output_interval = p.positive("output_interval");
  r.dts = positive_list(p, "dts");
  r.schemes = p.require<std::vector<std::string>>("schemes");
  if (r.schemes.empty()) throw p.error("schemes", "must not be empty");
  for (const auto& s : r.schemes) {
    try {
      (void)tm::ViscoelasticOptions::parse_integration(s);
    } catch (const Error& e) {
      throw p.error("schemes", e.what());
    }
  }
  try {
    r.history = tm::ViscoelasticOptions::parse_history(p.get<std::string>("history", "pk2"));
  } catch (const Error& e) {
    throw p.error("history", e.what());
  }
  r.newton = newton_options(p);
  // Output times and the ramp end must be step boundaries for every dt.
  for (double dt : r.dts)
    for (double span : {r.output_interval, r.ramp_time, r.t_end}) {
      const double k = span / dt;
      if (std::abs(k - std::round(k)) > 1e-9 * k)
        throw p.error("dts",
                      "dt = " + std::to_string(dt) + " must divide output_interval, ramp_time and t_end");
    }
  return r;
}

/// Runs the homogeneous cube with `scheme` and step dt; calls sample(t, run) at each output time.
template <class Setup, class Sample>
void run_prony_cube(const PronyParams& P, const Mesh& mesh, const std::string& scheme, double dt, Setup setup,
                    Sample sample) {
  tm::ViscoelasticOptions vo;
  vo.history = P.history;
  vo.integration = tm::ViscoelasticOptions::parse_integration(scheme);
  vo.energy_bookkeeping = false;
  tm::ViscoelasticStVK model(mesh, P.material, tm::PronySeries::from_long_term(P.alpha, P.tau), vo);
  std::vector<tm::DirichletCondition> bcs;
  std::vector<tm::SurfaceTraction> tractions;
  setup(bcs, tractions);
  StaticRun run(mesh, model, bcs, {}, tractions, P.newton);
  const long nsteps = std::lround(P.t_end / dt);
  const long every = std::lround(P.output_interval / dt);
  for (long s = 0; s < nsteps; ++s) {
    const double t0 = s * dt, t1 = (s + 1) * dt;
    run.advance(t0, t1);
    if ((s + 1) % every == 0) sample(t1, run);
  }
}

/// Error series per scheme: max over the output times of |model - exact| / max |exact|.
void add_time_series(Measurements& m, const std::string& scheme, const std::vector<double>& dts,
                     const std::vector<double>& errors) {
  Series s;
  s.x_label = "dt [s]";
  s.y_label = "max |error| / peak";
  s.x = dts;
  s.y = errors;
  m.series["error_" + scheme] = s;
  m.set("finest_error_" + scheme, errors.back());
  if (dts.size() >= 2)
    m.set("order_" + scheme + "_last_pair",
          std::log(errors[errors.size() - 2] / errors.back()) / std::log(dts[dts.size() - 2] / dts.back()));
}

/// The time-step study of a Prony cube: every scheme at every dt, the error of a run the maximum of
/// deviation(t, run) (= |model - exact| / peak) over the output times; logged per run ("of the peak
/// <quantity>") and added to m by add_time_series.
template <class Setup, class Deviation>
void time_step_study(const PronyParams& P, const Mesh& mesh, const CheckContext& ctx,
                     const std::string& quantity, Setup setup, Deviation deviation, Measurements& m) {
  for (const auto& scheme : P.schemes) {
    std::vector<double> errors;
    for (double dt : P.dts) {
      const auto t0 = std::chrono::steady_clock::now();
      double err = 0.0;
      run_prony_cube(P, mesh, scheme, dt, setup,
                     [&](double t, const StaticRun& run) { err = std::max(err, deviation(t, run)); });
      errors.push_back(err);
      ctx.log << "  " << scheme << " dt = " << dt << ": max error " << fmt(err) << " of the peak " << quantity
              << " (" << fmt(seconds_since(t0), 2) << " s)\n";
    }
    add_time_series(m, scheme, P.dts, errors);
  }
}

// Relaxation: u_x = eps0 L f(t) on X = L, f the C1 cubic ramp over [0, t1], held to t_end. The
// state is homogeneous with S22 = S33 = 0 for all t (lateral E22 = -nu E11, so the lateral long-term
// stress and its history vanish), and the model's time-continuous limit is, exactly (finite strain):
//   pk2:          F(t) = L^2 l(t) E_inf [Y(t) + sum_j alpha_j h_j(t)],  Y = E11 = eps + eps^2/2
//   nodal_force:  F(t) = L^2 E_inf [Y(t) + sum_j alpha_j h_j(t)],       Y = l E11 (nominal elastic stress /
//   E)
// h_j(t) = int_0^t exp(-(t-s)/tau_j) Y'(s) ds; Y is a polynomial in t on the ramp, so h_j is
// evaluated in closed form (exp_moments).
Measurements prony_relaxation(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const double eps0 = p.positive("strain");
  PronyParams P = read_prony(p);
  p.finish();
  const double L = P.size, Einf = P.material.young();
  const Mesh mesh = perturb_interior(
      make_box_mesh(Vec3::Zero(), Vec3::Constant(L), P.cells, P.cells, P.cells), P.perturb, 11u);

  const Poly f = smooth_ramp_poly(P.ramp_time);
  const Poly eps = poly_mul({eps0}, f);
  const Poly l = poly_add({1.0}, eps);
  const Poly E11 = poly_add(eps, poly_mul({0.5}, poly_mul(eps, eps)));
  const bool pk2 = P.history == tm::ViscoelasticOptions::History::Pk2;
  const Poly Y = pk2 ? E11 : poly_mul(l, E11);
  auto exact = [&](double t) {
    const double te = std::min(t, P.ramp_time);
    double X = poly_eval(Y, te);
    for (std::size_t j = 0; j < P.alpha.size(); ++j)
      X += P.alpha[j] * hereditary(Y, P.ramp_time, P.tau[j], t);
    return L * L * Einf * X * (pk2 ? poly_eval(l, te) : 1.0);
  };
  // The same closed form in small strain (Y = eps, no l factor): how much finite strain matters.
  auto exact_small = [&](double t) {
    const double te = std::min(t, P.ramp_time);
    double X = poly_eval(eps, te);
    for (std::size_t j = 0; j < P.alpha.size(); ++j)
      X += P.alpha[j] * hereditary(eps, P.ramp_time, P.tau[j], t);
    return L * L * Einf * X;
  };
  double peak = 0.0, nonlinear = 0.0;
  for (double t = P.output_interval; t <= P.t_end + 1e-12; t += P.output_interval)
    peak = std::max(peak, std::abs(exact(t)));
  for (double t = P.output_interval; t <= P.t_end + 1e-12; t += P.output_interval)
    nonlinear = std::max(nonlinear, std::abs(exact(t) - exact_small(t)) / peak);

  Measurements m;
  time_step_study(
      P, mesh, ctx, "force",
      [&](std::vector<tm::DirichletCondition>& bcs, std::vector<tm::SurfaceTraction>&) {
        bcs = symmetry_planes(mesh);
        bcs.push_back(condition("pull", group_nodes(mesh, "xmax"), {true, false, false}, Vec3(eps0 * L, 0, 0),
                                TimeFunction::smooth_ramp(0.0, P.ramp_time)));
      },
      [&](double t, const StaticRun& run) { return std::abs(run.reaction(3, t).x() - exact(t)) / peak; }, m);
  m.set("peak_force_N", peak);
  m.set("finite_strain_effect", nonlinear);
  m.notes.push_back(
      "closed form includes the geometric nonlinearity; finite-strain vs small-strain closed form differ "
      "by " +
      fmt(nonlinear, 2) + " of the peak");
  return m;
}

// Creep: a dead nominal traction sigma0 f(t) on X = L (f the C1 cubic ramp over [0, t1], held),
// one Prony term (standard linear solid, r = 1 + alpha e^{-t/tau}). Its creep compliance is
//   J(t) = (1/E_inf) [1 - beta e^{-t/tau_c}],  beta = alpha/(1+alpha),  tau_c = tau (1 + alpha),
// so the small-strain creep strain is eps(t) = (1/E_inf) [sigma(t) - beta int_0^t e^{-(t-s)/tau_c} sigma'(s)
// ds]. The model is measured by the nominal strain u_x(L)/L (mean over the loaded face). Finite strain
// changes eps by a relative O(1.5 eps), kept negligible by a tiny load (reported as
// "geometric_nonlinearity_bound" = 1.5 max eps).
Measurements prony_creep(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const double stress_ratio = p.positive("stress_over_E");
  PronyParams P = read_prony(p);
  p.finish();
  if (P.alpha.size() != 1)
    throw Error(ctx.vcase.spec_file().string() +
                ": key 'parameters.prony': the creep closed form is that of the standard "
                "linear solid: give exactly one Prony term");
  const double L = P.size, Einf = P.material.young(), sigma0 = stress_ratio * Einf;
  const double alpha = P.alpha[0], beta = alpha / (1.0 + alpha), tau_c = P.tau[0] * (1.0 + alpha);
  const Mesh mesh = perturb_interior(
      make_box_mesh(Vec3::Zero(), Vec3::Constant(L), P.cells, P.cells, P.cells), P.perturb, 13u);
  const std::vector<Index> pulled = group_nodes(mesh, "xmax");

  const Poly sigma = poly_mul({sigma0}, smooth_ramp_poly(P.ramp_time));
  auto exact = [&](double t) {
    return (poly_eval(sigma, std::min(t, P.ramp_time)) - beta * hereditary(sigma, P.ramp_time, tau_c, t)) /
           Einf;
  };
  double peak = 0.0;
  for (double t = P.output_interval; t <= P.t_end + 1e-12; t += P.output_interval)
    peak = std::max(peak, std::abs(exact(t)));

  Measurements m;
  time_step_study(
      P, mesh, ctx, "strain",
      [&](std::vector<tm::DirichletCondition>& bcs, std::vector<tm::SurfaceTraction>& tr) {
        bcs = symmetry_planes(mesh);
        tm::SurfaceTraction t;
        t.name = "creep";
        t.faces = select_faces(mesh, NodeSelector::from_json({{"group", "xmax"}}));
        t.traction = Vec3(sigma0, 0, 0);
        t.function = TimeFunction::smooth_ramp(0.0, P.ramp_time);
        tr.push_back(t);
      },
      [&](double t, const StaticRun& run) {
        double ux = 0.0;
        for (Index i : pulled) ux += run.u[3 * i];
        const double eps_h = ux / double(pulled.size()) / L;
        return std::abs(eps_h - exact(t)) / peak;
      },
      m);
  m.set("peak_strain", peak);
  m.set("geometric_nonlinearity_bound", 1.5 * peak);
  return m;
}

}  // namespace

void register_analytic_prony_checks(CheckRegistry& registry) {
  registry.add("analytic.prony_relaxation", prony_relaxation);
  registry.add("analytic.prony_creep", prony_creep);
}

}  // namespace tmlab::verify
