// ViscoelasticHyperelasticP2 (the pk2/full Prony scheme at the quadrature points of 10-node tets):
// - a homogeneous stretch ramped and held relaxes exactly as the P1 model's (homogeneous states are
//   exact on both): restricted forces, trial potentials and committed energies equal to round-off;
// - the force is the gradient of the trial potential and the tangent the derivative of the force
//   (finite differences, with committed history, both volumetric variants);
// - committed/trial discipline: a rejected step (begin_step, evaluations, begin_step again) leaves
//   the committed state as it was, bit for bit;
// - an elastic series is HyperelasticP2; refused options;
// - the per-slot driver (one point's F) and the per-tet energy give the values of the full
//   kinematics bit for bit.
#include "core/base/error.hpp"
#include "tensormass/testing/test_meshes.hpp"
#include "tensormass/viscoelastic/viscoelastic_law.hpp"
#include "tensormass/viscoelastic/viscoelastic_law_p2.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::tm {
namespace {

using testing::rel_err;
using Opt = ViscoelasticOptions;

PronySeries prony() { return PronySeries::from_long_term({0.8, 1.5}, {0.05, 0.7}); }

VecX to_quadratic(const QuadraticMesh& qm, const VecX& u1) {
  const std::vector<double> v(u1.data(), u1.data() + u1.size());
  const std::vector<double> w = interpolate_to_quadratic(qm, v, 3);
  return Eigen::Map<const VecX>(w.data(), static_cast<Eigen::Index>(w.size()));
}

/// The P1 force of the P2 force (restriction: f_v + 1/2 sum of the midside forces of its edges).
VecX restrict_to_vertices(const QuadraticMesh& qm, const VecX& f2) {
  VecX r = f2.head(3 * qm.num_vertices);
  for (Index e = 0; e < qm.num_edges(); ++e)
    for (Index v : qm.edges[static_cast<std::size_t>(e)])
      r.segment<3>(3 * v) += 0.5 * f2.segment<3>(3 * (qm.num_vertices + e));
  return r;
}

TEST(ViscoelasticLawP2, HomogeneousRelaxationEqualsTheP1Model) {
  std::mt19937 rng(21);
  const Mesh lin = testing::jittered_box(2, 0.5, 0.2, rng);
  const QuadraticMesh qm = make_quadratic(lin);
  Mat3 G = Mat3::Zero();
  G(0, 0) = 0.3;
  G(1, 1) = -0.1;
  G(0, 2) = 0.15;
  for (P2Options::Volumetric vol : {P2Options::Volumetric::Standard, P2Options::Volumetric::MeanDilatation})
    for (const Law& law :
         {Law(NeoHookean::from_young_poisson(2000.0, 0.45)), Law(MooneyRivlin(300.0, 100.0, 8000.0))}) {
      SCOPED_TRACE(P2Options::to_string(vol) + ", " + law.name());
      P2Options po;
      po.volumetric = vol;
      ViscoelasticHyperelastic p1(lin, law, prony());
      ViscoelasticHyperelasticP2 p2(qm, law, prony(), {}, po);
      double t = 0.0;
      for (int step = 0; step < 12; ++step) {
        const double dt = 0.03 + 0.01 * step;
        t += dt;
        const double s = std::min(t / 0.2, 1.0);  // ramp to the stretch, then hold
        const VecX u1 = testing::affine_displacement(lin, s * G, Vec3(0.1, 0.0, -0.2));
        const VecX u2 = to_quadratic(qm, u1);
        p1.begin_step(dt);
        p2.begin_step(dt);
        VecX f1, f2;
        p1.internal_force(u1, f1);
        p2.internal_force(u2, f2);
        EXPECT_LT((restrict_to_vertices(qm, f2) - f1).norm(), 1e-12 * f1.norm()) << step;
        EXPECT_LT(rel_err(p2.trial_potential(u2), p1.trial_potential(u1)), 1e-12) << step;
        EXPECT_LT(rel_err(p2.energy(u2), p1.energy(u1)), 1e-12) << step;
        p1.commit_step(u1);
        p2.commit_step(u2);
        EXPECT_LT(rel_err(p2.committed_branch_energy(), p1.committed_branch_energy()), 1e-12) << step;
        EXPECT_LT(rel_err(p2.total_dissipation(), p1.total_dissipation()), 1e-12) << step;
        EXPECT_LT(rel_err(p2.committed_elastic_energy(), p1.committed_elastic_energy()), 1e-12) << step;
        // a homogeneous state: every tet has the same mean total stress
        const Mat3 S0 = p2.mean_pk2_stress(0, u2);
        EXPECT_LT((p2.mean_pk2_stress(5, u2) - S0).norm(), 1e-12 * S0.norm()) << step;
      }
      EXPECT_GT(p2.total_dissipation(), 0.0);
    }
}

TEST(ViscoelasticLawP2, ForceIsTheGradientOfTheTrialPotentialWithHistory) {
  std::mt19937 rng(22);
  const QuadraticMesh qm = make_quadratic(testing::jittered_box(2, 0.5, 0.2, rng));
  for (P2Options::Volumetric vol : {P2Options::Volumetric::Standard, P2Options::Volumetric::MeanDilatation}) {
    SCOPED_TRACE(P2Options::to_string(vol));
    P2Options po;
    po.volumetric = vol;
    ViscoelasticHyperelasticP2 model(qm, Yeoh(200.0, 80.0, 10.0, 5000.0), prony(), {}, po);
    for (int step = 0; step < 3; ++step) {
      model.begin_step(0.05);
      model.commit_step(testing::random_displacement(qm.num_points(), 0.03, rng));
    }
    model.begin_step(0.07);
    const VecX u = testing::random_displacement(qm.num_points(), 0.03, rng);
    const VecX v = testing::random_displacement(qm.num_points(), 1.0, rng);
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

TEST(ViscoelasticLawP2, RejectedStepDoesNotChangeTheHistory) {
  std::mt19937 rng(23);
  const QuadraticMesh qm = make_quadratic(testing::jittered_box(1, 0.5, 0.0, rng));
  const Law law = NeoHookean::from_young_poisson(1000.0, 0.4);
  ViscoelasticHyperelasticP2 a(qm, law, prony()), b(qm, law, prony());
  const VecX u0 = testing::random_displacement(qm.num_points(), 0.03, rng);
  for (auto* m : {&a, &b}) {
    m->begin_step(0.1);
    m->commit_step(u0);
  }
  const std::vector<double> before = a.committed_state();
  // a: a rejected attempt (evaluations at a trial state, never committed), then the retry
  a.begin_step(0.2);
  VecX f;
  SpMat K;
  const VecX bad = testing::random_displacement(qm.num_points(), 0.05, rng);
  a.internal_force(bad, f);
  a.tangent(bad, K);
  (void)a.energy(bad);
  EXPECT_EQ(a.committed_state(), before);
  const VecX u1 = testing::random_displacement(qm.num_points(), 0.03, rng);
  a.begin_step(0.1);
  b.begin_step(0.1);
  a.commit_step(u1);
  b.commit_step(u1);
  EXPECT_EQ(a.committed_state(), b.committed_state());
  EXPECT_EQ(a.committed_history().size(), static_cast<std::size_t>(qm.num_tets()) * 14 * 2 * 6);
}

TEST(ViscoelasticLawP2, PointDriverAndTetEnergyEqualTheFullKinematics) {
  // The base's energy loop calls driver() per slot (one point's F, or the tet's kinematics with mean
  // dilatation); the model's own energy() evaluates the kinematics once per tet. Equal bit for bit,
  // and so is each point's F to the kinematics' F_q.
  std::mt19937 rng(25);
  const QuadraticMesh qm = make_quadratic(testing::jittered_box(2, 0.5, 0.2, rng));
  for (P2Options::Volumetric vol : {P2Options::Volumetric::Standard, P2Options::Volumetric::MeanDilatation}) {
    SCOPED_TRACE(P2Options::to_string(vol));
    P2Options po;
    po.volumetric = vol;
    ViscoelasticHyperelasticP2 model(qm, NeoHookean::from_young_poisson(1000.0, 0.45), prony(), {}, po);
    for (int step = 0; step < 3; ++step) {
      model.begin_step(0.05);
      model.commit_step(testing::random_displacement(qm.num_points(), 0.03, rng));
    }
    model.begin_step(0.07);
    const VecX u = testing::random_displacement(qm.num_points(), 0.03, rng);
    const double e = model.energy(u);
    EXPECT_EQ(e, model.ViscoelasticBase::energy(u));
    EXPECT_GT(e, model.elastic().energy(u));  // the branches hold energy
    for (Index t = 0; t < model.num_tets(); ++t) {
      const HyperelasticP2::TetKinematics k = model.elastic().kinematics(t, u);
      for (int q = 0; q < model.num_points_per_tet(); ++q)
        EXPECT_EQ(model.elastic().point_deformation_gradient(t, q, u), k.F[static_cast<std::size_t>(q)]);
    }
  }
}

TEST(ViscoelasticLawP2, ElasticSeriesIsTheElasticModelAndBadOptionsAreRefused) {
  std::mt19937 rng(24);
  const QuadraticMesh qm = make_quadratic(testing::jittered_box(1, 0.5, 0.0, rng));
  const Law law = NeoHookean::from_young_poisson(1000.0, 0.4);
  ViscoelasticHyperelasticP2 ve(qm, law, PronySeries::from_long_term({0.0}, {1.0}));
  const HyperelasticP2 el(qm, law);
  const VecX u = testing::random_displacement(qm.num_points(), 0.03, rng);
  ve.begin_step(0.1);
  VecX f1, f2;
  ve.internal_force(u, f1);
  el.internal_force(u, f2);
  EXPECT_EQ(f1, f2);
  Opt o;
  o.history = Opt::History::NodalForce;
  EXPECT_THROW(ViscoelasticHyperelasticP2(qm, law, prony(), o), Error);
  o = Opt{};
  o.relaxation = Opt::Relaxation::Deviatoric;
  EXPECT_THROW(ViscoelasticHyperelasticP2(qm, law, prony(), o), Error);
}

}  // namespace
}  // namespace tmlab::tm
