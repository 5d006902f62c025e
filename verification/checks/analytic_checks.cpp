// Analytic checks of the verification catalogue: the tensor-mass model (and, for neo-Hookean, the
// deal.II reference) against closed-form solutions of continuum mechanics.
//
//   analytic.uniaxial_stvk           homogeneous uniaxial stretch, St VK nominal stress and lateral stretch
//   analytic.simple_shear_neohookean homogeneous simple shear of the deal.II neo-Hookean reference
//   analytic.prony_relaxation        Prony (standard linear solid) relaxation under a smooth strain ramp
//   analytic.prony_creep             creep of the standard linear solid under a smooth stress ramp
//   analytic.hertz_traction          Hertz pressure on a thick graded block vs the elastic half-space
//   analytic.mms_static              manufactured static solution, L2 and H1 mesh convergence
//
// Every function measures and returns Measurements; the tolerances and their reasons live in the
// cases' verify.json (verification/cases/analytic-*/).
#include "verification/checks/check_support.hpp"

#include "core/base/format.hpp"

#include "core/base/error.hpp"
#include "core/base/stopwatch.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tet_geometry.hpp"
#include "tensormass/materials/stvk_material.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/dirichlet.hpp"
#include "tensormass/system/external_loads.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"
#include "tensormass/viscoelastic/prony_series.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"
#include "verification/checks/builtin_checks.hpp"

#ifdef TMLAB_HAVE_REFERENCE
#include "core/config/case_config.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/results/series_names.hpp"
#include "reference_fem/dealii/reference_runner.hpp"
#include "runner/case_runner.hpp"
#endif

#include <Eigen/Dense>
#include <Eigen/IterativeLinearSolvers>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace tmlab::verify {

namespace {

using tm::Mat3;
using tm::VecX;

constexpr double kPi = 3.14159265358979323846;

std::string fmt(double v, int digits = 3) { return scientific(v, digits); }

/// Reads a list of numbers (non-empty, each finite and > 0 unless allow_nonpositive).
std::vector<double> positive_list(ConfigReader& p, const std::string& key) {
  const auto v = p.require<std::vector<double>>(key);
  if (v.empty()) throw p.error(key, "must not be empty");
  for (double x : v)
    if (!(x > 0.0) || !std::isfinite(x))
      throw p.error(key, "entries must be finite and > 0 (got " + std::to_string(x) + ")");
  return v;
}

std::vector<int> count_list(ConfigReader& p, const std::string& key, int min_value) {
  const auto v = p.require<std::vector<int>>(key);
  if (v.empty()) throw p.error(key, "must not be empty");
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i] < min_value) throw p.error(key, "entries must be >= " + std::to_string(min_value));
    if (i > 0 && v[i] <= v[i - 1]) throw p.error(key, "must increase strictly");
  }
  return v;
}

tm::StVenantKirchhoff read_material(ConfigReader& p) {
  const double E = p.positive("E");
  const double nu = p.require<double>("nu");
  try {
    return tm::StVenantKirchhoff::from_young_poisson(E, nu);
  } catch (const Error& e) {
    throw p.error("nu", e.what());
  }
}

tm::NewtonOptions newton_options(ConfigReader& p) {
  tm::NewtonOptions o;
  o.rtol = p.positive("newton_rtol", 1e-12);
  // Absolute floor off: several cases load with tiny forces (small-strain regime), where the
  // default 1e-14 N floor would stop Newton long before the relative tolerance.
  o.atol = 0.0;
  o.max_iterations = 30;
  return o;
}

/// A static problem on a mesh: the model, the constraints and loads, solved by the tensor-mass
/// StaticSolver (Newton with line search and cut-backs; begin_step/commit_step per increment).
struct StaticRun {
  const Mesh& mesh;
  tm::ElasticModel& model;
  tm::MechanicalSystem system;
  tm::StaticSolver solver;
  VecX u;
  StaticRun(const Mesh& m, tm::ElasticModel& mod, std::vector<tm::DirichletCondition> bcs,
            const std::vector<tm::NodalForce>& nodal, const std::vector<tm::SurfaceTraction>& tractions,
            const tm::NewtonOptions& options)
      : mesh(m),
        model(mod),
        system(mod, tm::lumped_dof_mass(tm::lumped_node_mass(m, 1000.0)),
               tm::DirichletSet(m.num_points(), std::move(bcs)), make_loads(m, nodal, tractions)),
        solver(system, options),
        u(VecX::Zero(3 * m.num_points())) {}

  static tm::ExternalLoads make_loads(const Mesh& m, const std::vector<tm::NodalForce>& nodal,
                                      const std::vector<tm::SurfaceTraction>& tractions) {
    tm::ExternalLoads loads(m, tm::lumped_node_mass(m, 1000.0));
    for (const auto& f : nodal) loads.add(f);
    for (const auto& t : tractions) loads.add(t);
    return loads;
  }
  void advance(double t0, double t1) { solver.advance(t0, t1, u); }
  /// Reaction of Dirichlet condition k at the committed state: sum over its DOFs of f_int - f_ext.
  Vec3 reaction(std::size_t k, double t) const {
    VecX fi, fe;
    model.internal_force(u, fi);
    system.loads().assemble(u, t, fe);
    return system.bc().resultant(k, fi - fe);
  }
  /// |R_free| / |f_int| at u: the equilibrium residual actually reached.
  double relative_residual(double t) const {
    VecX fi, fe;
    model.internal_force(u, fi);
    system.loads().assemble(u, t, fe);
    VecX r = fi - fe;
    const double scale = std::max(fi.norm(), fe.norm());
    system.bc().zero_constrained(r);
    return scale > 0 ? r.norm() / scale : r.norm();
  }
};

std::vector<Index> group_nodes(const Mesh& m, const std::string& name) { return nodes_of_group(m, name); }

tm::DirichletCondition condition(const std::string& name, std::vector<Index> nodes, std::array<bool, 3> comps,
                                 const Vec3& value = Vec3::Zero(),
                                 TimeFunction f = TimeFunction::constant(1.0)) {
  tm::DirichletCondition c;
  c.name = name;
  c.nodes = std::move(nodes);
  c.components = comps;
  c.value = value;
  c.function = std::move(f);
  return c;
}

/// The three symmetry planes of a box [0, L]^3 (x = 0: u_x = 0, y = 0: u_y = 0, z = 0: u_z = 0).
std::vector<tm::DirichletCondition> symmetry_planes(const Mesh& m) {
  return {condition("x0", group_nodes(m, "xmin"), {true, false, false}),
          condition("y0", group_nodes(m, "ymin"), {false, true, false}),
          condition("z0", group_nodes(m, "zmin"), {false, false, true})};
}

