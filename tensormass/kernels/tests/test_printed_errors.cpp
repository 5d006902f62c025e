// One test per printed error of the seed paper's tensor-mass equations (docs/theory/seed-errata.md,
// eqs. 3, 5, 6): each shows that the PRINTED form disagrees with the total-Lagrangian oracle (or with the
// definition of E and nu) and that the corrected form agrees. The printed forms live here, as
// test-local code, never in the library.
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/testing/test_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace tmlab::tm {
namespace {

using testing::rel_err;

// ---------------------------------------------------------------------------------------------
// A single-tet tensor-mass energy with arbitrary B, C, D over all four nodes (errata eq. 2):
// W = sum_jk U_j^T B_jk U_k + sum_jkl (U_j . C_jkl)(U_k . U_l) + sum_jklm D_jklm (U_j . U_k)(U_l . U_m)
struct FullTensors {
  Mat3 B[4][4];
  Vec3 C[4][4][4];
  double D[4][4][4][4];
};

struct Terms {
  double quadratic = 0, cubic = 0, quartic = 0;
  double total() const { return quadratic + cubic + quartic; }
};

Terms energy_terms(const FullTensors& T, const std::array<Vec3, 4>& U) {
  Terms w;
  for (int j = 0; j < 4; ++j)
    for (int k = 0; k < 4; ++k) {
      w.quadratic += U[j].dot(T.B[j][k] * U[k]);
      for (int l = 0; l < 4; ++l) {
        w.cubic += U[j].dot(T.C[j][k][l]) * U[k].dot(U[l]);
        for (int m = 0; m < 4; ++m) w.quartic += T.D[j][k][l][m] * U[j].dot(U[k]) * U[l].dot(U[m]);
      }
    }
  return w;
}

enum class DForm { kCorrectProduct, kPrintedSum };

/// Tensors from vectors g_j with overall factors (fB, fC, fD): with g = a and f = (V, V, V) these
/// are the corrected tensors of errata eq. 3; with g = alpha (eq. 6) and f = (1, 1, 1) the printed.
FullTensors make_tensors(const std::array<Vec3, 4>& g, double lam, double mu, double fB, double fC, double fD,
                         DForm dform) {
  FullTensors T;
  double d[4][4];
  for (int j = 0; j < 4; ++j)
    for (int k = 0; k < 4; ++k) d[j][k] = g[j].dot(g[k]);
  for (int j = 0; j < 4; ++j)
    for (int k = 0; k < 4; ++k) {
      T.B[j][k] = fB * (lam / 2 * g[j] * g[k].transpose() +
                        mu / 2 * (g[k] * g[j].transpose() + d[j][k] * Mat3::Identity()));
      for (int l = 0; l < 4; ++l) {
        T.C[j][k][l] = fC * (lam / 2 * g[j] * d[k][l] + mu / 2 * (g[l] * d[j][k] + g[k] * d[j][l]));
        for (int m = 0; m < 4; ++m) {
          const double shear = dform == DForm::kCorrectProduct ? d[j][m] * d[k][l]   // corrected
                                                               : d[j][m] + d[k][l];  // printed
          T.D[j][k][l][m] = fD * (lam / 8 * d[j][k] * d[l][m] + mu / 4 * shear);
        }
      }
    }
  return T;
}

/// alpha_k of seed eq. 6, as printed (cross products of edge vectors).
std::array<Vec3, 4> printed_alpha(const std::array<Vec3, 4>& P) {
  return {(P[2] - P[1]).cross(P[3] - P[1]), (P[2] - P[3]).cross(P[0] - P[2]),
          (P[0] - P[3]).cross(P[1] - P[3]), (P[0] - P[1]).cross(P[2] - P[0])};
}

struct OneTet {
  std::array<Vec3, 4> P;
  Mesh mesh;
  VecX u;
  std::array<Vec3, 4> U;
};

OneTet one_tet(std::mt19937& rng, double size, double strain, double scale = 1.0) {
  OneTet t;
  t.P = testing::random_tet_points(rng, size, Vec3::Zero());
  t.u = testing::random_displacement(4, strain * size, rng);
  for (auto& p : t.P) p *= scale;
  t.u *= scale;
  t.mesh.points.assign(t.P.begin(), t.P.end());
  t.mesh.tets = {{0, 1, 2, 3}};
  for (int j = 0; j < 4; ++j) t.U[j] = t.u.segment<3>(3 * j);
  return t;
}

// ---------------------------------------------------------------------------------------------
// eq. 5: printed mu = E nu / (2(1+nu)). The oracle with the corrected mu = E/(2(1+nu)) reproduces
// the definition of E and nu (uniaxial stress: sigma_xx = E eps, no lateral stress at lateral strain
// -nu eps) and the shear modulus G = E/(2(1+nu)); the printed mu does not.
TEST(PrintedErrors, Eq5ShearModulus) {
  const double E = 3000.0, nu = 0.45, eps = 1e-7;
  const auto correct = StVenantKirchhoff::from_young_poisson(E, nu);
  const StVenantKirchhoff printed{correct.lambda, E * nu / (2.0 * (1.0 + nu))};
  std::mt19937 rng(41);
  OneTet t = one_tet(rng, 0.01, 0.0);
  // First Piola stress recovered from the oracle's nodal forces: sum_p f_p (x) P_p = V P.
  auto stress = [&](const StVenantKirchhoff& mat, const Mat3& G) {
    const TotalLagrangianStVK tl(t.mesh, mat);
    const VecX u = testing::affine_displacement(t.mesh, G, Vec3::Zero());
    const Mat34 f = tl.tet_force(0, u);
    Mat3 VP = Mat3::Zero();
    for (int p = 0; p < 4; ++p) VP += f.col(p) * t.P[p].transpose();
    return Mat3(VP / tl.rest(0).volume);
  };
  const Mat3 uniaxial = Vec3(eps, -nu * eps, -nu * eps).asDiagonal();
  Mat3 shear = Mat3::Zero();
  shear(0, 1) = eps;
  const double G = E / (2.0 * (1.0 + nu));
  const Mat3 Pc = stress(correct, uniaxial), Pp = stress(printed, uniaxial);
  const Mat3 Sc = stress(correct, shear), Sp = stress(printed, shear);
  std::printf(
      "uniaxial: sigma_xx/(E eps) corrected %.6f printed %.6f; sigma_yy/(E eps) corrected %.1e "
      "printed %.3f\nshear: sigma_xy/(G gamma) corrected %.6f printed %.6f\n",
      Pc(0, 0) / (E * eps), Pp(0, 0) / (E * eps), Pc(1, 1) / (E * eps), Pp(1, 1) / (E * eps),
      Sc(0, 1) / (G * eps), Sp(0, 1) / (G * eps));
  EXPECT_NEAR(Pc(0, 0) / (E * eps), 1.0, 1e-5);
  EXPECT_NEAR(Pc(1, 1) / (E * eps), 0.0, 1e-5);
  EXPECT_NEAR(Sc(0, 1) / (G * eps), 1.0, 1e-5);
  EXPECT_GT(std::abs(Pp(0, 0) / (E * eps) - 1.0), 0.3);  // 1862/3000
  EXPECT_GT(std::abs(Pp(1, 1) / (E * eps)), 0.1);
  EXPECT_NEAR(Sp(0, 1) / (G * eps), nu, 1e-5);  // printed mu = nu * G
}

// eq. 3, D: the printed SUM mu/4[(a_j.a_m) + (a_k.a_l)] instead of the product gives an energy error
// against the oracle that grows like strain^2 (measured: 6e-4 at 5 %, 5 % at 20 %, 26 % at 50 %
// strain); the product reproduces the oracle.
TEST(PrintedErrors, Eq3DIsAProductNotASum) {
  const auto mat = StVenantKirchhoff::from_young_poisson(3000.0, 0.45);
  std::mt19937 rng(42);
  for (double strain : {0.05, 0.2, 0.5}) {
    const OneTet t = one_tet(rng, 0.01, strain);
    const TotalLagrangianStVK tl(t.mesh, mat);
    const TetRest& r = tl.rest(0);
    const double V = r.volume, w_oracle = tl.energy(t.u);
    const double w_product =
        energy_terms(make_tensors(r.grad, mat.lambda, mat.mu, V, V, V, DForm::kCorrectProduct), t.U).total();
    const double w_sum =
        energy_terms(make_tensors(r.grad, mat.lambda, mat.mu, V, V, V, DForm::kPrintedSum), t.U).total();
    std::printf("strain ~%.2f: rel. energy error, D product %.1e, printed D sum %.1e\n", strain,
                rel_err(w_product, w_oracle), rel_err(w_sum, w_oracle));
    EXPECT_LT(rel_err(w_product, w_oracle), 1e-12);
    EXPECT_GT(rel_err(w_sum, w_oracle), 0.1 * strain * strain);  // grows like strain^2
  }
}

// eq. 6: alpha_k (printed cross products) = -6V a_k. With alpha, B, C, D need the factors 1/(36V),
// -1/(216V^2), 1/(1296V^3); without them (as printed) the energy is wrong and scales with the wrong
// powers of the mesh size: at fixed F, scaling the mesh by s must scale W by s^3 (volume), but the
// printed quadratic, cubic and quartic terms scale as s^6, s^9, s^12.
TEST(PrintedErrors, Eq6AlphaNormalisation) {
  const auto mat = StVenantKirchhoff::from_young_poisson(3000.0, 0.45);
  const std::uint32_t seed = 99;
  Terms printed_at[2];
  double oracle_at[2];
  const double scales[2] = {1.0, 2.0};
  for (int i = 0; i < 2; ++i) {
    std::mt19937 same(seed);  // the same tet and the same F at both scales
    const OneTet t = one_tet(same, 0.01, 0.2, scales[i]);
    const TotalLagrangianStVK tl(t.mesh, mat);
    const double V = tl.rest(0).volume;
    const auto alpha = printed_alpha(t.P);
    for (int k = 0; k < 4; ++k)
      EXPECT_LT((alpha[k] + 6.0 * V * tl.rest(0).grad[k]).norm(), 1e-12 * alpha[k].norm());
    oracle_at[i] = tl.energy(t.u);
    const double w_scaled =
        energy_terms(make_tensors(alpha, mat.lambda, mat.mu, 1.0 / (36 * V), -1.0 / (216 * V * V),
                                  1.0 / (1296 * V * V * V), DForm::kCorrectProduct),
                     t.U)
            .total();
    EXPECT_LT(rel_err(w_scaled, oracle_at[i]), 1e-12);
    printed_at[i] =
        energy_terms(make_tensors(alpha, mat.lambda, mat.mu, 1, 1, 1, DForm::kCorrectProduct), t.U);
    std::printf("scale %.0f: oracle W = %.4e J, alpha with factors rel. err %.1e, printed W = %.4e\n",
                scales[i], oracle_at[i], rel_err(w_scaled, oracle_at[i]), printed_at[i].total());
    EXPECT_GT(rel_err(printed_at[i].total(), oracle_at[i]), 0.5);
  }
  EXPECT_NEAR(oracle_at[1] / oracle_at[0], 8.0, 1e-9);
  EXPECT_NEAR(printed_at[1].quadratic / printed_at[0].quadratic, 64.0, 1e-8);
  EXPECT_NEAR(printed_at[1].cubic / printed_at[0].cubic, 512.0, 1e-7);
  EXPECT_NEAR(printed_at[1].quartic / printed_at[0].quartic, 4096.0, 1e-6);
  std::printf("printed W(2s)/W(s) = %.1f (must be 8)\n", printed_at[1].total() / printed_at[0].total());
  EXPECT_GT(std::abs(printed_at[1].total() / printed_at[0].total() - 8.0), 4.0);
}

}  // namespace
}  // namespace tmlab::tm
