// HyperelasticTL: for every law, force = dW/du and tangent = df/du by finite differences on a
// small jittered mesh (random, strongly compressed and sheared states), the assembled tangent equals
// the matrix-free action and is symmetric, rigid motions give no force; for St VK the kernel equals
// the total-Lagrangian oracle (tl_oracle.hpp) to round-off; outside the domain (det F <= 0) energy
// is +inf and force NaN.
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/testing/test_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace tmlab::tm {
namespace {

using testing::rel_err;

std::vector<Law> all_laws() {
  const double E = 1000.0, nu = 0.4, mu = E / (2 * (1 + nu)), kappa = E / (3 * (1 - 2 * nu));
  return {StVenantKirchhoff::from_young_poisson(E, nu),
          NeoHookean::from_young_poisson(E, nu),
          MooneyRivlin(0.35 * mu, 0.15 * mu, kappa),
          Yeoh(0.5 * mu, 0.3 * mu, 0.05 * mu, kappa),
          Ogden({0.6 * mu, 0.01 * mu, -0.05 * mu}, {1.3, 5.0, -2.0}, kappa),
          VerondaWestmann(0.25 * mu, 4.0, kappa)};
}

/// Displacements to test at: random (|grad u| ~ 0.2), uniaxial compression to J = 0.3 plus noise,
/// simple shear of amount 1 plus noise.
std::vector<std::pair<std::string, VecX>> states(const Mesh& m, std::mt19937& rng) {
  std::vector<std::pair<std::string, VecX>> out;
  out.emplace_back("random", testing::random_displacement(m.num_points(), 0.05, rng));
  Mat3 G = Mat3::Zero();
  G(0, 0) = -0.7;
  out.emplace_back("compression J=0.3", testing::affine_displacement(m, G, Vec3::Zero()) +
                                            testing::random_displacement(m.num_points(), 0.005, rng));
  G.setZero();
  G(0, 1) = 1.0;
  out.emplace_back("shear 1.0", testing::affine_displacement(m, G, Vec3::Zero()) +
                                    testing::random_displacement(m.num_points(), 0.005, rng));
  return out;
}

TEST(HyperelasticTL, ForceAndTangentAreDerivativesForEveryLaw) {
  std::mt19937 rng(5);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  const auto us = states(m, rng);
  for (const Law& law : all_laws()) {
    const HyperelasticTL model(m, law);
    for (const auto& [name, u] : us) {
      SCOPED_TRACE(law.name() + ", " + name);
      VecX f;
      model.internal_force(u, f);
      ASSERT_TRUE(f.allFinite());
      // 4th-order central differences of W and f along random directions
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
        SpMat K;
        model.tangent(u, K);
        EXPECT_LT(rel_err(VecX(K * v), Kv), 1e-13);
        EXPECT_LT((Eigen::MatrixXd(K) - Eigen::MatrixXd(K).transpose()).norm(),
                  1e-13 * Eigen::MatrixXd(K).norm());
      }
      // the pattern is reused: a second call refills in place and gives the same matrix
      SpMat K1, K2;
      model.tangent(u, K1);
      K2 = K1;
      model.tangent(u, K2);
      EXPECT_EQ((Eigen::MatrixXd(K1) - Eigen::MatrixXd(K2)).norm(), 0.0);
    }
  }
}

TEST(HyperelasticTL, StVenantKirchhoffEqualsTheOracle) {
  std::mt19937 rng(6);
  const Mesh m = testing::jittered_box(3, 0.3, 0.25, rng, Vec3(1.0, -2.0, 0.5));
  const auto mat = StVenantKirchhoff::from_young_poisson(3000.0, 0.45);
  const HyperelasticTL model(m, mat);
  const TotalLagrangianStVK oracle(m, mat);
  for (const auto& [name, u] : states(m, rng)) {
    SCOPED_TRACE(name);
    EXPECT_LT(rel_err(model.energy(u), oracle.energy(u)), 1e-13);
    VecX f, fo, Kv, Kvo;
    model.internal_force(u, f);
    oracle.internal_force(u, fo);
    EXPECT_LT(rel_err(f, fo), 1e-13);
    const VecX v = testing::random_displacement(m.num_points(), 1.0, rng);
    model.tangent_apply(u, v, Kv);
    oracle.tangent_apply(u, v, Kvo);
    EXPECT_LT(rel_err(Kv, Kvo), 1e-13);
    SpMat K, Ko;
    model.tangent(u, K);
    oracle.tangent(u, Ko);
    EXPECT_LT(rel_err(K, Ko), 1e-13);
  }
}

TEST(HyperelasticTL, RigidMotionGivesNoForce) {
  std::mt19937 rng(7);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  const VecX u = testing::random_displacement(m.num_points(), 0.05, rng);
  const VecX ur = testing::rigidly_moved(m, u, testing::rotation(Vec3(1, 2, 3), 1.1), Vec3(4, -5, 6));
  const VecX r =
      testing::rigidly_moved(m, VecX::Zero(u.size()), testing::rotation(Vec3(-1, 0, 2), 2.0), Vec3(1, 1, 1));
  for (const Law& law : all_laws()) {
    SCOPED_TRACE(law.name());
    const HyperelasticTL model(m, law);
    VecX f0, f;
    model.internal_force(r, f0);
    EXPECT_LT(f0.norm(), 1e-10 * law.small_strain().mu);
    EXPECT_NEAR(model.energy(r), 0.0, 1e-10 * law.small_strain().mu);
    // the energy of a deformed state is invariant under a superposed rigid motion
    EXPECT_LT(rel_err(model.energy(ur), model.energy(u)), 1e-11);
    model.internal_force(u, f0);
    model.internal_force(ur, f);
    EXPECT_NEAR(f.norm(), f0.norm(), 1e-11 * f0.norm());
  }
}

TEST(HyperelasticTL, InvertedTetIsOutsideTheDomain) {
  Mesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.tets = {{0, 1, 2, 3}};
  VecX u = VecX::Zero(12);
  u(11) = -2.0;  // node 3 pushed through the base: det F = -1
  for (const Law& law : all_laws()) {
    SCOPED_TRACE(law.name());
    const HyperelasticTL model(m, law);
    VecX f;
    model.internal_force(u, f);
    if (law.is_stvk()) {  // St VK is defined everywhere (and the oracle evaluates it there)
      EXPECT_TRUE(std::isfinite(model.energy(u)));
      EXPECT_TRUE(f.allFinite());
    } else {
      EXPECT_EQ(model.energy(u), std::numeric_limits<double>::infinity());
      EXPECT_TRUE(f.hasNaN());
    }
  }
}

}  // namespace
}  // namespace tmlab::tm