// ==== 1. uniaxial St VK ==========================================================================
//
// Cube [0, L]^3, symmetry planes, u_x = (l - 1) L prescribed on x = L, lateral faces free. The
// homogeneous state F = diag(l, m, m) with S22 = S33 = 0 gives E22 = -nu E11, i.e.
//   m = sqrt(1 - nu (l^2 - 1)),  S11 = E E11 = E (l^2 - 1)/2,  P11 = l S11,  sigma11 = l S11 / m^2,
// and the reaction of the pulled face is P11 L^2. P1 tets reproduce affine fields exactly (also on
// a perturbed mesh), so the only errors are Newton's stopping point and round-off.
Measurements uniaxial_stvk(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const tm::StVenantKirchhoff mat = read_material(p);
  const double L = p.positive("size");
  const int n = p.require<int>("cells");
  if (n < 1) throw p.error("cells", "must be >= 1");
  const double perturb = p.positive("perturb_fraction", 0.0, true);
  const auto stretches = positive_list(p, "stretches");
  const int steps = p.require<int>("load_steps");
  if (steps < 1) throw p.error("load_steps", "must be >= 1");
  const tm::NewtonOptions newton = newton_options(p);
  p.finish();
  const double E = mat.young(), nu = mat.poisson();
  for (double l : stretches)
    if (1.0 - nu * (l * l - 1.0) <= 0.0)
      throw p.error("stretches",
                    "stretch " + std::to_string(l) + " has no uniaxial St VK state (1 - nu (l^2 - 1) <= 0)");

  const Mesh mesh = perturb_interior(make_box_mesh(Vec3::Zero(), Vec3::Constant(L), n, n, n), perturb, 7u);
  tm::TensorMassStVK model(mesh, mat);
  Measurements m;
  double worst_force = 0.0, worst_lateral = 0.0, worst_field = 0.0, worst_residual = 0.0;
  nlohmann::json rows = nlohmann::json::array();
  for (double l : stretches) {
    auto bcs = symmetry_planes(mesh);
    bcs.push_back(condition("pull", group_nodes(mesh, "xmax"), {true, false, false},
                            Vec3((l - 1.0) * L, 0, 0), TimeFunction::ramp(0.0, 1.0)));
    StaticRun run(mesh, model, bcs, {}, {}, newton);
    for (int s = 0; s < steps; ++s) run.advance(double(s) / steps, double(s + 1) / steps);
    const double lat = std::sqrt(1.0 - nu * (l * l - 1.0));
    const double S11 = E * 0.5 * (l * l - 1.0);
    const double force_exact = l * S11 * L * L;
    const double force = run.reaction(3, 1.0).x();
    // The whole field against the affine solution u = ((l-1) X, (m-1) Y, (m-1) Z).
    double field = 0.0, lat_h = 0.0;
    for (Index i = 0; i < mesh.num_points(); ++i) {
      const Vec3& X = mesh.points[i];
      const Vec3 ue((l - 1.0) * X.x(), (lat - 1.0) * X.y(), (lat - 1.0) * X.z());
      field = std::max(field, (run.u.segment<3>(3 * i) - ue).norm() / L);
    }
    const Index corner = nearest_node(mesh, Vec3::Constant(L));
    lat_h = 1.0 + run.u[3 * corner + 1] / L;
    const double e_force = std::abs(force - force_exact) / std::abs(force_exact);
    const double e_lat = std::abs(lat_h - lat) / lat;
    worst_force = std::max(worst_force, e_force);
    worst_lateral = std::max(worst_lateral, e_lat);
    worst_field = std::max(worst_field, field);
    worst_residual = std::max(worst_residual, run.relative_residual(1.0));
    rows.push_back({{"stretch", l},
                    {"reaction_N", force},
                    {"reaction_exact_N", force_exact},
                    {"nominal_stress_Pa", force / (L * L)},
                    {"cauchy_stress_Pa", force / (lat * lat * L * L)},
                    {"lateral_stretch", lat_h},
                    {"lateral_stretch_exact", lat},
                    {"reaction_rel_error", e_force},
                    {"lateral_rel_error", e_lat},
                    {"field_error_over_L", field}});
    ctx.log << "  stretch " << l << ": reaction " << fmt(force, 12) << " N (exact " << fmt(force_exact, 12)
            << "), lateral stretch " << fmt(lat_h, 12) << " (exact " << fmt(lat, 12) << ")\n";
  }
  m.set("reaction_rel_error", worst_force);
  m.set("lateral_stretch_rel_error", worst_lateral);
  m.set("displacement_field_error", worst_field);
  m.set("equilibrium_residual", worst_residual);
  m.data["stretches"] = rows;
  m.notes.push_back(std::to_string(mesh.num_tets()) + " tets (perturbed interior), " +
                    std::to_string(stretches.size()) + " stretches from " + fmt(stretches.front(), 2) +
                    " to " + fmt(stretches.back(), 2));
  return m;
}

