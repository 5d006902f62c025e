// FastTetForce against its oracles (TotalLagrangianStVK for St VK, HyperelasticTL for neo-Hookean,
// the oracle's tet_force_from_stress for the objective viscoelastic trial force and for the fused
// Prony step, whose history is stored in the kernel's lane order): equal to 1e-12 relative on
// jittered boxes with large random displacements, and bit-identical for 1, 2 and 3 threads (the
// deterministic parallel scatter of fast_force.hpp).
#include "tensormass/kernels/fast_force.hpp"

#include "core/base/error.hpp"
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/testing/test_meshes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

/// The fused step's state: history [t][j][6] and driver [t][6] in mesh order.
struct PronyState {
  std::vector<double> hist, driver;
};

/// One fused step by the oracle, tet by tet in mesh order: E, the driver x (S_e or S_dev), h_j <-
/// a_j h_j + c_j (x - X), X <- x, the force of S_e + sum_j alpha_j h_j.
VecX oracle_fused_step(const Mesh& mesh, const VecX& u, const FastTetForce::PronyStep& step, PronyState& s) {
  const TotalLagrangianStVK oracle(mesh, kStVK);
  const int nj = step.terms;
  VecX f = VecX::Zero(3 * mesh.num_points());
  for (Index t = 0; t < mesh.num_tets(); ++t) {
    const std::size_t ts = static_cast<std::size_t>(t);
    const Mat3 F = oracle.deformation_gradient(t, u);
    const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
    Mat3 S = kStVK.pk2_stress(E);
    double x[6];
    to_voigt(step.deviatoric ? Mat3(2.0 * kStVK.mu * (E - E.trace() / 3.0 * Mat3::Identity())) : S, x);
    for (int j = 0; j < nj; ++j) {
      double* h = &s.hist[(ts * static_cast<std::size_t>(nj) + static_cast<std::size_t>(j)) * 6];
      for (int k = 0; k < 6; ++k) h[k] = step.a[j] * h[k] + step.c[j] * (x[k] - s.driver[6 * ts + k]);
      S += step.alpha[j] * from_voigt(h);
    }
    std::copy(x, x + 6, &s.driver[6 * ts]);
    const Mat34 ft = oracle.tet_force_from_stress(t, F, S);
    for (int q = 0; q < 4; ++q) f.segment<3>(3 * mesh.tets[ts][q]) += ft.col(q);
  }
  return f;
}

/// Mesh order [t][c] (per_tet values) to the kernel's lane order [g][c][l] and back.
std::vector<double> to_lanes(const FastTetForce& k, const std::vector<double>& mesh, int per_tet) {
  constexpr int L = FastTetForce::kLanes;
  std::vector<double> lanes(k.num_slots() * static_cast<std::size_t>(per_tet), 0.0);
  const std::vector<std::int32_t> slot = k.tet_slots();
  for (std::size_t t = 0; t < slot.size(); ++t)
    for (int c = 0; c < per_tet; ++c)
      lanes[(static_cast<std::size_t>(slot[t] / L * per_tet + c)) * L +
            static_cast<std::size_t>(slot[t] % L)] =
          mesh[t * static_cast<std::size_t>(per_tet) + static_cast<std::size_t>(c)];
  return lanes;
}
std::vector<double> from_lanes(const FastTetForce& k, const std::vector<double>& lanes, int per_tet) {
  constexpr int L = FastTetForce::kLanes;
  const std::vector<std::int32_t> slot = k.tet_slots();
  std::vector<double> mesh(slot.size() * static_cast<std::size_t>(per_tet));
  for (std::size_t t = 0; t < slot.size(); ++t)
    for (int c = 0; c < per_tet; ++c)
      mesh[t * static_cast<std::size_t>(per_tet) + static_cast<std::size_t>(c)] =
          lanes[(static_cast<std::size_t>(slot[t] / L * per_tet + c)) * L +
                static_cast<std::size_t>(slot[t] % L)];
  return mesh;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b, double* scale) {
  double d = 0.0, m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    d = std::max(d, std::abs(a[i] - b[i]));
    m = std::max(m, std::abs(b[i]));
  }
  *scale = m;
  return d;
}

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
  fast.trial_force_pk2(p.u, lam, mu, to_lanes(fast, s_hist, 6).data(), f);  // lane order
  EXPECT_LE(rel_err(f, f_ref), 1e-12);
  const FastTetForce neo(p.mesh, FastLaw::NeoHookean, 1000.0, 500.0);
  EXPECT_THROW(neo.trial_force_pk2(p.u, lam, mu, s_hist.data(), f), Error);
}

