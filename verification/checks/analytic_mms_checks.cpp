// Analytic check by a manufactured solution (label `analytic`): a smooth static displacement field
// with its body force computed analytically, the tensor-mass model's L2 and H1 errors under mesh
// refinement beside those of the nodal interpolant.
//
//   analytic.mms_static              manufactured static solution, L2 and H1 mesh convergence
//
// Every function measures and returns Measurements; the tolerances and their reasons live in the
// cases' verify.json (verification/cases/analytic-*/).
#include "verification/checks/analytic_support.hpp"
#include "verification/checks/builtin_checks.hpp"
#include "verification/checks/check_support.hpp"

#include "core/base/stopwatch.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tet_geometry.hpp"
#include "verification/numerics/quadrature.hpp"

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
using numerics::duffy_rule;
using numerics::TetRule;

// ==== Manufactured static solution =============================================================
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

void register_analytic_mms_checks(CheckRegistry& registry) {
  registry.add("analytic.mms_static", mms_static);
}

}  // namespace tmlab::verify