// ==== 2. neo-Hookean simple shear (deal.II reference) ===========================================
#ifdef TMLAB_HAVE_REFERENCE
//
// F = I + gamma e1 (x) e2 prescribed on every boundary node of a cube, interior free. For
// W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2 and J = 1:
//   P = mu (F - F^-T) = mu gamma (e1 (x) e2 + e2 (x) e1),   sigma = mu (B - I):
//   sigma12 = mu gamma, sigma11 = mu gamma^2, sigma22 = sigma33 = 0.
// Measured from reactions: the top face Y = L (deformed normal e2, area L^2) carries
// sigma e2 L^2 = (sigma12, sigma22, 0) L^2. The nodes of X = L below the top edge and above the
// bottom edge carry P e1 integrated against the sum of their shape functions, L (L - h) for the
// structured grid (h = L/n): its x component is P11 = sigma11 - gamma sigma12 (= 0), so
// sigma11 = P11 + gamma sigma12.
Measurements simple_shear_neohookean(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const tm::StVenantKirchhoff mat = read_material(p);
  const double L = p.positive("size");
  const int n = p.require<int>("cells");
  if (n < 2) throw p.error("cells", "must be >= 2 (the X = L face needs a node row below the top edge)");
  const double gamma = p.positive("gamma");
  const int steps = p.require<int>("load_steps");
  if (steps < 1) throw p.error("load_steps", "must be >= 1");
  const double rtol = p.positive("newton_rtol", 1e-12);
  p.finish();
  const double E = mat.young(), nu = mat.poisson(), mu = mat.mu;

  const Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Constant(L), n, n, n);
  const std::string mesh_file = (ctx.work_dir / "shear.msh").string();
  write_gmsh22(mesh, mesh_file);
  const double tol = 1e-9 * L;
  auto on = [&](double a, double b) { return std::abs(a - b) < tol; };
  nlohmann::json boundary = nlohmann::json::array();
  auto layer = [&](const std::string& name, const std::vector<Index>& nodes, double y) {
    nlohmann::json ids = nlohmann::json::array();
    for (Index i : nodes) ids.push_back(i);
    boundary.push_back({{"name", name},
                        {"nodes", {{"nodes", ids}}},
                        {"value", {gamma * y, 0.0, 0.0}},
                        {"function", {{"type", "ramp"}, {"t0", 0.0}, {"t1", 1.0}}}});
  };
  std::vector<std::string> xmax_layers;
  for (int k = 0; k <= n; ++k) {
    const double y = L * k / n;
    std::vector<Index> xmax, rest;
    for (Index i = 0; i < mesh.num_points(); ++i) {
      const Vec3& X = mesh.points[i];
      if (!on(X.y(), y)) continue;
      const bool face_x = on(X.x(), 0) || on(X.x(), L), face_z = on(X.z(), 0) || on(X.z(), L);
      if (k == 0 || k == n || face_x || face_z) (k > 0 && k < n && on(X.x(), L) ? xmax : rest).push_back(i);
    }
    if (k == 0 || k == n) {
      layer(k == 0 ? "bottom" : "top", rest, y);
    } else {
      layer("xmax" + std::to_string(k), xmax, y);
      layer("side" + std::to_string(k), rest, y);
      xmax_layers.push_back("xmax" + std::to_string(k));
    }
  }
  const nlohmann::json doc = {
      {"name", "shear"},
      {"mesh", {{"file", mesh_file}}},
      {"material", {{"E", E}, {"nu", nu}, {"density", 1000}}},
      {"boundary", boundary},
      {"solver", {{"type", "static"}, {"steps", steps}, {"newton", {{"rtol", rtol}}}}},
      {"output", {{"vtu", false}, {"xdmf", false}, {"plots", false}}}};
  const CaseConfig config = parse_case(doc, ctx.vcase.spec_file().string(), {ctx.work_dir.string()});
  tmlab::RunOptions ro;
  ro.results_root = (ctx.work_dir / "results").string();
  ro.tmlab_root = ctx.source_root.string();
  ro.plots = false;
  ref::ReferenceOptions refo;
  refo.law = MaterialLaw::NeoHookean;
  refo.newton_rtol = rtol;
  refo.serial = true;
  const auto result = ref::run_reference_case(config, ro, refo);

  const H5File ts = H5File::open_read(result.dir + "/timeseries.h5");
  auto series = [&](const std::string& name) { return ts.read_double("/series/" + name); };
  const auto time = series("time");
  namespace sn = series_names;
  const auto top_x = series(sn::component(sn::reaction("top"), "x")),
             top_y = series(sn::component(sn::reaction("top"), "y")),
             top_z = series(sn::component(sn::reaction("top"), "z"));
  std::vector<double> right_x(time.size(), 0.0), right_y(time.size(), 0.0);
  for (const auto& name : xmax_layers) {
    const auto rx = series(sn::component(sn::reaction(name), "x")),
               ry = series(sn::component(sn::reaction(name), "y"));
    for (std::size_t s = 0; s < time.size(); ++s) {
      right_x[s] += rx[s];
      right_y[s] += ry[s];
    }
  }
  const double A = L * L, A_right = L * (L - L / n);
  double e12 = 0.0, e22 = 0.0, e11 = 0.0, e21 = 0.0;
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t s = 0; s < time.size(); ++s) {
    const double g = gamma * time[s];
    if (g <= 0.0) continue;
    const double s12 = top_x[s] / A, s22 = top_y[s] / A, s32 = top_z[s] / A;
    const double p11 = right_x[s] / A_right, p21 = right_y[s] / A_right;
    const double s11 = p11 + g * s12;
    e12 = std::max(e12, std::abs(s12 - mu * g) / (mu * g));
    e22 = std::max(e22, std::max(std::abs(s22), std::abs(s32)) / (mu * g));
    e11 = std::max(e11, std::abs(s11 - mu * g * g) / (mu * g * g));
    e21 = std::max(e21, std::abs(p21 - mu * g) / (mu * g));
    rows.push_back({{"gamma", g},
                    {"sigma12_Pa", s12},
                    {"sigma22_Pa", s22},
                    {"sigma11_Pa", s11},
                    {"P21_Pa", p21},
                    {"mu_gamma_Pa", mu * g}});
    ctx.log << "  gamma " << g << ": sigma12 " << fmt(s12, 12) << " Pa (mu gamma " << fmt(mu * g, 12)
            << "), sigma11 " << fmt(s11, 12) << " Pa (mu gamma^2 " << fmt(mu * g * g, 12) << "), sigma22 "
            << fmt(s22, 3) << " Pa\n";
  }
  // The interior nodes against the affine field u = gamma Y e1 (last frame).
  H5File::Dims dims;
  const auto u = H5File::open_read(result.dir + "/displacement.h5").read_double("/u", &dims);
  const std::size_t last = (dims[0] - 1) * dims[1];
  double field = 0.0;
  for (Index i = 0; i < mesh.num_points(); ++i) {
    const Vec3 ue(gamma * mesh.points[i].y(), 0, 0);
    const Vec3 uh(u[last + 3 * i], u[last + 3 * i + 1], u[last + 3 * i + 2]);
    field = std::max(field, (uh - ue).norm() / (gamma * L));
  }
  Measurements m;
  m.set("sigma12_rel_error", e12);
  m.set("sigma11_rel_error", e11);
  m.set("normal_stress_sigma22_over_mu_gamma", e22);
  m.set("P21_rel_error", e21);
  m.set("displacement_field_error", field);
  m.data["steps"] = rows;
  m.notes.push_back("deal.II P1 neo-Hookean, " + std::to_string(mesh.num_tets()) + " tets, gamma up to " +
                    fmt(gamma, 2));
  return m;
}
#endif  // TMLAB_HAVE_REFERENCE

// ==== 3. Prony relaxation and creep: exact hereditary integrals of polynomial drivers ============

/// Polynomial in t, coefficients c[k] of t^k.
using Poly = std::vector<double>;
Poly poly_mul(const Poly& a, const Poly& b) {
  Poly r(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) r[i + j] += a[i] * b[j];
  return r;
}
Poly poly_add(Poly a, const Poly& b, double sb = 1.0) {
  if (a.size() < b.size()) a.resize(b.size(), 0.0);
  for (std::size_t i = 0; i < b.size(); ++i) a[i] += sb * b[i];
  return a;
}
Poly poly_deriv(const Poly& a) {
  if (a.size() < 2) return {0.0};
  Poly r(a.size() - 1);
  for (std::size_t k = 1; k < a.size(); ++k) r[k - 1] = double(k) * a[k];
  return r;
}
double poly_eval(const Poly& a, double t) {
  double v = 0.0;
  for (std::size_t k = a.size(); k-- > 0;) v = v * t + a[k];
  return v;
}

/// I_k(t) = int_0^t s^k exp(-(t - s)/tau) ds, k = 0..kmax, exactly: by the recursion
/// I_k = tau t^k - k tau I_{k-1}, I_0 = -tau expm1(-t/tau) when t >= tau (no cancellation there), and
/// by the alternating series I_k = t^{k+1} k! sum_m (-t/tau)^m / (k+m+1)! when t < tau.
std::vector<double> exp_moments(double t, double tau, std::size_t kmax) {
  std::vector<double> I(kmax + 1, 0.0);
  const double x = t / tau;
  if (x >= 1.0) {
    I[0] = -tau * std::expm1(-x);
    double tk = 1.0;
    for (std::size_t k = 1; k <= kmax; ++k) {
      tk *= t;
      I[k] = tau * tk - double(k) * tau * I[k - 1];
    }
    return I;
  }
  double tk1 = t, kfact = 1.0;  // t^{k+1}, k!
  for (std::size_t k = 0; k <= kmax; ++k) {
    if (k > 0) {
      tk1 *= t;
      kfact *= double(k);
    }
    // sum_m (-x)^m / (k+m+1)!, terms computed by ratio.
    double term = 1.0;
    for (std::size_t j = 1; j <= k + 1; ++j) term /= double(j);  // 1/(k+1)!
    double sum = term;
    for (int mm = 1; mm < 200; ++mm) {
      term *= -x / double(k + 1 + mm);
      sum += term;
      if (std::abs(term) < 1e-18 * std::abs(sum)) break;
    }
    I[k] = tk1 * kfact * sum;
  }
  return I;
}