TEST(FastForce, FusedPk2StepInLaneOrderEqualsTheOracle) {
  const Problem p = problem(3, 23u);  // 162 tets: partial groups, so padding slots
  std::mt19937 rng(31);
  const VecX u2 = testing::random_displacement(p.mesh.num_points(), 0.001, rng);  // a second displacement
  const FastTetForce one(p.mesh, FastLaw::StVK, kStVK.lambda, kStVK.mu, 1);
  ASSERT_GT(one.num_slots(), static_cast<std::size_t>(p.mesh.num_tets()));
  for (int nj = 0; nj <= FastTetForce::PronyStep::kMaxTerms; ++nj)
    for (bool dev : {false, true}) {
      FastTetForce::PronyStep step;
      step.terms = nj;
      step.deviatoric = dev;
      for (int j = 0; j < nj; ++j) {
        step.alpha[j] = testing::uniform(rng, 0.1, 2.0);
        step.a[j] = testing::uniform(rng, 0.3, 0.99);
        step.c[j] = testing::uniform(rng, 0.2, 0.9);
      }
      const std::size_t nt = static_cast<std::size_t>(p.mesh.num_tets());
      PronyState ref{std::vector<double>(nt * 6 * static_cast<std::size_t>(nj)), std::vector<double>(nt * 6)};
      for (double& v : ref.hist) v = testing::uniform(rng, -50.0, 50.0);
      for (double& v : ref.driver) v = testing::uniform(rng, -50.0, 50.0);
      std::vector<double> hist = to_lanes(one, ref.hist, 6 * nj), driver = to_lanes(one, ref.driver, 6);
      for (const VecX* u : {&p.u, &u2, &p.u}) {  // the state carried over three steps
        const VecX f_ref = oracle_fused_step(p.mesh, *u, step, ref);
        VecX f;
        one.force_and_commit_pk2(*u, step, hist.data(), driver.data(), f);
        EXPECT_LE(rel_err(f, f_ref), 1e-12) << nj << " terms, dev " << dev;
        double scale = 0.0;
        const double dh = max_abs_diff(from_lanes(one, hist, 6 * nj), ref.hist, &scale);
        EXPECT_LE(dh, 1e-12 * scale) << nj << " terms, dev " << dev;
        const double dx = max_abs_diff(from_lanes(one, driver, 6), ref.driver, &scale);
        EXPECT_LE(dx, 1e-12 * scale) << nj << " terms, dev " << dev;
      }
      // the padding slots stay zero
      constexpr std::size_t L = FastTetForce::kLanes;
      const std::vector<std::int32_t> slot = one.tet_slots();
      std::vector<bool> used(one.num_slots(), false);
      for (std::int32_t s : slot) used[static_cast<std::size_t>(s)] = true;
      for (std::size_t s = 0; s < one.num_slots(); ++s) {
        if (used[s]) continue;
        for (int k = 0; k < 6; ++k)
          ASSERT_EQ(driver[(s / L * 6 + static_cast<std::size_t>(k)) * L + s % L], 0.0) << s;
        for (int c = 0; c < 6 * nj; ++c)
          ASSERT_EQ(
              hist[(s / L * 6 * static_cast<std::size_t>(nj) + static_cast<std::size_t>(c)) * L + s % L], 0.0)
              << s;
      }
    }
  const FastTetForce neo(p.mesh, FastLaw::NeoHookean, 1000.0, 500.0);
  FastTetForce::PronyStep step;
  std::vector<double> h(neo.num_slots() * 6), x(neo.num_slots() * 6);
  VecX f;
  EXPECT_THROW(neo.force_and_commit_pk2(p.u, step, h.data(), x.data(), f), Error);
  step.terms = FastTetForce::PronyStep::kMaxTerms + 1;
  EXPECT_THROW(one.force_and_commit_pk2(p.u, step, h.data(), x.data(), f), Error);
}

TEST(FastForce, FusedPk2StepIsBitIdenticalForAnyThreadCount) {
  const Problem p = problem(9, 37u);
  FastTetForce::PronyStep step;
  step.terms = 2;
  for (int j = 0; j < 2; ++j) {
    step.alpha[j] = 0.8 / (j + 1);
    step.a[j] = 0.9 + 0.09 * j;
    step.c[j] = 0.7 - 0.2 * j;
  }
  const FastTetForce one(p.mesh, FastLaw::StVK, kStVK.lambda, kStVK.mu, 1);
  std::vector<double> h1(one.num_slots() * 12, 0.0), x1(one.num_slots() * 6, 0.0);
  VecX f1;
  one.force_and_commit_pk2(p.u, step, h1.data(), x1.data(), f1);
  one.force_and_commit_pk2(0.5 * p.u, step, h1.data(), x1.data(), f1);
  for (int threads : {2, 3}) {
    const FastTetForce many(p.mesh, FastLaw::StVK, kStVK.lambda, kStVK.mu, threads);
    ASSERT_EQ(many.tet_slots(), one.tet_slots());  // the lane order does not depend on the threads
    std::vector<double> hk(many.num_slots() * 12, 0.0), xk(many.num_slots() * 6, 0.0);
    VecX fk;
    many.force_and_commit_pk2(p.u, step, hk.data(), xk.data(), fk);
    many.force_and_commit_pk2(0.5 * p.u, step, hk.data(), xk.data(), fk);
    ASSERT_EQ(fk.size(), f1.size());
    EXPECT_EQ(std::memcmp(fk.data(), f1.data(), sizeof(double) * static_cast<std::size_t>(f1.size())), 0)
        << threads << " threads";
    EXPECT_EQ(hk, h1) << threads << " threads";
    EXPECT_EQ(xk, x1) << threads << " threads";
  }
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
