// ViscoelasticBase, the step and commit bookkeeping both viscoelastic models share, through each of
// them (ViscoelasticStVK with both histories, ViscoelasticHyperelastic): the trial factors and gain
// of begin_step; a step size below zero or not finite refused; trial evaluations and rejected steps
// never touch the committed history (only an accepted step advances it); the trapezoidal
// dissipation and its total; the lazily computed committed spring energy; an elastic series and
// bookkeeping switched off.
#include "core/base/error.hpp"
#include "tensormass/testing/test_meshes.hpp"
#include "tensormass/viscoelastic/viscoelastic_law.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

namespace tmlab::tm {
namespace {

using Opt = ViscoelasticOptions;

struct Fixture {
  std::mt19937 rng{11};
  Mesh mesh = testing::jittered_box(2, 0.5, 0.2, rng);
  StVenantKirchhoff mat = StVenantKirchhoff::from_young_poisson(2000.0, 0.4);

  /// The three model variants on the same mesh: StVK nodal_force, StVK pk2, the general-law model.
  std::vector<std::unique_ptr<ViscoelasticBase>> models(const PronySeries& prony, Opt o = {}) const {
    std::vector<std::unique_ptr<ViscoelasticBase>> m;
    o.history = Opt::History::NodalForce;
    m.push_back(std::make_unique<ViscoelasticStVK>(mesh, mat, prony, o));
    o.history = Opt::History::Pk2;
    m.push_back(std::make_unique<ViscoelasticStVK>(mesh, mat, prony, o));
    m.push_back(std::make_unique<ViscoelasticHyperelastic>(mesh, mat, prony, o));
    return m;
  }
  VecX displacement(double scale) { return testing::random_displacement(mesh.num_points(), scale, rng); }
};

PronySeries two_terms() { return PronySeries::from_long_term({0.8, 1.5}, {0.05, 0.7}); }

TEST(ViscoelasticBase, BeginStepSetsFactorsAndGain) {
  Fixture fx;
  const PronySeries prony = two_terms();
  for (Opt::Integration s :
       {Opt::Integration::Midpoint, Opt::Integration::ExactLinear, Opt::Integration::BackwardEuler}) {
    Opt o;
    o.integration = s;
    for (auto& m : fx.models(prony, o)) {
      EXPECT_EQ(m->trial_dt(), 0.0);
      m->begin_step(0.03);
      EXPECT_EQ(m->trial_dt(), 0.03);
      double g = 0.0;
      for (std::size_t j = 0; j < prony.size(); ++j)
        g += prony.alpha(j) * recursion_factors(s, 0.03, prony.tau(j)).c;
      EXPECT_EQ(m->trial_gain(), g) << Opt::to_string(s);
      EXPECT_LT(m->trial_gain(), prony.alpha_sum());  // c_j < 1 for dt > 0
      m->commit_step(fx.displacement(0.02));
      EXPECT_EQ(m->trial_dt(), 0.0);  // a commit resets the trial step to dt = 0: c_j = 1
      EXPECT_DOUBLE_EQ(m->trial_gain(), prony.alpha_sum());
    }
  }
}

TEST(ViscoelasticBase, RefusesNegativeOrNonFiniteStep) {
  Fixture fx;
  for (auto& m : fx.models(two_terms())) {
    for (double dt :
         {-1e-3, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
      EXPECT_THROW(m->begin_step(dt), Error) << dt;
    EXPECT_NO_THROW(m->begin_step(0.0));
  }
}

TEST(ViscoelasticBase, OnlyAnAcceptedStepAdvancesTheHistory) {
  Fixture fx;
  const PronySeries prony = two_terms();
  auto a = fx.models(prony), b = fx.models(prony);
  const VecX u1 = fx.displacement(0.03), u2 = fx.displacement(0.03), trial = fx.displacement(0.05);
  for (std::size_t i = 0; i < a.size(); ++i) {
    a[i]->begin_step(0.02);
    a[i]->commit_step(u1);
    b[i]->begin_step(0.02);
    b[i]->commit_step(u1);
    const std::vector<double> hist = a[i]->committed_history(), driver = a[i]->committed_driver();
    // a: a rejected attempt (dt = 0.05, evaluated, never committed), then the retry with dt = 0.01.
    a[i]->begin_step(0.05);
    VecX f;
    a[i]->internal_force(trial, f);
    (void)a[i]->energy(trial);
    SpMat K;
    a[i]->tangent(trial, K);
    EXPECT_EQ(a[i]->committed_history(), hist) << "model " << i;
    EXPECT_EQ(a[i]->committed_driver(), driver) << "model " << i;
    a[i]->begin_step(0.01);
    a[i]->commit_step(u2);
    b[i]->begin_step(0.01);
    b[i]->commit_step(u2);
    EXPECT_NE(a[i]->committed_history(), hist) << "model " << i;
    EXPECT_EQ(a[i]->committed_history(), b[i]->committed_history()) << "model " << i;
    EXPECT_EQ(a[i]->committed_driver(), b[i]->committed_driver()) << "model " << i;
    EXPECT_EQ(a[i]->total_dissipation(), b[i]->total_dissipation()) << "model " << i;
    EXPECT_EQ(a[i]->committed_state(), b[i]->committed_state()) << "model " << i;
  }
}

TEST(ViscoelasticBase, TrapezoidalDissipationAndLazySpringEnergy) {
  Fixture fx;
  for (auto& m : fx.models(two_terms())) {
    double total = 0.0;
    for (int step = 0; step < 4; ++step) {
      const double dt = 0.01 * (step + 1);
      const double rate_before = m->committed_dissipation_rate();
      const VecX u = fx.displacement(0.03);
      m->begin_step(dt);
      m->commit_step(u);
      EXPECT_GT(m->committed_dissipation_rate(), 0.0);
      EXPECT_GT(m->committed_branch_energy(), 0.0);
      EXPECT_EQ(m->step_dissipation(), 0.5 * dt * (rate_before + m->committed_dissipation_rate()));
      total += m->step_dissipation();
      EXPECT_EQ(m->total_dissipation(), total);
      // The committed spring is W_e(u) of the last commit, computed when asked for.
      const double we = dynamic_cast<ViscoelasticStVK*>(m.get())
                            ? dynamic_cast<ViscoelasticStVK*>(m.get())->elastic().energy(u)
                            : dynamic_cast<ViscoelasticHyperelastic*>(m.get())->elastic().energy(u);
      EXPECT_EQ(m->committed_elastic_energy(), we);
      EXPECT_GT(we, 0.0);
    }
  }
}

TEST(ViscoelasticBase, ElasticSeriesAndBookkeepingOff) {
  Fixture fx;
  for (auto& m : fx.models(PronySeries::from_long_term({0.0, 0.0}, {0.1, 1.0}))) {
    m->begin_step(0.05);
    EXPECT_EQ(m->trial_gain(), 0.0);
    m->commit_step(fx.displacement(0.03));
    EXPECT_EQ(m->trial_dt(), 0.0);
    EXPECT_EQ(m->step_dissipation(), 0.0);
    for (double h : m->committed_history()) EXPECT_EQ(h, 0.0);
    EXPECT_GT(m->committed_elastic_energy(), 0.0);
  }
  Opt o;
  o.energy_bookkeeping = false;
  for (auto& m : fx.models(two_terms(), o)) {
    m->begin_step(0.05);
    m->commit_step(fx.displacement(0.03));
    EXPECT_EQ(m->committed_elastic_energy(), 0.0);
    EXPECT_EQ(m->committed_branch_energy(), 0.0);
    EXPECT_EQ(m->total_dissipation(), 0.0);
    bool moved = false;
    for (double h : m->committed_history()) moved = moved || h != 0.0;
    EXPECT_TRUE(moved);  // the history advances without the bookkeeping
  }
}

}  // namespace
}  // namespace tmlab::tm