/// h(t) = int_0^t exp(-(t-s)/tau) Y'(s) ds for Y polynomial on [0, t1] and constant after.
double hereditary(const Poly& Y, double t1, double tau, double t) {
  const Poly dY = poly_deriv(Y);
  const double te = std::min(t, t1);
  const auto I = exp_moments(te, tau, dY.size());
  double h = 0.0;
  for (std::size_t k = 0; k < dY.size(); ++k) h += dY[k] * I[k];
  if (t > t1) h *= std::exp(-(t - t1) / tau);
  return h;
}

/// The C1 cubic ramp 3 s^2 - 2 s^3, s = t/t1, as a polynomial in t (TimeFunction::smooth_ramp).
Poly smooth_ramp_poly(double t1) { return {0.0, 0.0, 3.0 / (t1 * t1), -2.0 / (t1 * t1 * t1)}; }

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

// ==== 4. Hertz pressure on a thick block =========================================================
//
// Quarter model (symmetry planes x = 0, y = 0) of the block [0, W]^2 x [-W, 0], bottom clamped,
// outer sides free, loaded on the top z = 0 by the Hertz pressure p(r) = p0 sqrt(1 - r^2/a^2).
// Half-space (Johnson, Contact Mechanics, eq. 3.41a): u_z(r) = -(1 - nu^2)/E pi p0/(4a) (2a^2 - r^2),
// r <= a, so the offset-free differences are
//   delta(r) = u_z(r) - u_z(0) = (1 - nu^2) pi p0 r^2 / (4 a E),   delta(a) = (1 - nu^2) pi p0 a / (4E).
//
// Mesh: make_box_mesh of the reference cube [0, T]^2 x [-T, 0] (N cells per unit of T) mapped
// radially in the max-norm t = |xi|_inf: x = xi s(t)/t with s(t) = a t/t_a for t <= t_a (a uniform grid
// of N t_a cells across the load radius) and s(t) = a + (a/t_a)(exp(k (t - t_a)) - 1)/k beyond (C1;
// k from s(1) = W). Refining N halves every cell; the planes x = 0, y = 0, z = 0 and the outer
// faces stay planar. A larger block (the truncation estimate) extends T beyond 1 with the same s, so
// the inner mesh is identical.
double grading_rate(double W_over_a, double t_a) {
  // Solve a + (a/t_a)(e^{k(1-t_a)} - 1)/k = W for k > 0 by bisection (the left side grows with k).
  auto g = [&](double k) { return 1.0 + (std::expm1(k * (1.0 - t_a)) / k) / t_a - W_over_a; };
  double lo = 1e-9, hi = 1.0;
  while (g(hi) < 0.0) hi *= 2.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Mesh hertz_mesh(double a, double t_a, double k, int N, double T) {
  const int cells = static_cast<int>(std::lround(N * T));
  Mesh mesh = make_box_mesh(Vec3(0, 0, -double(cells) / N), Vec3(double(cells) / N, double(cells) / N, 0),
                            cells, cells, cells);
  auto s = [&](double t) { return t <= t_a ? a * t / t_a : a + (a / t_a) * std::expm1(k * (t - t_a)) / k; };
  for (Vec3& x : mesh.points) {
    const double t = x.cwiseAbs().maxCoeff();
    if (t > 0.0) x *= s(t) / t;
  }
  return mesh;
}

/// The 7-point degree-5 rule on a triangle (Dunavant): weights and barycentric points.
constexpr double kTriW[7] = {0.225,
                             0.1323941527885062,
                             0.1323941527885062,
                             0.1323941527885062,
                             0.1259391805448271,
                             0.1259391805448271,
                             0.1259391805448271};
constexpr double kTriB[7][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3},
                                {0.0597158717897698, 0.4701420641051151, 0.4701420641051151},
                                {0.4701420641051151, 0.0597158717897698, 0.4701420641051151},
                                {0.4701420641051151, 0.4701420641051151, 0.0597158717897698},
                                {0.7974269853530873, 0.1012865073234563, 0.1012865073234563},
                                {0.1012865073234563, 0.7974269853530873, 0.1012865073234563},
                                {0.1012865073234563, 0.1012865073234563, 0.7974269853530873}};

double hertz_pressure(const Vec3& x, double a, double p0) {
  const double q = 1.0 - (x.x() * x.x() + x.y() * x.y()) / (a * a);
  return q > 0.0 ? p0 * std::sqrt(q) : 0.0;
}

/// Adds int p N_c dA (c = the parent face's 3 vertices X) over the sub-triangle whose corners have
/// the parent barycentric coordinates B (one row per corner), splitting it in four `level` more
/// times while it meets the edge of contact r = a.
void integrate_hertz(const std::array<Vec3, 3>& X, const Eigen::Matrix3d& B, int level, double a, double p0,
                     std::array<double, 3>& out) {
  std::array<Vec3, 3> y;
  for (int c = 0; c < 3; ++c) y[c] = B(c, 0) * X[0] + B(c, 1) * X[1] + B(c, 2) * X[2];
  const Vec3 centre = (y[0] + y[1] + y[2]) / 3.0;
  double rad = 0.0, rmax = 0.0;
  for (int c = 0; c < 3; ++c) {
    rad = std::max(rad, (y[c] - centre).norm());
    rmax = std::max(rmax, std::hypot(y[c].x(), y[c].y()));
  }
  const double rc = std::hypot(centre.x(), centre.y());
  if (rc - rad >= a) return;    // wholly outside the contact: p = 0
  if (level > 0 && rmax > a) {  // meets r = a: split
    const Eigen::RowVector3d b0 = B.row(0), b1 = B.row(1), b2 = B.row(2);
    const Eigen::RowVector3d m0 = 0.5 * (b1 + b2), m1 = 0.5 * (b0 + b2), m2 = 0.5 * (b0 + b1);
    Eigen::Matrix3d sub;
    sub << b0, m2, m1;
    integrate_hertz(X, sub, level - 1, a, p0, out);
    sub << m2, b1, m0;
    integrate_hertz(X, sub, level - 1, a, p0, out);
    sub << m1, m0, b2;
    integrate_hertz(X, sub, level - 1, a, p0, out);
    sub << m0, m1, m2;
    integrate_hertz(X, sub, level - 1, a, p0, out);
    return;
  }
  const double area = 0.5 * (y[1] - y[0]).cross(y[2] - y[0]).norm();
  for (int q = 0; q < 7; ++q) {
    const Vec3 x = kTriB[q][0] * y[0] + kTriB[q][1] * y[1] + kTriB[q][2] * y[2];
    const Eigen::RowVector3d parent =
        kTriB[q][0] * B.row(0) + kTriB[q][1] * B.row(1) + kTriB[q][2] * B.row(2);
    const double v = kTriW[q] * area * hertz_pressure(x, a, p0);
    for (int c = 0; c < 3; ++c) out[c] += v * parent(c);
  }
}

