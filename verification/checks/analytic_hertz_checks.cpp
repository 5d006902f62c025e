// Analytic check of a surface load (label `analytic`): the Hertz pressure on a thick graded block,
// the tensor-mass model against the elastic half-space.
//
//   analytic.hertz_traction          Hertz pressure on a thick graded block vs the elastic half-space
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
#include "tensormass/kernels/tensor_mass.hpp"
#include "verification/numerics/graded_map.hpp"
#include "verification/numerics/profile_fit.hpp"
#include "verification/numerics/quadrature.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

namespace tmlab::verify {

namespace {

using namespace analytic;
using numerics::grading_rate;
using numerics::kTriB;
using numerics::kTriW;
using numerics::profile_errors;
using numerics::ProfileErrors;

constexpr double kPi = 3.14159265358979323846;

// ==== Hertz pressure on a thick block =========================================================
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
// k from s(1) = W; numerics::graded). Refining N halves every cell; the planes x = 0, y = 0, z = 0 and the
// outer faces stay planar. A larger block (the truncation estimate) extends T beyond 1 with the same s, so
// the inner mesh is identical.
Mesh hertz_mesh(double a, double t_a, double k, int N, double T) {
  const int cells = static_cast<int>(std::lround(N * T));
  Mesh mesh = make_box_mesh(Vec3(0, 0, -double(cells) / N), Vec3(double(cells) / N, double(cells) / N, 0),
                            cells, cells, cells);
  auto s = [&](double t) { return numerics::graded(t, a, t_a, k); };
  for (Vec3& x : mesh.points) {
    const double t = x.cwiseAbs().maxCoeff();
    if (t > 0.0) x *= s(t) / t;
  }
  return mesh;
}

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
    const ProfileErrors pe = profile_errors(r.r, r.uz, a, c);
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

}  // namespace

void register_analytic_hertz_checks(CheckRegistry& registry) {
  registry.add("analytic.hertz_traction", hertz_traction);
}

}  // namespace tmlab::verify
