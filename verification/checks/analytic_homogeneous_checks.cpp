// Analytic checks of homogeneous deformations (label `analytic`): the tensor-mass model and the
// deal.II neo-Hookean reference against the closed-form stresses of a homogeneous state.
//
//   analytic.uniaxial_stvk           homogeneous uniaxial stretch, St VK nominal stress and lateral stretch
//   analytic.simple_shear_neohookean homogeneous simple shear of the deal.II neo-Hookean reference
//
// Every function measures and returns Measurements; the tolerances and their reasons live in the
// cases' verify.json (verification/cases/analytic-*/).
#include "verification/checks/analytic_support.hpp"
#include "verification/checks/builtin_checks.hpp"
#include "verification/checks/check_support.hpp"

#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/kernels/tensor_mass.hpp"

#ifdef TMLAB_HAVE_REFERENCE
#include "core/config/case_config.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/results/series_names.hpp"
#include "reference_fem/dealii/reference_runner.hpp"
#include "runner/case_runner.hpp"
#endif

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

namespace tmlab::verify {

namespace {

using namespace analytic;

// ==== uniaxial St VK ==========================================================================
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

// ==== neo-Hookean simple shear (deal.II reference) ===========================================
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

}  // namespace

void register_analytic_homogeneous_checks(CheckRegistry& registry) {
  registry.add("analytic.uniaxial_stvk", uniaxial_stvk);
#ifdef TMLAB_HAVE_REFERENCE
  registry.add("analytic.simple_shear_neohookean", simple_shear_neohookean);
#endif
}

}  // namespace tmlab::verify