/// Consistent nodal forces of the Hertz pressure on the top faces: f_i = -e_z int p N_i dA, by the
/// 7-point degree-5 rule on each face, recursively split (`depth` times) where the face meets the
/// edge of contact r = a (p has an infinite slope there).
struct HertzLoad {
  std::vector<Index> nodes;
  std::vector<double> fz;
  double total = 0.0;
};
HertzLoad hertz_nodal_forces(const Mesh& mesh, const std::vector<Tri>& top, double a, double p0, int depth) {
  std::vector<double> f(mesh.points.size(), 0.0);
  for (const Tri& tri : top) {
    const std::array<Vec3, 3> X{mesh.points[tri[0]], mesh.points[tri[1]], mesh.points[tri[2]]};
    std::array<double, 3> out{0.0, 0.0, 0.0};
    integrate_hertz(X, Eigen::Matrix3d::Identity(), depth, a, p0, out);
    for (int c = 0; c < 3; ++c) f[tri[c]] += out[c];
  }
  HertzLoad load;
  for (Index i = 0; i < mesh.num_points(); ++i)
    if (f[i] != 0.0) {
      load.nodes.push_back(i);
      load.fz.push_back(-f[i]);
      load.total += f[i];
    }
  return load;
}

struct HertzResult {
  double delta_half = 0.0, delta_edge = 0.0;  ///< u_z(r) - u_z(0) at r = a/2 and r = a
  double total_force = 0.0;
  double residual = 0.0;
  Index tets = 0, nodes = 0;
  std::vector<double> r, uz;  ///< radius and u_z of the surface nodes with r <= a
};

/// Offset-free errors of the surface profile inside the contact, relative to delta(a) = c a^2:
/// the RMS over the surface nodes (r <= a, uniform grid there) of (u_h - u_exact) minus its mean, and
/// the curvature B of the least-squares fit u_z = A + B r^2 against c (u_z = -c (2a^2 - r^2)).
struct ProfileErrors {
  double rms = 0.0, curvature = 0.0;
};
ProfileErrors profile_errors(const HertzResult& h, double a, double c) {
  const std::size_t n = h.r.size();
  double mean = 0.0;
  for (std::size_t i = 0; i < n; ++i) mean += h.uz[i] + c * (2 * a * a - h.r[i] * h.r[i]);
  mean /= double(n);
  double ss = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = h.uz[i] + c * (2 * a * a - h.r[i] * h.r[i]) - mean;
    ss += d * d;
  }
  Eigen::MatrixXd A(n, 2);
  VecX b(n);
  for (std::size_t i = 0; i < n; ++i) {
    A(i, 0) = 1.0;
    A(i, 1) = h.r[i] * h.r[i];
    b[i] = h.uz[i];
  }
  const Eigen::Vector2d coef = A.colPivHouseholderQr().solve(b);
  ProfileErrors e;
  e.rms = std::sqrt(ss / double(n)) / (c * a * a);
  e.curvature = std::abs(coef[1] - c) / c;
  return e;
}

/// f_int(u) - f_ext for fixed nodal forces: the Hertz block's nonlinear system (potential W - f.u).
class DeadLoadResidual final : public tm::NonlinearSystem {
 public:
  DeadLoadResidual(const tm::ElasticModel& model, const VecX& f_ext) : model_(model), f_ext_(f_ext) {}
  void residual(const VecX& u, VecX& r) override {
    model_.internal_force(u, r);
    r -= f_ext_;
  }
  void jacobian(const VecX& u, tm::SpMat& J) override { model_.tangent(u, J); }
  bool symmetric() const override { return true; }
  double force_scale() const override { return f_ext_.norm(); }
  bool potential(const VecX& u, double& value) override {
    value = model_.energy(u) - f_ext_.dot(u);
    return true;
  }

 private:
  const tm::ElasticModel& model_;
  const VecX& f_ext_;
};

/// Static equilibrium by the fast model's Newton (tmlab::tm::newton_solve: line search, round-off
/// test) with incomplete-Cholesky preconditioned CG as the linear solver (sparse LDL^T fills in too
/// much beyond ~2e4 DOFs in 3D). Returns the relative free residual |R_free| / |f_ext| reached.
double newton_cg(const tm::ElasticModel& model, const tm::DirichletSet& bc, const VecX& f_ext, double rtol,
                 VecX& u, std::ostream& log) {
  DeadLoadResidual system(model, f_ext);
  tm::ConstrainedLinearSolver cg(tm::ConstrainedLinearSolver::Kind::ConjugateGradient, 0.1 * rtol);
  tm::NewtonOptions o;
  o.rtol = rtol;
  o.atol = 0.0;
  o.max_iterations = 20;
  const tm::NewtonResult nr = tm::newton_solve(system, bc, 0.0, u, o, cg);
  const double scale = f_ext.norm();
  for (std::size_t k = 0; k < nr.history.size(); ++k)
    log << "    Newton " << k << ": |R|/|f| = " << fmt(nr.history[k] / scale, 2) << "\n";
  if (!nr.converged)
    throw Error("hertz: Newton did not reach the relative residual " + fmt(rtol, 1) +
                " in 20 iterations (last " + fmt(nr.residual_final / scale, 2) + ")");
  return nr.residual_final / scale;
}

