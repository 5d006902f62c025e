// ViscoelasticHyperelastic (the pk2/full Prony scheme on a general law): for St VK it equals
// ViscoelasticStVK (pk2, full) to round-off over a history of steps; for the other laws the force is
// the gradient of the trial potential and the tangent the derivative of the force (finite
// differences, with committed history); a held finite deformation relaxes exactly as
// 1 + sum_j alpha_j exp(-t/tau_j) (the scheme is exact for a held strain); refused options.
#include "core/base/error.hpp"
#include "tensormass/testing/test_meshes.hpp"
#include "tensormass/viscoelastic/viscoelastic_law.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::tm {
namespace {

using testing::rel_err;
using Opt = ViscoelasticOptions;

PronySeries prony() { return PronySeries::from_long_term({0.8, 1.5}, {0.05, 0.7}); }

TEST(ViscoelasticLaw, StVenantKirchhoffEqualsViscoelasticStVK) {
  std::mt19937 rng(3);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  const auto mat = StVenantKirchhoff::from_young_poisson(2000.0, 0.4);
  for (Opt::Integration s :
       {Opt::Integration::Midpoint, Opt::Integration::ExactLinear, Opt::Integration::BackwardEuler}) {
    SCOPED_TRACE(Opt::to_string(s));
    Opt o;
    o.history = Opt::History::Pk2;
    o.integration = s;
    ViscoelasticHyperelastic a(m, mat, prony(), o);
    ViscoelasticStVK b(m, mat, prony(), o);
    for (int step = 0; step < 5; ++step) {
      const double dt = 0.02 * (step + 1);
      a.begin_step(dt);
      b.begin_step(dt);
      const VecX u = testing::random_displacement(m.num_points(), 0.04, rng);
      const VecX v = testing::random_displacement(m.num_points(), 1.0, rng);
      EXPECT_LT(rel_err(a.trial_gain(), b.trial_gain()), 1e-15);
      VecX fa, fb, ka, kb;
      a.internal_force(u, fa);
      b.internal_force(u, fb);
      EXPECT_LT(rel_err(fa, fb), 1e-12);
      a.tangent_apply(u, v, ka);
      b.tangent_apply(u, v, kb);
      EXPECT_LT(rel_err(ka, kb), 1e-12);
      SpMat Ka, Kb;
      a.tangent(u, Ka);
      b.tangent(u, Kb);
      EXPECT_LT(rel_err(Ka, Kb), 1e-12);
      EXPECT_LT(rel_err(a.trial_potential(u), b.trial_potential(u)), 1e-12);
      EXPECT_LT(rel_err(a.energy(u), b.energy(u)), 1e-12);
      a.commit_step(u);
      b.commit_step(u);
      EXPECT_LT(rel_err(a.committed_branch_energy(), b.committed_branch_energy()), 1e-12);
      EXPECT_LT(rel_err(a.total_dissipation(), b.total_dissipation()), 1e-12);
      EXPECT_GE(a.step_dissipation(), 0.0);
    }
  }
}

TEST(ViscoelasticLaw, ForceAndTangentAreDerivativesOfTheTrialPotential) {
  std::mt19937 rng(4);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  const std::vector<Law> laws = {NeoHookean::from_young_poisson(1000.0, 0.4),
                                 Ogden({300.0, -20.0}, {2.5, -2.0}, 5000.0), Yeoh(150.0, 80.0, 10.0, 5000.0)};
  for (const Law& law : laws) {
    SCOPED_TRACE(law.name());
    ViscoelasticHyperelastic model(m, law, prony());
    model.begin_step(0.03);
    model.commit_step(testing::random_displacement(m.num_points(), 0.05, rng));  // some history
    model.begin_step(0.1);
    const VecX u = testing::random_displacement(m.num_points(), 0.05, rng);
    VecX f;
    model.internal_force(u, f);
    for (int k = 0; k < 3; ++k) {
      const VecX v = testing::random_displacement(m.num_points(), 1.0, rng);
      const double h = 1e-4;
      auto W = [&](double s) { return model.trial_potential(u + s * v); };
      EXPECT_NEAR((-W(2 * h) + 8 * W(h) - 8 * W(-h) + W(-2 * h)) / (12 * h), f.dot(v),
                  1e-8 * f.norm() * v.norm());
      auto Fv = [&](double s) {
        VecX g;
        model.internal_force(u + s * v, g);
        return g;
      };
      VecX Kv;
      model.tangent_apply(u, v, Kv);
      EXPECT_LT(rel_err(VecX((-Fv(2 * h) + 8 * Fv(h) - 8 * Fv(-h) + Fv(-2 * h)) / (12 * h)), Kv), 1e-8);
      SpMat K;
      model.tangent(u, K);
      EXPECT_LT(rel_err(VecX(K * v), Kv), 1e-13);
    }
  }
}

TEST(ViscoelasticLaw, HeldFiniteDeformationRelaxesExactly) {
  // A homogeneous deformation (compression to J = 0.5 with shear) applied at t = 0 and held: every
  // scheme with a_j = exp(-dt/tau_j) (midpoint, the default; exact_linear) gives h_j = S_e exp(-t/tau_j)
  // at the step ends, so f(t) = (1 + sum_j alpha_j e^{-t/tau_j}) f_e.
  std::mt19937 rng(5);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  Mat3 G = Mat3::Zero();
  G(0, 0) = -0.5;
  G(1, 2) = 0.4;
  const VecX u = testing::affine_displacement(m, G, Vec3::Zero());
  const PronySeries p = prony();
  for (const Law& law :
       {Law(NeoHookean::from_young_poisson(1000.0, 0.45)), Law(VerondaWestmann(50.0, 3.0, 5000.0))}) {
    SCOPED_TRACE(law.name());
    ViscoelasticHyperelastic model(m, law, p);
    VecX fe;
    model.elastic().internal_force(u, fe);
    model.begin_step(0.0);
    model.commit_step(u);  // the jump, instantaneous response
    double t = 0.0;
    for (int step = 0; step < 20; ++step) {
      const double dt = 0.01 * (1 + step % 3);
      model.begin_step(dt);
      model.commit_step(u);
      t += dt;
      VecX f;
      model.internal_force(u, f);  // committed total force
      const double r = 1.0 + p.alpha(0) * std::exp(-t / p.tau(0)) + p.alpha(1) * std::exp(-t / p.tau(1));
      EXPECT_LT(rel_err(f, VecX(r * fe)), 1e-12) << "t = " << t;
    }
  }
}

TEST(ViscoelasticLaw, ElasticLimitAndRefusedOptions) {
  std::mt19937 rng(6);
  const Mesh m = testing::jittered_box(1, 1.0, 0.0, rng);
  const Law law = NeoHookean(2.0, 1.0);
  ViscoelasticHyperelastic el(m, law, PronySeries::from_long_term({0.0}, {1.0}));
  const VecX u = testing::random_displacement(m.num_points(), 0.05, rng);
  VecX f, fe;
  el.begin_step(0.1);
  el.internal_force(u, f);
  el.elastic().internal_force(u, fe);
  EXPECT_EQ((f - fe).norm(), 0.0);
  Opt o;
  o.history = Opt::History::NodalForce;
  try {
    ViscoelasticHyperelastic(m, law, prony(), o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("history 'nodal_force'"), std::string::npos) << e.what();
  }
  o.history = Opt::History::Pk2;
  o.relaxation = Opt::Relaxation::Deviatoric;
  EXPECT_THROW(ViscoelasticHyperelastic(m, law, prony(), o), Error);
}

}  // namespace
}  // namespace tmlab::tm
