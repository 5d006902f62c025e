// The total-Lagrangian oracle against finite differences of itself, plus rigid-motion invariance
// and the affine patch test. Every other kernel is checked against this one.
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/testing/test_meshes.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

namespace tmlab::tm {
namespace {

using testing::rel_err;

Mesh single_tet(std::mt19937& rng) {
  Mesh m;
  const auto p = testing::random_tet_points(rng, 1.0, Vec3::Zero());
  m.points.assign(p.begin(), p.end());
  m.tets = {{0, 1, 2, 3}};
  return m;
}

// Central differences of W (a quartic in u) have error exactly h^2/6 W''' : the error must fall by
// 100x per decade of h until round-off, and reach ~1e-9 relative.
TEST(TLOracle, ForceIsCentralDifferenceOfEnergyStepStudy) {
  std::mt19937 rng(1);
  const auto mat = StVenantKirchhoff::from_young_poisson(3000.0, 0.45);
  for (int trial = 0; trial < 5; ++trial) {
    const Mesh m = single_tet(rng);
    const TotalLagrangianStVK model(m, mat);
    const VecX u = testing::random_displacement(4, 0.3, rng);  // finite strain, |grad u| ~ 0.5
    VecX f;
    model.internal_force(u, f);
    std::vector<double> errs;
    for (double h : {1e-2, 1e-3, 1e-4, 1e-5}) {
      VecX fd(12);
      for (int i = 0; i < 12; ++i) {
        VecX up = u, um = u;
        up(i) += h;
        um(i) -= h;
        fd(i) = (model.energy(up) - model.energy(um)) / (2 * h);
      }
      errs.push_back(rel_err(fd, f));
    }
    std::printf("force FD rel. error, h = 1e-2..1e-5: %.2e %.2e %.2e %.2e\n", errs[0], errs[1], errs[2],
                errs[3]);
    EXPECT_NEAR(errs[0] / errs[1], 100.0, 5.0);  // second-order convergence
    EXPECT_NEAR(errs[1] / errs[2], 100.0, 20.0);
    EXPECT_LT(*std::min_element(errs.begin(), errs.end()), 1e-8);
  }
}

TEST(TLOracle, TangentIsCentralDifferenceOfForceStepStudy) {
  std::mt19937 rng(2);
  const auto mat = StVenantKirchhoff::from_young_poisson(3000.0, 0.3);
  for (int trial = 0; trial < 5; ++trial) {
    const Mesh m = single_tet(rng);
    const TotalLagrangianStVK model(m, mat);
    const VecX u = testing::random_displacement(4, 0.3, rng);
    SpMat Ks;
    model.tangent(u, Ks);
    const Eigen::MatrixXd K = Eigen::MatrixXd(Ks);
    EXPECT_LT((K - K.transpose()).norm(), 1e-14 * K.norm());
    EXPECT_LT((K - model.tet_stiffness(0, u)).norm(), 1e-14 * K.norm());
    std::vector<double> errs;
    for (double h : {1e-2, 1e-3, 1e-4, 1e-5}) {
      Eigen::MatrixXd fd(12, 12);
      for (int i = 0; i < 12; ++i) {
        VecX up = u, um = u, fp, fm;
        up(i) += h;
        um(i) -= h;
        model.internal_force(up, fp);
        model.internal_force(um, fm);
        fd.col(i) = (fp - fm) / (2 * h);
      }
      errs.push_back((fd - K).norm() / K.norm());
    }
    std::printf("tangent FD rel. error, h = 1e-2..1e-5: %.2e %.2e %.2e %.2e\n", errs[0], errs[1], errs[2],
                errs[3]);
    EXPECT_NEAR(errs[0] / errs[1], 100.0, 5.0);
    EXPECT_NEAR(errs[1] / errs[2], 100.0, 20.0);
    EXPECT_LT(*std::min_element(errs.begin(), errs.end()), 1e-8);
    // matrix-free action = assembled matrix times v
    const VecX v = testing::random_displacement(4, 1.0, rng);
    VecX Kv;
    model.tangent_apply(u, v, Kv);
    EXPECT_LT(rel_err(Kv, VecX(K * v)), 1e-14);
  }
}

TEST(TLOracle, RigidMotionsGiveZeroForce) {
  std::mt19937 rng(3);
  const Mesh m = testing::jittered_box(4, 0.01, 0.2, rng);
  const TotalLagrangianStVK model(m, StVenantKirchhoff::from_young_poisson(3000.0, 0.45));
  // force scale: a unit-order strain
  VecX fref;
  model.internal_force(testing::random_displacement(m.num_points(), 0.5 * 0.01, rng), fref);
  const VecX zero = VecX::Zero(model.num_dofs());
  for (double angle : {0.0, 0.3, 2.0, 3.1}) {
    const VecX u =
        testing::rigidly_moved(m, zero, testing::rotation(Vec3(1, 2, 3), angle), Vec3(0.3, -0.2, 0.05));
    VecX f;
    model.internal_force(u, f);
    std::printf("rigid motion, angle %.1f: |f|/|f_ref| = %.2e, W = %.2e\n", angle, f.norm() / fref.norm(),
                model.energy(u));
    EXPECT_LT(f.norm(), 1e-12 * fref.norm());
  }
}

TEST(TLOracle, AffinePatchTest) {
  std::mt19937 rng(4);
  const int n = 4;
  const Mesh m = testing::jittered_box(n, 0.01, 0.25, rng);
  const TotalLagrangianStVK model(m, StVenantKirchhoff::from_young_poisson(3000.0, 0.45));
  Mat3 G;
  G << 0.2, -0.1, 0.05, 0.15, -0.1, 0.3, -0.05, 0.1, 0.1;
  const VecX u = testing::affine_displacement(m, G, Vec3(0.1, 0.2, 0.3));
  const Mat3 F = Mat3::Identity() + G;
  const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
  for (Index t = 0; t < model.num_tets(); ++t)
    ASSERT_LT((model.green_strain(t, u) - E).norm(), 1e-13) << "tet " << t;
  VecX f;
  model.internal_force(u, f);
  double fmax = 0.0, finterior = 0.0;
  for (Index i = 0; i < m.num_points(); ++i) {
    const Vec3 X = m.points[static_cast<std::size_t>(i)];
    const bool interior = (X.array() > 1e-9).all() && (X.array() < n * 0.01 - 1e-9).all();
    fmax = std::max(fmax, f.segment<3>(3 * i).norm());
    if (interior) finterior = std::max(finterior, f.segment<3>(3 * i).norm());
  }
  std::printf("patch test: max interior |f| / max |f| = %.2e\n", finterior / fmax);
  EXPECT_LT(finterior, 1e-12 * fmax);
}

}  // namespace
}  // namespace tmlab::tm