HertzResult hertz_solve(const Mesh& mesh, const tm::StVenantKirchhoff& mat, double a, double p0, int depth,
                        double rtol, std::ostream& log) {
  const double tol = 1e-9 * a;
  double zmin = 0.0;
  for (const Vec3& x : mesh.points) zmin = std::min(zmin, x.z());
  // Symmetry planes x = 0 (u_x = 0), y = 0 (u_y = 0); bottom clamped.
  DirichletCondition sym_x{"symmetry_x", {}, {true, false, false}, Vec3::Zero(), TimeFunction::constant()};
  DirichletCondition sym_y{"symmetry_y", {}, {false, true, false}, Vec3::Zero(), TimeFunction::constant()};
  DirichletCondition bottom{"bottom", {}, {true, true, true}, Vec3::Zero(), TimeFunction::constant()};
  for (Index i = 0; i < mesh.num_points(); ++i) {
    const Vec3& x = mesh.points[i];
    if (std::abs(x.x()) < tol) sym_x.nodes.push_back(i);
    if (std::abs(x.y()) < tol) sym_y.nodes.push_back(i);
    if (std::abs(x.z() - zmin) < tol) bottom.nodes.push_back(i);
  }
  const tm::DirichletSet bc(mesh.num_points(), {sym_x, sym_y, bottom});
  const auto top = select_faces(mesh, NodeSelector::from_json({{"group", "zmax"}}));
  const HertzLoad load = hertz_nodal_forces(mesh, top, a, p0, depth);
  VecX f_ext = VecX::Zero(3 * mesh.num_points());
  for (std::size_t i = 0; i < load.nodes.size(); ++i) f_ext[3 * load.nodes[i] + 2] = load.fz[i];
  tm::TensorMassStVK model(mesh, mat);
  VecX u = VecX::Zero(3 * mesh.num_points());
  HertzResult r;
  r.residual = newton_cg(model, bc, f_ext, rtol, u, log);
  auto uz = [&](const Vec3& p) {
    const Index i = nearest_node(mesh, p);
    if ((mesh.points[i] - p).norm() > tol)
      throw Error("hertz mesh: no node at (" + fmt(p.x()) + ", " + fmt(p.y()) + ", 0)");
    return u[3 * i + 2];
  };
  const double u0 = uz(Vec3::Zero());
  r.delta_half = uz(Vec3(0.5 * a, 0, 0)) - u0;
  r.delta_edge = uz(Vec3(a, 0, 0)) - u0;
  for (Index i = 0; i < mesh.num_points(); ++i) {
    const Vec3& x = mesh.points[i];
    const double radius = std::hypot(x.x(), x.y());
    if (std::abs(x.z()) < tol && radius <= a + tol) {
      r.r.push_back(radius);
      r.uz.push_back(u[3 * i + 2]);
    }
  }
  r.total_force = load.total;
  r.tets = mesh.num_tets();
  r.nodes = mesh.num_points();
  return r;
}

Measurements hertz_traction(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const tm::StVenantKirchhoff mat = read_material(p);
  const double a = p.positive("contact_radius");
  const double p0 = p.positive("p0_over_E") * mat.young();
  const double W = p.positive("block_over_a");
  const double t_a = p.positive("patch_fraction");
  if (t_a >= 1.0) throw p.error("patch_fraction", "must be < 1");
  // Nodes at r = a/2 and r = a on every mesh: N t_a cells across a, an even number.
  auto check_cells = [&](const std::string& key, int N) {
    const double half_cells = N * t_a / 2.0;
    if (N < 2 || std::abs(half_cells - std::round(half_cells)) > 1e-9)
      throw p.error(key, "N * patch_fraction must be an even number (nodes at r = a/2 and r = a); N = " +
                             std::to_string(N));
  };
  const auto levels = count_list(p, "cells", 2);
  for (int N : levels) check_cells("cells", N);
  const double W2 = p.positive("truncation_block_over_a");
  if (W2 <= W) throw p.error("truncation_block_over_a", "must exceed block_over_a");
  const int trunc_level = p.require<int>("truncation_cells");
  check_cells("truncation_cells", trunc_level);
  const int depth = p.require<int>("quadrature_depth");
  if (depth < 0 || depth > 12) throw p.error("quadrature_depth", "must be in 0..12");
  const double rtol = p.positive("newton_rtol", 1e-10);
  p.finish();

  const double E = mat.young(), nu = mat.poisson();
  const double c = (1.0 - nu * nu) * kPi * p0 / (4.0 * a * E);
  const double exact_half = c * 0.25 * a * a, exact_edge = c * a * a;
  const double exact_total = kPi * a * a * p0 / 6.0;  // quarter of 2/3 pi a^2 p0
  const double k = grading_rate(W, t_a);

  Measurements m;
  Series edge;
  edge.x_label = "h = a / cells across a [m]";
  edge.y_label = "|delta_h(a) - delta(a)| / delta(a)";
  double profile_finest = 0.0, curvature_finest = 0.0;
  double half_finest = 0.0;
  double force_err = 0.0, residual = 0.0;
  nlohmann::json rows = nlohmann::json::array();
  for (int N : levels) {
    const auto t0 = std::chrono::steady_clock::now();
    const Mesh mesh = hertz_mesh(a, t_a, k, N, 1.0);
    const HertzResult r = hertz_solve(mesh, mat, a, p0, depth, rtol, ctx.log);
    const double h = a / (N * t_a);
    const double e_half = std::abs(r.delta_half - exact_half) / exact_half;
    const double e_edge = std::abs(r.delta_edge - exact_edge) / exact_edge;
    const ProfileErrors pe = profile_errors(r, a, c);
    half_finest = e_half;
    edge.x.push_back(h);
    edge.y.push_back(e_edge);
    profile_finest = pe.rms;
    curvature_finest = pe.curvature;
    force_err = std::max(force_err, std::abs(r.total_force - exact_total) / exact_total);
    residual = std::max(residual, r.residual);
    rows.push_back({{"cells", N},
                    {"h", h},
                    {"tets", r.tets},
                    {"delta_half", r.delta_half},
                    {"delta_edge", r.delta_edge},
                    {"rel_error_half", e_half},
                    {"rel_error_edge", e_edge},
                    {"profile_rms_error", pe.rms},
                    {"curvature_rel_error", pe.curvature}});
    ctx.log << "  N = " << N << " (" << r.tets << " tets, h = a/" << N * t_a << "): delta(a/2) "
            << fmt(r.delta_half, 6) << " (exact " << fmt(exact_half, 6) << ", rel. error " << fmt(e_half)
            << "), delta(a) " << fmt(r.delta_edge, 6) << " (exact " << fmt(exact_edge, 6) << ", rel. error "
            << fmt(e_edge) << "), profile RMS " << fmt(pe.rms) << ", curvature " << fmt(pe.curvature) << ", "
            << fmt(seconds_since(t0), 2) << " s\n";
  }
  // Truncation: the same inner mesh in a block W2 instead of W (T extended with the same grading).
  {
    const double T2 = t_a + std::log1p((W2 - 1.0) * k * t_a) / k;  // s(T2) = W2 a
    const double T2g = std::ceil(T2 * trunc_level - 1e-9) / trunc_level;
    const auto t0 = std::chrono::steady_clock::now();
    const HertzResult r1 =
        hertz_solve(hertz_mesh(a, t_a, k, trunc_level, 1.0), mat, a, p0, depth, rtol, ctx.log);
    const HertzResult r2 =
        hertz_solve(hertz_mesh(a, t_a, k, trunc_level, T2g), mat, a, p0, depth, rtol, ctx.log);
    const double tr_half = std::abs(r2.delta_half - r1.delta_half) / exact_half;
    const double tr_edge = std::abs(r2.delta_edge - r1.delta_edge) / exact_edge;
    m.set("truncation_estimate_half", tr_half);
    m.set("truncation_estimate_edge", tr_edge);
    const double W2_actual = 1.0 + (std::expm1(k * (T2g - t_a)) / k) / t_a;
    ctx.log << "  truncation (N = " << trunc_level << ", block " << W << " a vs " << W2_actual
            << " a): " << fmt(tr_half) << " at a/2, " << fmt(tr_edge) << " at a ("
            << fmt(seconds_since(t0), 2) << " s)\n";
    m.data["truncation_block_over_a"] = W2_actual;
  }
  m.series["rel_error_edge"] = edge;
  m.set("finest_rel_error_half", half_finest);
  m.set("finest_rel_error_edge", edge.y.back());
  m.set("finest_profile_rms_error", profile_finest);
  m.set("finest_curvature_rel_error", curvature_finest);
  m.set("applied_force_rel_error", force_err);
  m.set("equilibrium_residual", residual);
  m.data["levels"] = rows;
  m.data["grading_rate_k"] = k;
  m.notes.push_back("half-space: delta(a) = (1-nu^2) pi p0 a / (4E) = " + fmt(exact_edge, 6) + " m");
  return m;
}

