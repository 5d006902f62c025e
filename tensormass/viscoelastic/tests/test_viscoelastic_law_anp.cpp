// ViscoelasticAveragedPressureTet (the pk2/full Prony scheme at the averaged F of the p1_anp tet):
// - a homogeneous stretch ramped and held relaxes exactly as the P1 model's (Jbar = J there):
//   forces, trial potentials, energies and the committed energies and dissipation equal to round-off;
// - the force is the gradient of the trial potential and the tangent the derivative of the force
//   (finite differences, with committed history, on a jittered mesh where Jbar != J);
// - the step dissipation is non-negative at every commit of a non-homogeneous loading path with
//   varying steps, and positive in total;
// - committed/trial discipline: a rejected step (begin_step, evaluations, begin_step again) leaves
//   the committed state as it was, bit for bit; the committed drivers are the long-term PK2 stress
//   at each tet's averaged F;
// - an elastic series is AveragedPressureTet; refused options.
#include "core/base/error.hpp"
#include "tensormass/testing/test_meshes.hpp"
#include "tensormass/viscoelastic/viscoelastic_law.hpp"
#include "tensormass/viscoelastic/viscoelastic_law_anp.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::tm {
namespace {

using testing::rel_err;
using Opt = ViscoelasticOptions;

PronySeries prony() { return PronySeries::from_long_term({0.8, 1.5}, {0.05, 0.7}); }

TEST(ViscoelasticLawAnp, HomogeneousRelaxationEqualsTheP1Model) {
  std::mt19937 rng(31);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  Mat3 G = Mat3::Zero();
  G(0, 0) = 0.3;
  G(1, 1) = -0.1;
  G(0, 2) = 0.15;
  for (const Law& law :
       {Law(NeoHookean::from_young_poisson(2000.0, 0.45)), Law(MooneyRivlin(300.0, 100.0, 8000.0)),
        Law(StVenantKirchhoff::from_young_poisson(2000.0, 0.3))}) {
    SCOPED_TRACE(law.name());
    ViscoelasticHyperelastic p1(m, law, prony());
    ViscoelasticAveragedPressureTet anp(m, law, prony());
    double t = 0.0;
    for (int step = 0; step < 12; ++step) {
      const double dt = 0.03 + 0.01 * step;
      t += dt;
      const double s = std::min(t / 0.2, 1.0);  // ramp to the stretch, then hold
      const VecX u = testing::affine_displacement(m, s * G, Vec3(0.1, 0.0, -0.2));
      p1.begin_step(dt);
      anp.begin_step(dt);
      VecX f1, f2;
      p1.internal_force(u, f1);
      anp.internal_force(u, f2);
      EXPECT_LT((f2 - f1).norm(), 1e-12 * f1.norm()) << step;
      EXPECT_LT(rel_err(anp.trial_potential(u), p1.trial_potential(u)), 1e-12) << step;
      EXPECT_LT(rel_err(anp.energy(u), p1.energy(u)), 1e-12) << step;
      p1.commit_step(u);
      anp.commit_step(u);
      EXPECT_LT(rel_err(anp.committed_branch_energy(), p1.committed_branch_energy()), 1e-12) << step;
      EXPECT_LT(rel_err(anp.total_dissipation(), p1.total_dissipation()), 1e-12) << step;
      EXPECT_LT(rel_err(anp.committed_elastic_energy(), p1.committed_elastic_energy()), 1e-12) << step;
      const std::vector<double> h1 = p1.committed_history(), h2 = anp.committed_history();
      ASSERT_EQ(h1.size(), h2.size());
      double dh = 0.0, nh = 0.0;
      for (std::size_t k = 0; k < h1.size(); ++k) {
        dh = std::max(dh, std::abs(h2[k] - h1[k]));
        nh = std::max(nh, std::abs(h1[k]));
      }
      EXPECT_LE(dh, 1e-12 * nh) << step;
    }
    EXPECT_GT(anp.total_dissipation(), 0.0);
  }
}

TEST(ViscoelasticLawAnp, ForceIsTheGradientOfTheTrialPotentialWithHistory) {
  std::mt19937 rng(32);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  for (const Law& law :
       {Law(Yeoh(200.0, 80.0, 10.0, 5000.0)), Law(NeoHookean::from_young_poisson(1000.0, 0.49))}) {
    SCOPED_TRACE(law.name());
    ViscoelasticAveragedPressureTet model(m, law, prony());
    for (int step = 0; step < 3; ++step) {
      model.begin_step(0.05);
      model.commit_step(testing::random_displacement(m.num_points(), 0.05, rng));
    }
    model.begin_step(0.07);
    const VecX u = testing::random_displacement(m.num_points(), 0.05, rng);
    // the volume ratios differ from 1: the averaging is at work
    double spread = 0.0;
    for (double r : model.elastic().volume_ratios(u)) spread = std::max(spread, std::abs(r - 1.0));
    EXPECT_GT(spread, 1e-3);
    for (int k = 0; k < 2; ++k) {
      const VecX v = testing::random_displacement(m.num_points(), 1.0, rng);
      VecX f, Kv;
      model.internal_force(u, f);
      const double h = 1e-4;
      auto W = [&](double s) { return model.trial_potential(u + s * v); };
      EXPECT_NEAR((-W(2 * h) + 8 * W(h) - 8 * W(-h) + W(-2 * h)) / (12 * h), f.dot(v),
                  1e-8 * f.norm() * v.norm());
      auto Fv = [&](double s) {
        VecX g;
        model.internal_force(u + s * v, g);
        return g;
      };
      const VecX fd = (-Fv(2 * h) + 8 * Fv(h) - 8 * Fv(-h) + Fv(-2 * h)) / (12 * h);
      model.tangent_apply(u, v, Kv);
      EXPECT_LT(rel_err(fd, Kv), 1e-7);
      SpMat K;
      model.tangent(u, K);
      EXPECT_LT(rel_err(VecX(K * v), Kv), 1e-13);
    }
  }
}

TEST(ViscoelasticLawAnp, StepDissipationIsNonNegative) {
  // A non-homogeneous path (a random field scaled up and back, then reversed) with varying steps,
  // for every integration rule: the branch energies are quadratic forms and the trapezoidal step
  // dissipation of non-negative rates, so it is >= 0 at every commit.
  std::mt19937 rng(33);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  const VecX shape = testing::random_displacement(m.num_points(), 0.05, rng);
  for (Opt::Integration integ :
       {Opt::Integration::Midpoint, Opt::Integration::ExactLinear, Opt::Integration::BackwardEuler}) {
    SCOPED_TRACE(Opt::to_string(integ));
    Opt o;
    o.integration = integ;
    ViscoelasticAveragedPressureTet model(m, NeoHookean::from_young_poisson(1000.0, 0.45), prony(), o);
    double total = 0.0;
    for (int step = 0; step < 30; ++step) {
      const double dt = 0.01 * (1 + step % 4);
      const double a = std::sin(0.3 * step);
      model.begin_step(dt);
      model.commit_step(a * shape);
      EXPECT_GE(model.step_dissipation(), 0.0) << step;
      EXPECT_GE(model.committed_dissipation_rate(), 0.0) << step;
      total += model.step_dissipation();
      EXPECT_DOUBLE_EQ(model.total_dissipation(), total);
    }
    EXPECT_GT(model.total_dissipation(), 0.0);
  }
}

TEST(ViscoelasticLawAnp, RejectedStepDoesNotChangeTheHistory) {
  std::mt19937 rng(34);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  const Law law = NeoHookean::from_young_poisson(1000.0, 0.4);
  ViscoelasticAveragedPressureTet a(m, law, prony()), b(m, law, prony());
  const VecX u0 = testing::random_displacement(m.num_points(), 0.03, rng);
  for (auto* mm : {&a, &b}) {
    mm->begin_step(0.1);
    mm->commit_step(u0);
  }
  const std::vector<double> before = a.committed_state();
  // a: a rejected attempt (evaluations at a trial state, never committed), then the retry
  a.begin_step(0.2);
  VecX f, Kv;
  SpMat K;
  const VecX bad = testing::random_displacement(m.num_points(), 0.05, rng);
  a.internal_force(bad, f);
  a.tangent(bad, K);
  a.tangent_apply(bad, bad, Kv);
  (void)a.energy(bad);
  (void)a.trial_potential(bad);
  EXPECT_EQ(a.committed_state(), before);
  const VecX u1 = testing::random_displacement(m.num_points(), 0.03, rng);
  a.begin_step(0.1);
  b.begin_step(0.1);
  a.commit_step(u1);
  b.commit_step(u1);
  EXPECT_EQ(a.committed_state(), b.committed_state());
  EXPECT_EQ(a.committed_history().size(), static_cast<std::size_t>(m.num_tets()) * 2 * 6);
  // the committed driver of each tet is the long-term PK2 stress at its averaged F
  const std::vector<Mat3> fbar = a.elastic().averaged_deformation_gradients(u1);
  const std::vector<double> x = a.committed_driver();
  for (std::size_t t = 0; t < fbar.size(); ++t) {
    double s[6];
    to_voigt(law.pk2_stress(0.5 * (fbar[t].transpose() * fbar[t] - Mat3::Identity())), s);
    for (int k = 0; k < 6; ++k) EXPECT_EQ(x[6 * t + static_cast<std::size_t>(k)], s[k]);
  }
}

TEST(ViscoelasticLawAnp, ElasticSeriesIsTheElasticModelAndBadOptionsAreRefused) {
  std::mt19937 rng(35);
  const Mesh m = testing::jittered_box(1, 0.5, 0.0, rng);
  const Law law = NeoHookean::from_young_poisson(1000.0, 0.4);
  ViscoelasticAveragedPressureTet ve(m, law, PronySeries::from_long_term({0.0}, {1.0}));
  const AveragedPressureTet el(m, law);
  const VecX u = testing::random_displacement(m.num_points(), 0.03, rng);
  ve.begin_step(0.1);
  VecX f1, f2;
  ve.internal_force(u, f1);
  el.internal_force(u, f2);
  EXPECT_EQ(f1, f2);
  EXPECT_EQ(ve.energy(u), el.energy(u));
  Opt o;
  o.history = Opt::History::NodalForce;
  EXPECT_THROW(ViscoelasticAveragedPressureTet(m, law, prony(), o), Error);
  o = Opt{};
  o.relaxation = Opt::Relaxation::Deviatoric;
  EXPECT_THROW(ViscoelasticAveragedPressureTet(m, law, prony(), o), Error);
  o = Opt{};
  o.fast_threads = 2;
  EXPECT_THROW(ViscoelasticAveragedPressureTet(m, law, prony(), o), Error);
}

}  // namespace
}  // namespace tmlab::tm
