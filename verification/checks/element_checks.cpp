// Element checks: the fast model's element kinds (mesh.element, docs/elements.md) on the problems
// that tell them apart.
//
//   element.patch_test      an affine displacement on the boundary of an irregular mesh is reproduced
//                           exactly in the interior by p1_anp, p2 and p2_mean_dilatation (static Newton
//                           solve on the element's own nodes: the quadratic mesh's for p2)
//   element.cook_membrane   Cook's membrane (the CoFEA benchmark geometry, material and load, plane
//                           strain, small-load regime) run by the case runner with each element on a
//                           sequence of meshes; the tip deflection of each against the converged value
//                           (Richardson on the finest three levels of one element) and against the
//                           published converged value
//
// Measurements only: the tolerances and their rationale are in the cases' verify.json.
#include "verification/checks/builtin_checks.hpp"
#include "verification/checks/check_support.hpp"

#include "convergence/grid_convergence.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/stopwatch.hpp"
#include "core/config/case_config.hpp"
#include "core/config/element_kind.hpp"
#include "core/mesh/cook_membrane.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/quadratic_mesh.hpp"
#include "runner/case_runner.hpp"
#include "tensormass/kernels/averaged_pressure_tet.hpp"
#include "tensormass/kernels/hyperelastic_p2.hpp"
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/materials/law.hpp"

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace tmlab::verify {

namespace {

namespace fs = std::filesystem;
using tm::VecX;

std::string fmt(double v, int digits = 3) { return scientific(v, digits); }

ElementKind element_from(ConfigReader& p, const std::string& key, const std::string& name) {
  const auto e = element_kind_from_string(name);
  if (!e) throw p.error(key, "unknown element '" + name + "' (p1 | p1_anp | p2 | p2_mean_dilatation)");
  return *e;
}

// ------------------------------------------------------------------ element.patch_test
/// Static Newton on the free DOFs (the rest prescribed to `ua`'s values, ramped in `steps` steps):
/// u_f <- u_f - K_ff^-1 r_f until |r_f| <= rtol |f_int(ua)| (max norm). Returns the iterations.
int newton_prescribed(const tm::ElasticModel& model, const std::vector<bool>& fixed, const VecX& ua,
                      int steps, double rtol, VecX& u) {
  const Eigen::Index n = ua.size();
  std::vector<Eigen::Index> free;
  for (Eigen::Index i = 0; i < n; ++i)
    if (!fixed[static_cast<std::size_t>(i)]) free.push_back(i);
  VecX f;
  model.internal_force(ua, f);
  const double scale = f.lpNorm<Eigen::Infinity>();
  int iterations = 0;
  u = VecX::Zero(n);
  for (int s = 1; s <= steps; ++s) {
    const double lam = double(s) / steps;
    for (Eigen::Index i = 0; i < n; ++i)
      if (fixed[static_cast<std::size_t>(i)]) u[i] = lam * ua[i];
    for (int it = 0; it < 30; ++it) {
      model.internal_force(u, f);
      VecX rf(static_cast<Eigen::Index>(free.size()));
      for (std::size_t k = 0; k < free.size(); ++k) rf[static_cast<Eigen::Index>(k)] = f[free[k]];
      if (rf.lpNorm<Eigen::Infinity>() <= rtol * scale) break;
      tm::SpMat K;
      model.tangent(u, K);
      // K_ff by a selection matrix (free DOFs only).
      std::vector<Eigen::Index> map(static_cast<std::size_t>(n), -1);
      for (std::size_t k = 0; k < free.size(); ++k) map[static_cast<std::size_t>(free[k])] = Eigen::Index(k);
      std::vector<Eigen::Triplet<double>> trip;
      for (int c = 0; c < K.outerSize(); ++c)
        for (tm::SpMat::InnerIterator e(K, c); e; ++e) {
          const Eigen::Index r = map[static_cast<std::size_t>(e.row())],
                             cc = map[static_cast<std::size_t>(e.col())];
          if (r >= 0 && cc >= 0) trip.emplace_back(r, cc, e.value());
        }
      tm::SpMat Kff(static_cast<Eigen::Index>(free.size()), static_cast<Eigen::Index>(free.size()));
      Kff.setFromTriplets(trip.begin(), trip.end());
      Eigen::SimplicialLDLT<tm::SpMat> ldlt(Kff);
      if (ldlt.info() != Eigen::Success) throw Error("element.patch_test: the free-DOF tangent is singular");
      const VecX du = ldlt.solve(rf);
      for (std::size_t k = 0; k < free.size(); ++k) u[free[k]] -= du[static_cast<Eigen::Index>(k)];
      ++iterations;
    }
  }
  return iterations;
}

Measurements element_patch_test(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const Mesh mesh = mesh_from_parameters(ctx, p.child("mesh"));
  const double E = p.positive("young");
  const double nu = p.require<double>("poisson");
  if (!(nu > -1.0 && nu < 0.5)) throw p.error("poisson", "must be in (-1, 0.5)");
  const auto g = p.require<std::vector<double>>("gradient");
  if (g.size() != 9) throw p.error("gradient", "needs 9 values (F - I, row-major)");
  const auto names = p.require<std::vector<std::string>>("elements");
  if (names.empty()) throw p.error("elements", "must name at least one element");
  std::vector<ElementKind> elements;
  for (const auto& n : names) elements.push_back(element_from(p, "elements", n));
  const int steps = p.get<int>("load_steps", 4);
  p.finish();
  Eigen::Matrix3d H;
  for (int i = 0; i < 9; ++i) H(i / 3, i % 3) = g[static_cast<std::size_t>(i)];
  if ((Eigen::Matrix3d::Identity() + H).determinant() <= 0.0)
    throw Error(ctx.vcase.spec_file().string() + ": key 'parameters.gradient': det(I + H) must be > 0");
  const tm::Law law(tm::StVenantKirchhoff::from_young_poisson(E, nu));
  const QuadraticMesh qm = make_quadratic(mesh);
  const std::vector<Tri> bfaces = boundary_faces(mesh);

  Measurements m;
  double worst_error = 0.0, worst_residual = 0.0;
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const ElementKind e = elements[k];
    const bool quad = is_quadratic(e);
    const std::vector<Vec3>& pts = quad ? qm.points : mesh.points;
    std::unique_ptr<tm::ElasticModel> model;
    if (e == ElementKind::P1) model = std::make_unique<tm::HyperelasticTL>(mesh, law);
    if (e == ElementKind::P1Anp) model = std::make_unique<tm::AveragedPressureTet>(mesh, law);
    if (quad) {
      tm::P2Options o;
      if (e == ElementKind::P2MeanDilatation) o.volumetric = tm::P2Options::Volumetric::MeanDilatation;
      model = std::make_unique<tm::HyperelasticP2>(qm, law, o);
    }
    const Index n = Index(pts.size());
    const std::vector<Index> bnodes = quad ? qm.face_nodes(bfaces) : boundary_nodes(mesh);
    std::vector<bool> fixed(3 * std::size_t(n), false);
    for (Index b : bnodes)
      for (int c = 0; c < 3; ++c) fixed[3 * std::size_t(b) + std::size_t(c)] = true;
    VecX ua(3 * n);
    for (Index i = 0; i < n; ++i) ua.segment<3>(3 * i) = H * pts[std::size_t(i)];
    VecX u;
    const int iterations = newton_prescribed(*model, fixed, ua, steps, 1e-12, u);
    const double err = rel_max_diff(u, ua);
    // The interior residual of the exact affine field itself (no solve), relative to the largest
    // nodal force of that field.
    VecX f;
    model->internal_force(ua, f);
    const double fmax = f.lpNorm<Eigen::Infinity>();
    for (Index b : bnodes) f.segment<3>(3 * b).setZero();
    const double res = f.lpNorm<Eigen::Infinity>() / fmax;
    const std::string tag = names[k];
    m.set(tag + "_interior_rel_error", err);
    m.set(tag + "_affine_residual_rel", res);
    m.set(tag + "_newton_iterations", iterations);
    m.set(tag + "_interior_nodes", double(n - Index(bnodes.size())));
    worst_error = std::max(worst_error, err);
    worst_residual = std::max(worst_residual, res);
    ctx.log << "  " << tag << ": " << n << " nodes (" << n - Index(bnodes.size())
            << " interior), interior error " << fmt(err) << ", affine residual " << fmt(res) << ", "
            << iterations << " Newton iterations\n";
  }
  m.set("interior_rel_error", worst_error);
  m.set("affine_residual_rel", worst_residual);
  m.notes.push_back(std::to_string(mesh.num_tets()) + " tets; worst over the elements");
  return m;
}

// ------------------------------------------------------------------ element.cook_membrane
struct CookLevel {
  int cells = 0;
  Index tets = 0, nodes = 0;
  double h = 0.0;           ///< in-plane spacing L / cells, m
  double deflection = 0.0;  ///< tip u_y scaled to the full load, mm
  double seconds = 0.0;
};

/// The load case of cook_membrane's runs (its parameters as read).
struct CookLoad {
  double E = 0.0, nu = 0.0;
  double traction = 0.0;  ///< the benchmark's shear traction
  double scale = 1.0;     ///< the fraction of it applied (the small-load regime)
  int layers = 1;
  std::vector<std::string> fix_z;  ///< faces with u_z = 0
};

/// One level of Cook's membrane: the mesh of `c` cells, the case with element `name` run through the
/// case runner, the tip deflection scaled back to the full load (mm).
CookLevel run_cook_level(const CheckContext& ctx, const CookLoad& load, ElementKind kind,
                         const std::string& name, int c) {
  const double E = load.E, nu = load.nu, traction = load.traction, scale = load.scale;
  const int layers = load.layers;
  const auto& fix_z = load.fix_z;
  CookMembraneSpec spec;
  spec.layers = layers;
  spec.cells = c;
  const Vec3 tip(spec.length, spec.left + spec.right, 0.0);
  const double force_scale = 1000.0 / scale;  // m at the scaled load -> mm at the full load
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path mesh_file =
      ctx.work_dir / ("cook_" + std::to_string(c) + "x" + std::to_string(layers) + ".msh");
  const Mesh mesh = make_cook_membrane_mesh(spec);
  if (!fs::exists(mesh_file)) write_gmsh22(mesh, mesh_file.string());
  nlohmann::json boundary = nlohmann::json::array();
  boundary.push_back({{"name", "clamped"}, {"nodes", {{"group", "clamped"}}}});
  for (const auto& f : fix_z)
    boundary.push_back({{"name", "plane_" + f}, {"nodes", {{"group", f}}}, {"components", "z"}});
  const nlohmann::json doc = {
      {"name", "cook-" + name + "-" + std::to_string(c)},
      {"model", "hyperelastic_tl"},
      {"mesh", {{"file", mesh_file.string()}, {"element", name}}},
      {"material", {{"law", "stvk"}, {"E", E}, {"nu", nu}, {"density", 1000.0}}},
      {"boundary", boundary},
      {"loads",
       {{{"type", "traction"},
         {"name", "shear"},
         {"faces", {{"group", "loaded"}}},
         {"traction", {0.0, scale * traction, 0.0}}}}},
      {"solver", {{"type", "static"}, {"steps", 1}, {"linear", "cholmod"}, {"newton", {{"rtol", 1e-10}}}}},
      {"output",
       {{"vtu", false},
        {"xdmf", false},
        {"plots", false},
        {"probes", {{{"name", "tip"}, {"point", {tip.x(), tip.y(), tip.z()}}}}}}}};
  CaseConfig cfg = parse_case(doc, (ctx.work_dir / "cook.json").string(), {ctx.work_dir.string()});
  if (cfg.mesh.element != kind) throw Error("element.cook_membrane: element not applied");
  tmlab::RunOptions o;
  o.results_root = (ctx.work_dir / "runs").string();
  o.tmlab_root = ctx.source_root.string();
  o.plots = false;
  const tmlab::RunResult r = tm::run_case(cfg, o);
  const auto& d = r.summary.at("probes").at("tip").at("displacement_m");
  CookLevel L;
  L.cells = c;
  L.tets = mesh.num_tets();
  L.nodes = static_cast<Index>(r.summary.at("mesh").value("nodes", static_cast<long>(mesh.num_points())));
  L.h = spec.length / c;
  L.deflection = d.at(1).get<double>() * force_scale;
  L.seconds = seconds_since(t0);
  ctx.log << "  " << name << ", " << c << " cells (" << L.tets << " tets, " << L.nodes
          << " nodes): tip deflection " << fmt(L.deflection, 6) << " mm (" << fmt(L.seconds, 2) << " s)\n";
  return L;
}

Measurements cook_membrane(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const double E = p.positive("young");
  const double nu = p.require<double>("poisson");
  if (!(nu > 0.0 && nu < 0.5)) throw p.error("poisson", "must be in (0, 0.5)");
  const double traction = p.positive("traction");
  const double scale = p.positive("load_scale");
  if (scale > 1.0) throw p.error("load_scale", "must be <= 1 (the small-load regime)");
  const int layers = p.get<int>("layers", 1);
  if (layers < 1) throw p.error("layers", "must be >= 1");
  const auto fix_z = p.require<std::vector<std::string>>("fix_z_faces");
  for (const auto& f : fix_z)
    if (f != "back" && f != "front") throw p.error("fix_z_faces", "entries must be 'back' or 'front'");
  const auto names = p.require<std::vector<std::string>>("elements");
  if (names.empty()) throw p.error("elements", "must name at least one element");
  std::vector<ElementKind> kinds;
  std::vector<std::vector<int>> cells;
  for (const auto& n : names) {
    kinds.push_back(element_from(p, "elements", n));
    const std::string key = n + "_cells";
    auto c = p.require<std::vector<int>>(key);
    if (c.empty()) throw p.error(key, "must not be empty");
    for (std::size_t i = 0; i < c.size(); ++i)
      if (c[i] < 1 || (i > 0 && c[i] <= c[i - 1])) throw p.error(key, "must be >= 1 and increase");
    cells.push_back(c);
  }
  const std::string converged_from = p.require<std::string>("converged_from");
  const auto conv_it = std::find(names.begin(), names.end(), converged_from);
  if (conv_it == names.end()) throw p.error("converged_from", "must be one of 'elements'");
  const auto& conv_cells = cells[std::size_t(conv_it - names.begin())];
  if (conv_cells.size() < 3) throw p.error("converged_from", "that element needs at least three levels");
  for (std::size_t i = conv_cells.size() - 2; i < conv_cells.size(); ++i)
    if (conv_cells[i] != 2 * conv_cells[i - 1])
      throw p.error(converged_from + "_cells", "the finest three levels must double the cells (ratio 2)");
  const int fine = p.require<int>("fine_cells");
  for (std::size_t k = 0; k < names.size(); ++k)
    if (std::find(cells[k].begin(), cells[k].end(), fine) == cells[k].end())
      throw p.error("fine_cells", "must be one of the levels of every element ('" + names[k] + "_cells')");
  const auto published = p.require<std::vector<double>>("published");
  if (published.size() != 2 || !(published[0] > 0.0 && published[1] >= published[0]))
    throw p.error("published", "needs [low, high], 0 < low <= high (mm)");
  p.finish();

  const CookLoad load{E, nu, traction, scale, layers, fix_z};

  std::vector<std::vector<CookLevel>> runs(names.size());
  for (std::size_t k = 0; k < names.size(); ++k)
    for (int c : cells[k]) runs[k].push_back(run_cook_level(ctx, load, kinds[k], names[k], c));

  // The converged value: Richardson on the finest three levels of `converged_from` (ratio 2).
  const auto& cr = runs[std::size_t(conv_it - names.begin())];
  const std::size_t nc = cr.size();
  const double f1 = cr[nc - 3].deflection, f2 = cr[nc - 2].deflection, f3 = cr[nc - 1].deflection;
  const double order = convergence::observed_order(f1, f2, f3, 2.0);
  if (!(order > 0.0))
    throw Error("element.cook_membrane: the finest three " + converged_from +
                " levels do not converge monotonically (observed order " + fmt(order) +
                "): no converged value");
  const double u_inf = convergence::richardson(f2, f3, 2.0, order);
  Measurements m;
  m.set("converged_deflection_mm", u_inf);
  m.set("converged_observed_order", order);
  if (nc >= 4)
    m.set("converged_observed_order_coarser",
          convergence::observed_order(cr[nc - 4].deflection, f1, f2, 2.0));
  m.set("converged_richardson_correction", std::abs(u_inf - f3) / std::abs(u_inf));
  const double lo = published[0], hi = published[1];
  const double outside = u_inf < lo ? (lo - u_inf) / lo : (u_inf > hi ? (u_inf - hi) / hi : 0.0);
  m.set("converged_outside_published", outside);

  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t k = 0; k < names.size(); ++k) {
    Series s;
    s.x_label = "h = L / cells [m]";
    s.y_label = "|u_tip - u_converged| / u_converged";
    for (const CookLevel& L : runs[k]) {
      const double err = std::abs(L.deflection - u_inf) / u_inf;
      s.x.push_back(L.h);
      s.y.push_back(err);
      rows.push_back({{"element", names[k]},
                      {"cells", L.cells},
                      {"tets", L.tets},
                      {"nodes", L.nodes},
                      {"tip_deflection_mm", L.deflection},
                      {"rel_error_vs_converged", err},
                      {"signed_rel_error_vs_published_mid", L.deflection / (0.5 * (lo + hi)) - 1.0},
                      {"seconds", L.seconds}});
      if (L.cells == fine) {
        m.set(names[k] + "_fine_deflection_mm", L.deflection);
        m.set(names[k] + "_fine_error", err);
        m.set(names[k] + "_fine_shortfall", (u_inf - L.deflection) / u_inf);
      }
    }
    m.set(names[k] + "_finest_error", s.y.back());
    m.series[names[k] + "_error"] = s;
  }
  m.data["levels"] = rows;
  m.notes.push_back("converged tip deflection " + fmt(u_inf, 6) + " mm (Richardson, " + converged_from +
                    " on " + std::to_string(conv_cells[nc - 3]) + ", " + std::to_string(conv_cells[nc - 2]) +
                    ", " + std::to_string(conv_cells[nc - 1]) + " cells, observed order " + fmt(order) +
                    "); published " + fmt(lo, 4) + " - " + fmt(hi, 4) + " mm");
  m.notes.push_back("E = " + fmt(E, 3) + ", nu = " + fmt(nu, 5) + ", traction " + fmt(traction, 3) + " x " +
                    fmt(scale, 1) + " (deflections scaled back to the full load), " + std::to_string(layers) +
                    " layer(s), u_z = 0 on " + std::to_string(fix_z.size()) + " face(s)");
  return m;
}

}  // namespace

void register_element_checks(CheckRegistry& registry) {
  registry.add({{"element.patch_test", element_patch_test}, {"element.cook_membrane", cook_membrane}});
}

}  // namespace tmlab::verify
