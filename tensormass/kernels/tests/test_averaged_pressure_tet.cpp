// AveragedPressureTet: psi's gradient and Hessian against finite differences; for every law,
// force = dW/du and tangent = df/du by finite differences on a jittered mesh, the assembled (widened)
// tangent equals the matrix-free action, is symmetric and needs all of its pattern; an affine field
// gives exactly P1's (HyperelasticTL's) energy and force; rigid motions give no force; exactly six
// zero modes at u = 0 on distorted patches; the patch test (boundary affine, interior solved); no
// locking on the model-locking deep beam (nu 0.3 vs 0.499) where P1 locks; outside the domain
// energy +inf and NaN force; the widened pattern's nonzeros against P1's on a 16^3 block; the fused
// force pass against the direct (reference) force, for the Law and for a viscoelastic trial law
// (TrialStress, with its own finite-difference checks); the cube root against std::cbrt.
#include "tensormass/kernels/averaged_pressure_tet.hpp"
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/kernels/tangent_pattern.hpp"
#include "tensormass/testing/test_meshes.hpp"

#include "core/mesh/sample_meshes.hpp"

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace tmlab::tm {
namespace {

using Eigen::MatrixXd;
using testing::rel_err;

std::vector<Law> all_laws(double nu = 0.4) {
  const double E = 1000.0, mu = E / (2 * (1 + nu)), kappa = E / (3 * (1 - 2 * nu));
  return {StVenantKirchhoff::from_young_poisson(E, nu),
          NeoHookean::from_young_poisson(E, nu),
          MooneyRivlin(0.35 * mu, 0.15 * mu, kappa),
          Yeoh(0.5 * mu, 0.3 * mu, 0.05 * mu, kappa),
          Ogden({0.6 * mu, 0.01 * mu, -0.05 * mu}, {1.3, 5.0, -2.0}, kappa),
          VerondaWestmann(0.25 * mu, 4.0, kappa)};
}

/// Displacements to test at: random (|grad u| ~ 0.2), uniaxial compression to J = 0.5 plus noise,
/// simple shear of amount 1 plus noise (noise makes the J_e differ, so Jbar != J).
std::vector<std::pair<std::string, VecX>> states(const Mesh& m, std::mt19937& rng) {
  std::vector<std::pair<std::string, VecX>> out;
  out.emplace_back("random", testing::random_displacement(m.num_points(), 0.05, rng));
  Mat3 G = Mat3::Zero();
  G(0, 0) = -0.5;
  out.emplace_back("compression J=0.5", testing::affine_displacement(m, G, Vec3::Zero()) +
                                            testing::random_displacement(m.num_points(), 0.01, rng));
  G.setZero();
  G(0, 1) = 1.0;
  out.emplace_back("shear 1.0", testing::affine_displacement(m, G, Vec3::Zero()) +
                                    testing::random_displacement(m.num_points(), 0.01, rng));
  return out;
}

TEST(AveragedPressureTet, PsiGradientAndHessianAreDerivatives) {
  std::mt19937 rng(11);
  const Mesh m = testing::jittered_box(1, 1.0, 0.0, rng);
  for (const Law& law : all_laws()) {
    SCOPED_TRACE(law.name());
    const AveragedPressureTet model(m, law);
    for (int trial = 0; trial < 4; ++trial) {
      Mat3 F = Mat3::Identity();
      for (int i = 0; i < 3; ++i) F.row(i) += testing::random_vec(rng, 0.3).transpose();
      if (F.determinant() < 0.2) F = Mat3::Identity();
      const double Jb = F.determinant() * testing::uniform(rng, 0.6, 1.5);
      const auto g = model.psi_gradient(F, Jb);
      const auto H = model.psi_hessian(F, Jb);
      const double h = 1e-5;
      for (int k = 0; k < 10; ++k) {
        auto at = [&](double s) {
          Mat3 Fs = F;
          double Js = Jb;
          if (k < 9)
            Fs(k / 3, k % 3) += s;
          else
            Js += s;
          return std::make_pair(Fs, Js);
        };
        auto psi = [&](double s) {
          const auto [Fs, Js] = at(s);
          return model.psi(Fs, Js);
        };
        auto grd = [&](double s) {
          const auto [Fs, Js] = at(s);
          return Eigen::Matrix<double, 10, 1>(model.psi_gradient(Fs, Js));
        };
        const double fd = (-psi(2 * h) + 8 * psi(h) - 8 * psi(-h) + psi(-2 * h)) / (12 * h);
        EXPECT_NEAR(fd, g(k), 1e-7 * g.norm());
        const Eigen::Matrix<double, 10, 1> fdH =
            (-grd(2 * h) + 8 * grd(h) - 8 * grd(-h) + grd(-2 * h)) / (12 * h);
        EXPECT_LT((fdH - H.col(k)).norm(), 1e-7 * H.norm());
      }
      EXPECT_LT((H - H.transpose()).norm(), 1e-12 * H.norm());
      // P_iso : F = 0 (the element's own part is isochoric)
      Mat3 Piso;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) Piso(i, j) = g(3 * i + j);
      EXPECT_NEAR(Piso.cwiseProduct(F).sum(), 0.0, 1e-12 * Piso.norm() * F.norm());
    }
  }
}

TEST(AveragedPressureTet, ForceAndTangentAreDerivativesForEveryLaw) {
  std::mt19937 rng(5);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  const auto us = states(m, rng);
  for (const Law& law : all_laws()) {
    const AveragedPressureTet model(m, law);
    for (const auto& [name, u] : us) {
      SCOPED_TRACE(law.name() + ", " + name);
      VecX f;
      model.internal_force(u, f);
      ASSERT_TRUE(f.allFinite());
      SpMat K;
      model.tangent(u, K);
      const MatrixXd Kd(K);
      EXPECT_LT((Kd - Kd.transpose()).norm(), 1e-13 * Kd.norm());
      for (int k = 0; k < 3; ++k) {
        const VecX v = testing::random_displacement(m.num_points(), 1.0, rng);
        const double h = 1e-4;
        auto W = [&](double s) { return model.energy(u + s * v); };
        const double fd_w = (-W(2 * h) + 8 * W(h) - 8 * W(-h) + W(-2 * h)) / (12 * h);
        EXPECT_NEAR(fd_w, f.dot(v), 1e-8 * f.norm() * v.norm());
        auto Fv = [&](double s) {
          VecX g;
          model.internal_force(u + s * v, g);
          return g;
        };
        const VecX fd_k = (-Fv(2 * h) + 8 * Fv(h) - 8 * Fv(-h) + Fv(-2 * h)) / (12 * h);
        VecX Kv;
        model.tangent_apply(u, v, Kv);
        EXPECT_LT(rel_err(fd_k, Kv), 1e-8);
        EXPECT_LT(rel_err(VecX(K * v), Kv), 1e-13);
      }
      SpMat K2 = K;  // the pattern is reused: a refill in place gives the same matrix
      const double* before = K2.valuePtr();
      model.tangent(u, K2);
      EXPECT_EQ(K2.valuePtr(), before);
      EXPECT_EQ((MatrixXd(K2) - Kd).norm(), 0.0);
    }
  }
}

TEST(AveragedPressureTet, VolumeCubeRootIsTheRealCubeRoot) {
  // Within 4 ulps of std::cbrt: on [1/2, 2] (the polynomial and Halley branch, 10^5 points) and
  // outside it (std::cbrt itself, negative ratios included: St VK accepts J_e < 0).
  const double ulp = std::numeric_limits<double>::epsilon();
  double worst = 0.0;
  for (int k = 0; k <= 100000; ++k) {
    const double r = 0.5 + 1.5 * k / 100000.0;
    worst = std::max(worst, std::abs(AveragedPressureTet::volume_cube_root(r) / std::cbrt(r) - 1.0));
  }
  std::printf("volume_cube_root on [1/2, 2]: max relative difference to std::cbrt %.2e (%.2f ulp)\n", worst,
              worst / ulp);
  EXPECT_LE(worst, 4.0 * ulp);
  for (double r : {1e-6, 0.1, 0.4999, 2.0001, 8.0, 1e5, -0.3, -1.0, -5.0})
    EXPECT_EQ(AveragedPressureTet::volume_cube_root(r), std::cbrt(r)) << r;
  EXPECT_NEAR(AveragedPressureTet::volume_cube_root(1.0), 1.0, ulp);
}

/// A trial stress of a viscoelastic step: gain g and a random per-tet S_hist of order `scale`.
std::vector<double> random_history_stress(Index num_tets, double scale, std::mt19937& rng) {
  std::vector<double> s(6 * static_cast<std::size_t>(num_tets));
  for (double& x : s) x = testing::uniform(rng, -scale, scale);
  return s;
}

TEST(AveragedPressureTet, FusedForceEqualsTheReferenceForce) {
  std::mt19937 rng(13);
  const Mesh m = testing::jittered_box(3, 0.5, 0.25, rng);
  const auto us = states(m, rng);
  for (const Law& law : all_laws()) {
    const AveragedPressureTet model(m, law);
    const std::vector<double> sh = random_history_stress(model.num_tets(), 0.2 * law.small_strain().mu, rng);
    const AveragedPressureTet::TrialStress ts{0.7, sh.data()};
    for (const auto& [name, u] : us) {
      SCOPED_TRACE(law.name() + ", " + name);
      VecX f, fr;
      model.internal_force(u, f);
      model.internal_force_reference(u, fr);
      EXPECT_LT((f - fr).norm(), 1e-12 * fr.norm());
      model.internal_force_with(u, f, ts);
      model.internal_force_reference(u, fr, ts);
      EXPECT_LT((f - fr).norm(), 1e-12 * fr.norm());
      // a second call reuses the workspace: the same result
      VecX f2;
      model.internal_force_with(u, f2, ts);
      EXPECT_EQ(f2, f);
    }
  }
}

TEST(AveragedPressureTet, TrialStressForceAndTangentAreDerivatives) {
  std::mt19937 rng(14);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  const auto us = states(m, rng);
  for (const Law& law :
       {Law(NeoHookean::from_young_poisson(1000.0, 0.45)), Law(Yeoh(200.0, 80.0, 10.0, 5000.0)),
        Law(StVenantKirchhoff::from_young_poisson(1000.0, 0.3))}) {
    const AveragedPressureTet model(m, law);
    const std::vector<double> sh = random_history_stress(model.num_tets(), 0.2 * law.small_strain().mu, rng);
    const AveragedPressureTet::TrialStress ts{0.4, sh.data()};
    for (const auto& [name, u] : us) {
      SCOPED_TRACE(law.name() + ", " + name);
      VecX f;
      model.internal_force_with(u, f, ts);
      SpMat K;
      model.tangent_with(u, K, ts);
      const VecX v = testing::random_displacement(m.num_points(), 1.0, rng);
      const double h = 1e-4;
      auto W = [&](double s) { return model.energy_with(u + s * v, ts); };
      EXPECT_NEAR((-W(2 * h) + 8 * W(h) - 8 * W(-h) + W(-2 * h)) / (12 * h), f.dot(v),
                  1e-8 * f.norm() * v.norm());
      auto Fv = [&](double s) {
        VecX g;
        model.internal_force_with(u + s * v, g, ts);
        return g;
      };
      const VecX fd_k = (-Fv(2 * h) + 8 * Fv(h) - 8 * Fv(-h) + Fv(-2 * h)) / (12 * h);
      VecX Kv;
      model.tangent_apply_with(u, v, Kv, ts);
      EXPECT_LT(rel_err(fd_k, Kv), 1e-8);
      EXPECT_LT(rel_err(VecX(K * v), Kv), 1e-13);
      // the trial law differs from the law: the history stress is in the force
      VecX fe;
      model.internal_force(u, fe);
      EXPECT_GT((f - fe).norm(), 1e-3 * fe.norm());
    }
  }
}

TEST(AveragedPressureTet, TheWidenedPatternIsNeededEverywhere) {
  // Every 3x3 block of the pattern (nodes at most three edges apart) is nonzero at a generic u: the
  // widening is the exact Hessian's, not a loose bound.
  std::mt19937 rng(12);
  const Mesh m = testing::jittered_box(3, 0.5, 0.2, rng);
  const AveragedPressureTet model(m, NeoHookean::from_young_poisson(1000.0, 0.45));
  SpMat K;
  model.tangent(testing::random_displacement(m.num_points(), 0.05, rng), K);
  EXPECT_EQ(K.nonZeros(), model.pattern_nonzeros());
  int zero_blocks = 0;
  for (Eigen::Index c = 0; c < K.cols(); c += 3)
    for (SpMat::InnerIterator it(K, c); it; ++it)
      if (it.row() % 3 == 0 && MatrixXd(K.block(it.row(), c, 3, 3)).norm() == 0.0) ++zero_blocks;
  EXPECT_EQ(zero_blocks, 0);
  TangentPattern p1(m.num_points(), m.tets);
  SpMat K1;
  p1.reset(K1);
  EXPECT_GT(K.nonZeros(), K1.nonZeros());
}

TEST(AveragedPressureTet, AffineFieldIsExactlyP1) {
  std::mt19937 rng(6);
  const Mesh m = testing::jittered_box(3, 0.3, 0.25, rng, Vec3(1.0, -2.0, 0.5));
  Mat3 G;
  G << 0.2, 0.1, -0.05, 0.03, -0.3, 0.1, 0.02, 0.05, 0.15;
  const VecX u = testing::affine_displacement(m, G, Vec3(0.3, -0.1, 0.2));
  for (const Law& law : all_laws()) {
    SCOPED_TRACE(law.name());
    const AveragedPressureTet model(m, law);
    const HyperelasticTL p1(m, law);
    for (double r : model.volume_ratios(u)) EXPECT_NEAR(r, 1.0, 1e-14);
    EXPECT_LT(rel_err(model.energy(u), p1.energy(u)), 1e-13);
    VecX f, f1;
    model.internal_force(u, f);
    p1.internal_force(u, f1);
    // f1 is the boundary traction of the uniform stress (the interior nodes' forces cancel)
    EXPECT_LT((f - f1).norm(), 1e-13 * f1.norm());
  }
}

TEST(AveragedPressureTet, RigidMotionGivesNoForce) {
  std::mt19937 rng(7);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  const VecX u = testing::random_displacement(m.num_points(), 0.05, rng);
  const VecX ur = testing::rigidly_moved(m, u, testing::rotation(Vec3(1, 2, 3), 1.1), Vec3(4, -5, 6));
  const VecX r =
      testing::rigidly_moved(m, VecX::Zero(u.size()), testing::rotation(Vec3(-1, 0, 2), 2.0), Vec3(1, 1, 1));
  for (const Law& law : all_laws()) {
    SCOPED_TRACE(law.name());
    const AveragedPressureTet model(m, law);
    VecX f0, f;
    model.internal_force(r, f0);
    EXPECT_LT(f0.norm(), 1e-10 * law.small_strain().mu);
    EXPECT_NEAR(model.energy(r), 0.0, 1e-10 * law.small_strain().mu);
    EXPECT_LT(rel_err(model.energy(ur), model.energy(u)), 1e-11);
    model.internal_force(u, f0);
    model.internal_force(ur, f);
    EXPECT_NEAR(f.norm(), f0.norm(), 1e-11 * f0.norm());
  }
}

/// Sorted eigenvalues of the dense tangent at u = 0.
Eigen::VectorXd spectrum(const ElasticModel& model) {
  SpMat K;
  model.tangent(VecX::Zero(model.num_dofs()), K);
  return Eigen::SelfAdjointEigenSolver<MatrixXd>(MatrixXd(K), Eigen::EigenvaluesOnly).eigenvalues();
}

TEST(AveragedPressureTet, ExactlySixRigidZeroModesOnDistortedPatches) {
  for (int n : {1, 2, 3}) {
    for (double nu : {0.3, 0.499}) {
      std::mt19937 rng(static_cast<unsigned>(100 + n));
      const Mesh m = testing::jittered_box(n, 1.0, 0.3, rng);
      const Law law = NeoHookean::from_young_poisson(1000.0, nu);
      const Eigen::VectorXd ev = spectrum(AveragedPressureTet(m, law));
      const Eigen::VectorXd ev1 = spectrum(HyperelasticTL(m, law));
      const double top = ev(ev.size() - 1), top1 = ev1(ev1.size() - 1);
      SCOPED_TRACE("n = " + std::to_string(n) + ", nu = " + std::to_string(nu));
      EXPECT_GT(ev(0), -1e-10 * top);  // positive semi-definite
      for (int k = 0; k < 6; ++k) EXPECT_LT(std::abs(ev(k)), 1e-10 * top);
      EXPECT_GT(ev(6), 1e-6 * top);
      EXPECT_GT(ev1(6), 1e-6 * top1);
      std::printf(
          "zero modes: %d^3 box (%d tets, %d DOFs, interior jitter 0.3 h), nu = %.3f: "
          "|lambda_1..6|/lambda_max "
          "<= %.1e; lambda_7/lambda_max: ANP %.4e (lambda_7 %.4e), P1 %.4e (lambda_7 %.4e)\n",
          n, static_cast<int>(m.num_tets()), static_cast<int>(3 * m.num_points()), nu,
          std::max(std::abs(ev(0)), std::abs(ev(5))) / top, ev(6) / top, ev(6), ev1(6) / top1, ev1(6));
    }
  }
}

TEST(AveragedPressureTet, PatchTest) {
  // A distorted 4^3 patch: the boundary nodes follow u = G X + c, the 27 interior nodes start away
  // from it and are solved by Newton with the assembled tangent. The solution is the affine field to
  // round-off and Fbar (so the stress) is uniform.
  std::mt19937 rng(21);
  const int n = 4;
  const Mesh m = testing::jittered_box(n, 0.25, 0.3, rng);
  Mat3 G;
  G << 0.15, 0.05, -0.1, 0.02, -0.2, 0.07, -0.04, 0.03, 0.1;
  const Vec3 c(0.01, -0.02, 0.03);
  const VecX ua = testing::affine_displacement(m, G, c);
  std::vector<Eigen::Index> interior;
  for (Index i = 0; i < m.num_points(); ++i) {
    const Vec3& p = m.points[static_cast<std::size_t>(i)];
    if ((p.array() > 1e-9).all() && (p.array() < n * 0.25 - 1e-9).all())
      for (int a = 0; a < 3; ++a) interior.push_back(3 * i + a);
  }
  ASSERT_EQ(interior.size(), 3u * 27u);
  const auto ni = static_cast<Eigen::Index>(interior.size());
  for (const Law& law : all_laws(0.45)) {
    SCOPED_TRACE(law.name());
    const AveragedPressureTet model(m, law);
    VecX u = ua;
    for (Eigen::Index k : interior)
      u(k) += testing::uniform(rng, -0.005, 0.005);  // 2 % of a cell: full Newton steps
    VecX f;
    SpMat K;
    double r0 = 0.0, r = 0.0;
    for (int it = 0; it < 30; ++it) {
      model.internal_force(u, f);
      VecX ri(ni);
      for (Eigen::Index k = 0; k < ni; ++k) ri(k) = f(interior[static_cast<std::size_t>(k)]);
      r = ri.norm();
      if (it == 0) r0 = r;
      if (r < 1e-14 * r0) break;
      model.tangent(u, K);
      const MatrixXd Kd(K);
      MatrixXd Kii(ni, ni);
      for (Eigen::Index a = 0; a < ni; ++a)
        for (Eigen::Index b = 0; b < ni; ++b)
          Kii(a, b) = Kd(interior[static_cast<std::size_t>(a)], interior[static_cast<std::size_t>(b)]);
      const VecX du = Kii.ldlt().solve(-ri);
      for (Eigen::Index k = 0; k < ni; ++k) u(interior[static_cast<std::size_t>(k)]) += du(k);
    }
    EXPECT_LT(r, 1e-12 * r0);
    EXPECT_LT((u - ua).lpNorm<Eigen::Infinity>(), 1e-12 * ua.lpNorm<Eigen::Infinity>());
    const Mat3 F = Mat3::Identity() + G;
    for (Index t = 0; t < model.num_tets(); ++t)
      EXPECT_LT((model.averaged_deformation_gradient(t, u) - F).norm(), 1e-12);
  }
}

TEST(AveragedPressureTet, InvertedTetIsOutsideTheDomain) {
  Mesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.tets = {{0, 1, 2, 3}};
  VecX u = VecX::Zero(12);
  u(11) = -2.0;  // det F = -1
  for (const Law& law : all_laws()) {
    SCOPED_TRACE(law.name());
    const AveragedPressureTet model(m, law);
    VecX f;
    model.internal_force(u, f);
    if (law.is_stvk()) {
      EXPECT_TRUE(std::isfinite(model.energy(u)));
      EXPECT_TRUE(f.allFinite());
    } else {
      EXPECT_EQ(model.energy(u), std::numeric_limits<double>::infinity());
      EXPECT_TRUE(f.hasNaN());
    }
  }
}

/// model-locking's quarter deep beam (verification/cases/model-locking/beam.json): box 20 x 10 x 20
/// mm (x: half span, y: half width, z: depth), symmetry x = 0 (u_x = 0) and y = 0 (u_y = 0), the
/// diaphragm support x = 20 mm (u_y = u_z = 0), own weight (1000 kg/m^3, g = 9.81), E = 1 MPa, St VK
/// linearised at u = 0. Returns the mid-span deflection -u_z at (0, 0, 10 mm).
double beam_deflection(bool anp, int cells, double nu) {
  const double Lx = 0.02, Ly = 0.01, Lz = 0.02;
  const Mesh m = make_box_mesh(Vec3::Zero(), Vec3(Lx, Ly, Lz), cells, cells, cells);
  const Law law = StVenantKirchhoff::from_young_poisson(1e6, nu);
  SpMat K;
  const VecX u0 = VecX::Zero(3 * m.num_points());
  if (anp)
    AveragedPressureTet(m, law).tangent(u0, K);
  else
    HyperelasticTL(m, law).tangent(u0, K);
  const std::vector<TetRest> rest = compute_tet_rest(m);
  VecX f = VecX::Zero(K.rows());
  for (std::size_t t = 0; t < m.tets.size(); ++t)
    for (Index a : m.tets[t]) f(3 * a + 2) -= 1000.0 * 9.81 * rest[t].volume / 4.0;
  std::vector<Eigen::Index> free_of(static_cast<std::size_t>(K.rows()), -1);
  Eigen::Index nf = 0;
  Index probe = -1;
  const double eps = 1e-9;
  for (Index i = 0; i < m.num_points(); ++i) {
    const Vec3& p = m.points[static_cast<std::size_t>(i)];
    const bool fixed[3] = {p.x() < eps, p.y() < eps || p.x() > Lx - eps, p.x() > Lx - eps};
    for (int a = 0; a < 3; ++a)
      if (!fixed[a]) free_of[static_cast<std::size_t>(3 * i + a)] = nf++;
    if (p.x() < eps && p.y() < eps && std::abs(p.z() - Lz / 2) < eps) probe = i;
  }
  std::vector<Eigen::Triplet<double>> trip;
  for (Eigen::Index c = 0; c < K.cols(); ++c)
    for (SpMat::InnerIterator it(K, c); it; ++it) {
      const Eigen::Index r = free_of[static_cast<std::size_t>(it.row())],
                         cc = free_of[static_cast<std::size_t>(c)];
      if (r >= 0 && cc >= 0) trip.emplace_back(r, cc, it.value());
    }
  SpMat Kf(nf, nf);
  Kf.setFromTriplets(trip.begin(), trip.end());
  VecX ff(nf);
  for (Eigen::Index k = 0; k < K.rows(); ++k)
    if (free_of[static_cast<std::size_t>(k)] >= 0) ff(free_of[static_cast<std::size_t>(k)]) = f(k);
  const Eigen::SimplicialLDLT<SpMat> ldlt(Kf);
  EXPECT_EQ(ldlt.info(), Eigen::Success);
  const VecX uf = ldlt.solve(ff);
  return -uf(free_of[static_cast<std::size_t>(3 * probe + 2)]);
}

TEST(AveragedPressureTet, NoLockingOnTheDeepBeam) {
  // model-locking measures P1's mid-span deflection error growing by 2.79x from nu = 0.3 to 0.499
  // against deal.II P2 on the refined (8^3) mesh, whose deflections it reports: 15.61 um (nu = 0.3)
  // and 16.32 um (nu = 0.499) (verification/cases/model-locking/README.md, an independent solver).
  // Locking means an error constant growing with lambda/mu: model-locking's criterion is an error
  // ratio err(0.499)/err(0.3) >= 2, and P1 meets it here too. This element must stay below it, and
  // as lambda/mu grows tenfold more (nu = 0.499 -> 0.4999, where the continuum deflection changes by
  // well under 1 %) its deflection must stay within 1 % (measured: -0.5 %; P1, already near its fully
  // locked limit on this mesh, -2.8 %). It converges: the 8^3 error is below half the 4^3 one.
  const double ref_p2[2] = {15.61e-6, 16.32e-6};
  const double nus[3] = {0.3, 0.499, 0.4999};
  double anp[3], p1[3], anp8[2];
  for (int k = 0; k < 3; ++k) {
    anp[k] = beam_deflection(true, 4, nus[k]);
    p1[k] = beam_deflection(false, 4, nus[k]);
    if (k < 2) anp8[k] = beam_deflection(true, 8, nus[k]);
    std::printf("deep beam nu = %.4f: mid-span deflection (um) 4^3: ANP %.4f P1 %.4f%s\n", nus[k],
                1e6 * anp[k], 1e6 * p1[k],
                k < 2 ? (", ANP 8^3 " + std::to_string(1e6 * anp8[k]) + ", P2 8^3 (deal.II) " +
                         std::to_string(1e6 * ref_p2[k]))
                            .c_str()
                      : "");
  }
  double err_anp[2], err_p1[2], err_anp8[2];
  for (int k = 0; k < 2; ++k) {
    err_anp[k] = std::abs(anp[k] - ref_p2[k]) / ref_p2[k];
    err_p1[k] = std::abs(p1[k] - ref_p2[k]) / ref_p2[k];
    err_anp8[k] = std::abs(anp8[k] - ref_p2[k]) / ref_p2[k];
  }
  std::printf(
      "deep beam 4^3 errors vs P2: ANP %.4f (nu 0.3) %.4f (nu 0.499) ratio %.3f; P1 %.4f %.4f ratio %.3f; "
      "ANP 8^3 %.4f %.4f; d(0.4999)/d(0.499): ANP %.5f P1 %.4f\n",
      err_anp[0], err_anp[1], err_anp[1] / err_anp[0], err_p1[0], err_p1[1], err_p1[1] / err_p1[0],
      err_anp8[0], err_anp8[1], anp[2] / anp[1], p1[2] / p1[1]);
  EXPECT_LT(err_anp[1] / err_anp[0], 2.0);
  EXPECT_GE(err_p1[1] / err_p1[0], 2.0);
  EXPECT_LT(std::abs(anp[2] / anp[1] - 1.0), 0.01);
  for (int k = 0; k < 2; ++k) EXPECT_LT(err_anp8[k], 0.5 * err_anp[k]);  // and it converges
}

TEST(AveragedPressureTet, WidenedPatternNonzerosOnABlock) {
  BlockSpec spec;
  spec.nx = spec.ny = spec.nz = 16;
  const Mesh m = make_block_mesh(spec);
  const AveragedPressureTet model(m, NeoHookean::from_young_poisson(3000.0, 0.45));
  SpMat K1;
  TangentPattern(m.num_points(), m.tets).reset(K1);
  std::printf("tangent nonzeros, make_block_mesh 16^3 (%d nodes, %d tets): P1 %ld, ANP %ld (x%.2f)\n",
              static_cast<int>(m.num_points()), static_cast<int>(m.num_tets()),
              static_cast<long>(K1.nonZeros()), static_cast<long>(model.pattern_nonzeros()),
              static_cast<double>(model.pattern_nonzeros()) / static_cast<double>(K1.nonZeros()));
  EXPECT_GT(model.pattern_nonzeros(), K1.nonZeros());
}

}  // namespace
}  // namespace tmlab::tm
