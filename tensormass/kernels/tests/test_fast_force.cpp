// FastTetForce against its oracles (TotalLagrangianStVK for St VK, HyperelasticTL for neo-Hookean,
// the oracle's tet_force_from_stress for the objective viscoelastic trial force): equal to 1e-12
// relative on jittered boxes with large random displacements, and bit-identical for 1, 2 and 3
// threads (the deterministic parallel scatter of fast_force.hpp).
#include "tensormass/kernels/fast_force.hpp"

#include "core/base/error.hpp"
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/testing/test_meshes.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

namespace tmlab::tm {
namespace {

using testing::rel_err;

struct Problem {
  Mesh mesh;
  VecX u;
};

Problem problem(int n, unsigned seed) {
  std::mt19937 rng(seed);
  Problem p;
  const double h = 0.01;
  p.mesh = testing::jittered_box(n, h, 0.25, rng);
  p.u = testing::random_displacement(p.mesh.num_points(), 0.1 * h, rng);
  return p;
}

const StVenantKirchhoff kStVK = StVenantKirchhoff::from_young_poisson(3000.0, 0.45);

TEST(FastForce, StVKEqualsTheOracle) {
  for (int n : {1, 3, 7}) {  // 6, 162 and 2058 tets: partial groups, empty parts, many shared nodes
    const Problem p = problem(n, 7u + static_cast<unsigned>(n));
    const TotalLagrangianStVK oracle(p.mesh, kStVK);
    const FastTetForce fast(p.mesh, FastLaw::StVK, kStVK.lambda, kStVK.mu);
    VecX f_ref, f;
    oracle.internal_force(p.u, f_ref);
    fast.internal_force(p.u, f);
    EXPECT_LE(rel_err(f, f_ref), 1e-12) << n;
  }
}

TEST(FastForce, NeoHookeanEqualsHyperelasticTL) {
  const Problem p = problem(5, 11u);
  const NeoHookean law = NeoHookean::from_young_poisson(3000.0, 0.45);
  const HyperelasticTL oracle(p.mesh, Law(law));
  const FastTetForce fast(p.mesh, FastLaw::NeoHookean, law.lambda(), law.mu());
  VecX f_ref, f;
  oracle.internal_force(p.u, f_ref);
  fast.internal_force(p.u, f);
  EXPECT_LE(rel_err(f, f_ref), 1e-12);
}

TEST(FastForce, NeoHookeanInvertedTetGivesNaN) {
  Problem p = problem(1, 3u);
  // Mirror the whole box through x = 0: every tet is inverted.
  for (Index i = 0; i < p.mesh.num_points(); ++i)
    p.u[3 * i] = -2.0 * p.mesh.points[static_cast<std::size_t>(i)].x();
  const FastTetForce fast(p.mesh, FastLaw::NeoHookean, 1000.0, 500.0);
  VecX f;
  fast.internal_force(p.u, f);
  EXPECT_FALSE(f.allFinite());
}

TEST(FastForce, Pk2TrialForceEqualsTheOracleWithAStressHistory) {
  const Problem p = problem(5, 13u);
  const TotalLagrangianStVK oracle(p.mesh, kStVK);
  const FastTetForce fast(p.mesh, FastLaw::StVK, kStVK.lambda, kStVK.mu);
  std::mt19937 rng(5);
  std::vector<double> s_hist(6 * static_cast<std::size_t>(p.mesh.num_tets()));
  for (double& s : s_hist) s = testing::uniform(rng, -50.0, 50.0);
  const double lam = 1.3 * kStVK.lambda, mu = 1.3 * kStVK.mu;
  const StVenantKirchhoff eff{lam, mu};
  VecX f_ref = VecX::Zero(3 * p.mesh.num_points()), f;
  for (Index t = 0; t < p.mesh.num_tets(); ++t) {
    const Mat3 F = oracle.deformation_gradient(t, p.u);
    const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
    const Mat3 S = eff.pk2_stress(E) + from_voigt(&s_hist[6 * static_cast<std::size_t>(t)]);
    const Mat34 ft = oracle.tet_force_from_stress(t, F, S);
    for (int q = 0; q < 4; ++q)
      f_ref.segment<3>(3 * p.mesh.tets[static_cast<std::size_t>(t)][q]) += ft.col(q);
  }
  fast.trial_force_pk2(p.u, lam, mu, s_hist.data(), f);
  EXPECT_LE(rel_err(f, f_ref), 1e-12);
  const FastTetForce neo(p.mesh, FastLaw::NeoHookean, 1000.0, 500.0);
  EXPECT_THROW(neo.trial_force_pk2(p.u, lam, mu, s_hist.data(), f), Error);
}

TEST(FastForce, ThreadCountDoesNotChangeABit) {
  const Problem p = problem(9, 17u);
  for (FastLaw law : {FastLaw::StVK, FastLaw::NeoHookean}) {
    const FastTetForce one(p.mesh, law, kStVK.lambda, kStVK.mu, 1);
    VecX f1;
    one.internal_force(p.u, f1);
    for (int threads : {2, 3}) {
      const FastTetForce many(p.mesh, law, kStVK.lambda, kStVK.mu, threads);
      EXPECT_EQ(many.threads(), threads);
      VecX fk;
      for (int rep = 0; rep < 3; ++rep) {  // the pool is reused across calls
        many.internal_force(p.u, fk);
        ASSERT_EQ(fk.size(), f1.size());
        EXPECT_EQ(std::memcmp(fk.data(), f1.data(), sizeof(double) * static_cast<std::size_t>(f1.size())), 0)
            << threads << " threads, call " << rep;
      }
    }
  }
}

TEST(FastForce, BadInputIsRefused) {
  const Problem p = problem(2, 19u);
  EXPECT_THROW(FastTetForce(p.mesh, FastLaw::StVK, 1.0, 1.0, 0), Error);
  const FastTetForce fast(p.mesh, FastLaw::StVK, 1.0, 1.0);
  VecX f;
  EXPECT_THROW(fast.internal_force(VecX::Zero(5), f), Error);
}

}  // namespace
}  // namespace tmlab::tm