// ==== 5. Manufactured static solution =============================================================
//
// u*(X) = c (sin(x + 2y), cos(2x - z), sin(yz + x)) on the unit cube, St VK, body force
// b0 = -Div P(F*), P = F S(E), computed analytically from the gradient and Hessian of u*:
//   (Div P)_i = sum_JK u_i,KJ S_KJ + sum_K F_iK (Div S)_K,
//   (Div S)_K = lambda d_K tr E + 2 mu sum_J d_J E_KJ,  d_J E_KL = 1/2 sum_m (u_m,KJ F_mL + F_mK u_m,LJ),
// checked against 4th-order central differences of P. Nodal loads f_i = int b0 N_i dV and the
// errors by a collapsed (Duffy) Gauss-Legendre rule on every tet; Dirichlet u* on all boundary nodes.
struct Manufactured {
  double c = 0.03;
  void gradient_hessian(const Vec3& X, Mat3& G, std::array<Mat3, 3>& H) const {
    const double x = X.x(), y = X.y(), z = X.z();
    const double a1 = x + 2 * y, a2 = 2 * x - z, a3 = y * z + x;
    G << c * std::cos(a1), 2 * c * std::cos(a1), 0.0,  //
        -2 * c * std::sin(a2), 0.0, c * std::sin(a2),  //
        c * std::cos(a3), c * z * std::cos(a3), c * y * std::cos(a3);
    Mat3 h1, h2;
    h1 << 1, 2, 0, 2, 4, 0, 0, 0, 0;
    h2 << 4, 0, -2, 0, 0, 0, -2, 0, 1;
    H[0] = -c * std::sin(a1) * h1;
    H[1] = -c * std::cos(a2) * h2;
    const Vec3 gphi(1.0, z, y);
    Mat3 hphi;
    hphi << 0, 0, 0, 0, 0, 1, 0, 1, 0;
    H[2] = -c * std::sin(a3) * gphi * gphi.transpose() + c * std::cos(a3) * hphi;
  }
  Vec3 value(const Vec3& X) const {
    const double x = X.x(), y = X.y(), z = X.z();
    return c * Vec3(std::sin(x + 2 * y), std::cos(2 * x - z), std::sin(y * z + x));
  }
  Mat3 gradient(const Vec3& X) const {
    Mat3 G;
    std::array<Mat3, 3> H;
    gradient_hessian(X, G, H);
    return G;
  }
  static Mat3 first_pk(const tm::StVenantKirchhoff& mat, const Mat3& G) {
    const Mat3 F = Mat3::Identity() + G;
    const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
    return F * mat.pk2_stress(E);
  }
  Vec3 div_p(const tm::StVenantKirchhoff& mat, const Vec3& X) const {
    Mat3 G;
    std::array<Mat3, 3> H;  // H[i](K, J) = u_i,KJ
    gradient_hessian(X, G, H);
    const Mat3 F = Mat3::Identity() + G;
    const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
    const Mat3 S = mat.pk2_stress(E);
    std::array<Mat3, 3> dE;  // dE[J](K, L) = d_J E_KL
    for (int J = 0; J < 3; ++J) {
      Mat3 HJ;  // HJ(m, K) = u_m,KJ
      for (int mm = 0; mm < 3; ++mm)
        for (int K = 0; K < 3; ++K) HJ(mm, K) = H[mm](K, J);
      dE[J] = 0.5 * (HJ.transpose() * F + F.transpose() * HJ);
    }
    Vec3 divS;
    for (int K = 0; K < 3; ++K) {
      double v = mat.lambda * dE[K].trace();
      for (int J = 0; J < 3; ++J) v += 2.0 * mat.mu * dE[J](K, J);
      divS[K] = v;
    }
    Vec3 out;
    for (int i = 0; i < 3; ++i) out[i] = H[i].cwiseProduct(S).sum() + F.row(i).dot(divS);
    return out;
  }
  Vec3 div_p_fd(const tm::StVenantKirchhoff& mat, const Vec3& X, double h) const {
    Vec3 out = Vec3::Zero();
    for (int J = 0; J < 3; ++J) {
      auto P = [&](double s) { return first_pk(mat, gradient(X + s * h * Vec3::Unit(J))); };
      const Mat3 d = (8.0 * (P(1) - P(-1)) - (P(2) - P(-2))) / (12.0 * h);
      out += d.col(J);
    }
    return out;
  }
};

/// Collapsed Gauss-Legendre rule on the reference tet: barycentric points and weights (sum 1).
struct TetRule {
  std::vector<std::array<double, 4>> bary;
  std::vector<double> weight;
};
TetRule duffy_rule(int q) {
  Eigen::VectorXd x(q), w(q);
  // Gauss-Legendre on [0, 1] by the Golub-Welsch eigenvalue method.
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(q, q);
  for (int i = 1; i < q; ++i) J(i, i - 1) = J(i - 1, i) = i / std::sqrt(4.0 * i * i - 1.0);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(J);
  for (int i = 0; i < q; ++i) {
    x[i] = 0.5 * (es.eigenvalues()[i] + 1.0);
    w[i] = es.eigenvectors()(0, i) * es.eigenvectors()(0, i);  // sums to 1 on [0, 1]
  }
  TetRule r;
  for (int i = 0; i < q; ++i)
    for (int j = 0; j < q; ++j)
      for (int k = 0; k < q; ++k) {
        const double u = x[i], v = x[j], s = x[k];
        const double x1 = u, x2 = v * (1 - u), x3 = s * (1 - u) * (1 - v);
        r.bary.push_back({1 - x1 - x2 - x3, x1, x2, x3});
        r.weight.push_back(6.0 * w[i] * w[j] * w[k] * (1 - u) * (1 - u) * (1 - v));
      }
  return r;
}

Measurements mms_static(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const tm::StVenantKirchhoff mat = read_material(p);
  Manufactured ms;
  ms.c = p.positive("amplitude");
  const auto levels = count_list(p, "cells", 1);
  const double perturb = p.positive("perturb_fraction", 0.0, true);
  const int q = p.require<int>("quadrature_points");
  if (q < 2 || q > 10)
    throw p.error("quadrature_points", "must be in 2..10 (per direction of the collapsed rule)");
  const int steps = p.require<int>("load_steps");
  if (steps < 1) throw p.error("load_steps", "must be >= 1");
  const tm::NewtonOptions newton = newton_options(p);
  p.finish();
  const TetRule rule = duffy_rule(q);

  Measurements m;
  // Body force against finite differences of P at a few points.
  double fd = 0.0;
  for (const Vec3& X :
       {Vec3(0.1, 0.2, 0.3), Vec3(0.5, 0.5, 0.5), Vec3(0.9, 0.7, 0.2), Vec3(0.3, 0.95, 0.8)}) {
    const Vec3 a = ms.div_p(mat, X), b = ms.div_p_fd(mat, X, 1e-3);
    fd = std::max(fd, (a - b).norm() / a.norm());
  }
  m.set("body_force_fd_rel_error", fd);
  // Peak strain of u* (max |E| entry over a sample grid).
  double strain = 0.0;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j)
      for (int k = 0; k <= 10; ++k) {
        const Mat3 F = Mat3::Identity() + ms.gradient(Vec3(i, j, k) / 10.0);
        strain = std::max(strain, (0.5 * (F.transpose() * F - Mat3::Identity())).cwiseAbs().maxCoeff());
      }
  m.set("max_green_strain", strain);

  Series l2, h1;
  l2.x_label = h1.x_label = "h = 1/n";
  l2.y_label = "||u_h - u*||_L2 / ||u*||_L2";
  h1.y_label = "|u_h - u*|_H1 / |u*|_H1";
  double l2i_fin = 0.0, h1i_fin = 0.0, residual = 0.0;
  nlohmann::json rows = nlohmann::json::array();
  for (int n : levels) {
    const auto t0 = std::chrono::steady_clock::now();
    const Mesh mesh =
        perturb_interior(make_box_mesh(Vec3::Zero(), Vec3::Ones(), n, n, n), perturb, 17u + unsigned(n));
    const auto rest = tm::compute_tet_rest(mesh);
    // Consistent body loads.
    VecX fb = VecX::Zero(3 * mesh.num_points());
    for (Index t = 0; t < mesh.num_tets(); ++t) {
      const Tet& tet = mesh.tets[t];
      for (std::size_t g = 0; g < rule.weight.size(); ++g) {
        Vec3 X = Vec3::Zero();
        for (int c = 0; c < 4; ++c) X += rule.bary[g][c] * mesh.points[tet[c]];
        const Vec3 b0 = -ms.div_p(mat, X);
        for (int c = 0; c < 4; ++c)
          fb.segment<3>(3 * tet[c]) += (rule.weight[g] * rest[t].volume * rule.bary[g][c]) * b0;
      }
    }
    std::vector<tm::NodalForce> forces;
    std::vector<char> on_boundary(mesh.points.size(), 0);
    std::vector<tm::DirichletCondition> bcs;
    for (Index i : boundary_nodes(mesh)) {
      on_boundary[i] = 1;
      bcs.push_back(condition("b" + std::to_string(i), {i}, {true, true, true}, ms.value(mesh.points[i]),
                              TimeFunction::ramp(0.0, 1.0)));
    }
    for (Index i = 0; i < mesh.num_points(); ++i) {
      if (on_boundary[i]) continue;  // constrained: its load only enters the reaction
      tm::NodalForce f;
      f.name = "body";
      f.nodes = {i};
      f.force = fb.segment<3>(3 * i);
      f.function = TimeFunction::ramp(0.0, 1.0);
      forces.push_back(std::move(f));
    }
    tm::TensorMassStVK model(mesh, mat);
    StaticRun run(mesh, model, bcs, forces, {}, newton);
    for (int s = 0; s < steps; ++s) run.advance(double(s) / steps, double(s + 1) / steps);
    residual = std::max(residual, run.relative_residual(1.0));
    // Errors of u_h and of the nodal interpolant of u*.
    double e2 = 0, eh = 0, i2 = 0, ih = 0, n2 = 0, nh = 0;
    for (Index t = 0; t < mesh.num_tets(); ++t) {
      const Tet& tet = mesh.tets[t];
      Mat3 Gh = Mat3::Zero(), Gi = Mat3::Zero();
      for (int c = 0; c < 4; ++c) {
        Gh += run.u.segment<3>(3 * tet[c]) * rest[t].grad[c].transpose();
        Gi += ms.value(mesh.points[tet[c]]) * rest[t].grad[c].transpose();
      }
      for (std::size_t g = 0; g < rule.weight.size(); ++g) {
        Vec3 X = Vec3::Zero(), uh = Vec3::Zero(), ui = Vec3::Zero();
        for (int c = 0; c < 4; ++c) {
          X += rule.bary[g][c] * mesh.points[tet[c]];
          uh += rule.bary[g][c] * run.u.segment<3>(3 * tet[c]);
          ui += rule.bary[g][c] * ms.value(mesh.points[tet[c]]);
        }
        const double wv = rule.weight[g] * rest[t].volume;
        const Vec3 ue = ms.value(X);
        const Mat3 Ge = ms.gradient(X);
        e2 += wv * (uh - ue).squaredNorm();
        i2 += wv * (ui - ue).squaredNorm();
        n2 += wv * ue.squaredNorm();
        eh += wv * (Gh - Ge).squaredNorm();
        ih += wv * (Gi - Ge).squaredNorm();
        nh += wv * Ge.squaredNorm();
      }
    }
    const double el2 = std::sqrt(e2 / n2), eh1 = std::sqrt(eh / nh);
    l2i_fin = std::sqrt(i2 / n2);
    h1i_fin = std::sqrt(ih / nh);
    l2.x.push_back(1.0 / n);
    l2.y.push_back(el2);
    h1.x.push_back(1.0 / n);
    h1.y.push_back(eh1);
    rows.push_back({{"n", n},
                    {"tets", mesh.num_tets()},
                    {"l2_error", el2},
                    {"h1_error", eh1},
                    {"l2_interpolation_error", l2i_fin},
                    {"h1_interpolation_error", h1i_fin}});
    ctx.log << "  n = " << n << " (" << mesh.num_tets() << " tets): L2 " << fmt(el2) << " (interpolant "
            << fmt(l2i_fin) << "), H1 " << fmt(eh1) << " (interpolant " << fmt(h1i_fin) << "), "
            << fmt(seconds_since(t0), 2) << " s\n";
  }
  m.series["l2_error"] = l2;
  m.series["h1_error"] = h1;
  m.set("finest_l2_error", l2.y.back());
  m.set("finest_h1_error", h1.y.back());
  m.set("finest_l2_interpolation_error", l2i_fin);
  m.set("finest_h1_interpolation_error", h1i_fin);
  m.set("h1_error_over_interpolation_error", h1.y.back() / h1i_fin);
  m.set("equilibrium_residual", residual);
  m.data["levels"] = rows;
  return m;
}

}  // namespace

void register_analytic_checks(CheckRegistry& registry) {
  registry.add("analytic.uniaxial_stvk", uniaxial_stvk);
#ifdef TMLAB_HAVE_REFERENCE
  registry.add("analytic.simple_shear_neohookean", simple_shear_neohookean);
#endif
  registry.add("analytic.prony_relaxation", prony_relaxation);
  registry.add("analytic.prony_creep", prony_creep);
  registry.add("analytic.hertz_traction", hertz_traction);
  registry.add("analytic.mms_static", mms_static);
}

}  // namespace tmlab::verify
