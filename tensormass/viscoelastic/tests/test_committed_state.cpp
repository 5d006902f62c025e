// Checkpoints of history models (issue 12): a model whose committed state is restored from
// committed_state() continues bit for bit like the one it was saved from (both viscoelastic
// models, both history forms, and the fast kernel's fused pass, which keeps the history in its lane
// order but saves it in mesh order); a state of the wrong size is refused, and an elastic model has
// none.
#include "core/base/error.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/testing/test_meshes.hpp"
#include "tensormass/viscoelastic/viscoelastic_law.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tmlab::tm {
namespace {

using Opt = ViscoelasticOptions;

bool same_bits(const VecX& a, const VecX& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

/// Steps `a` 4 times, saves, restores into `b` (fresh), then steps both 3 more times alike.
template <typename Model>
void check_continues_identically(Model& a, Model& b, const Mesh& m, std::mt19937& rng) {
  for (int step = 0; step < 4; ++step) {
    a.begin_step(0.01 * (step + 1));
    a.commit_step(testing::random_displacement(m.num_points(), 0.03, rng));
  }
  const std::vector<double> saved = a.committed_state();
  ASSERT_FALSE(saved.empty());
  b.restore_committed_state(saved);
  EXPECT_EQ(b.committed_state(), saved);
  EXPECT_EQ(b.trial_dt(), 0.0);
  for (int step = 0; step < 3; ++step) {
    const VecX u = testing::random_displacement(m.num_points(), 0.03, rng);
    VecX fa, fb;
    a.internal_force(u, fa);  // dt = 0 after commit/restore: the committed total force
    b.internal_force(u, fb);
    EXPECT_TRUE(same_bits(fa, fb)) << "step " << step;
    a.begin_step(0.02);
    b.begin_step(0.02);
    a.internal_force(u, fa);
    b.internal_force(u, fb);
    EXPECT_TRUE(same_bits(fa, fb)) << "step " << step;
    a.commit_step(u);
    b.commit_step(u);
    EXPECT_EQ(a.total_dissipation(), b.total_dissipation());
    EXPECT_EQ(a.committed_branch_energy(), b.committed_branch_energy());
  }
  EXPECT_EQ(a.committed_state(), b.committed_state());
  std::vector<double> wrong = saved;
  wrong.pop_back();
  EXPECT_THROW(b.restore_committed_state(wrong), Error);
}

TEST(CommittedState, ViscoelasticStVKContinuesBitForBit) {
  std::mt19937 rng(5);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  const auto mat = StVenantKirchhoff::from_young_poisson(2000.0, 0.4);
  const PronySeries prony = PronySeries::from_long_term({0.8, 1.5}, {0.05, 0.7});
  for (Opt::History h : {Opt::History::NodalForce, Opt::History::Pk2}) {
    Opt o;
    o.history = h;
    ViscoelasticStVK a(m, mat, prony, o), b(m, mat, prony, o);
    check_continues_identically(a, b, m, rng);
  }
}

TEST(CommittedState, FastKernelLaneOrderSavesAndRestoresInMeshOrder) {
  std::mt19937 rng(8);
  const Mesh m = testing::jittered_box(3, 0.5, 0.2, rng);  // 162 tets: the lane order has padding slots
  const auto mat = StVenantKirchhoff::from_young_poisson(2000.0, 0.4);
  const PronySeries prony = PronySeries::from_long_term({0.8, 1.5}, {0.05, 0.7});
  for (bool book : {false, true}) {  // false: the fused pass of the fast kernel
    Opt o;
    o.history = Opt::History::Pk2;
    o.energy_bookkeeping = book;
    ViscoelasticStVK ref(m, mat, prony, o);
    o.fast_threads = 1;
    ViscoelasticStVK a(m, mat, prony, o), b(m, mat, prony, o);
    o.fast_threads = 3;
    ViscoelasticStVK c(m, mat, prony, o);
    VecX f;
    for (int step = 0; step < 4; ++step) {
      const VecX u = testing::random_displacement(m.num_points(), 0.03, rng);
      for (ViscoelasticStVK* x : {&ref, &a}) {
        x->begin_step(0.01);
        x->force_and_commit(u, f);
      }
    }
    // mesh order: the reference model's layout, value for value (to round-off: another kernel)
    const std::vector<double> saved = a.committed_state(), saved_ref = ref.committed_state();
    ASSERT_EQ(saved.size(), saved_ref.size());
    double d = 0.0, n = 0.0;
    for (std::size_t k = 0; k + 5 < saved.size(); ++k) {
      d = std::max(d, std::abs(saved[k] - saved_ref[k]));
      n = std::max(n, std::abs(saved_ref[k]));
    }
    EXPECT_LE(d, 1e-12 * n) << "book " << book;
    // the same bytes through a model of the other storage order and back
    ViscoelasticStVK plain(m, mat, prony, ref.options());
    plain.restore_committed_state(saved);
    EXPECT_EQ(plain.committed_state(), saved);
    b.restore_committed_state(plain.committed_state());
    c.restore_committed_state(saved);
    EXPECT_EQ(b.committed_state(), saved);
    EXPECT_EQ(b.committed_history(), a.committed_history());
    EXPECT_EQ(b.committed_driver(), a.committed_driver());
    // the restored models continue bit for bit, whatever their thread count
    for (int step = 0; step < 3; ++step) {
      const VecX u = testing::random_displacement(m.num_points(), 0.03, rng);
      VecX fa, fb, fc;
      for (ViscoelasticStVK* x : {&a, &b, &c}) x->begin_step(0.02);
      a.force_and_commit(u, fa);
      b.force_and_commit(u, fb);
      c.force_and_commit(u, fc);
      EXPECT_TRUE(same_bits(fa, fb)) << "step " << step << " book " << book;
      EXPECT_TRUE(same_bits(fa, fc)) << "step " << step << " book " << book;
    }
    EXPECT_EQ(a.committed_state(), b.committed_state());
    EXPECT_EQ(a.committed_state(), c.committed_state());
  }
}

TEST(CommittedState, ViscoelasticHyperelasticContinuesBitForBit) {
  std::mt19937 rng(6);
  const Mesh m = testing::jittered_box(2, 0.5, 0.2, rng);
  const auto mat = StVenantKirchhoff::from_young_poisson(2000.0, 0.4);
  const PronySeries prony = PronySeries::from_long_term({0.8, 1.5}, {0.05, 0.7});
  ViscoelasticHyperelastic a(m, mat, prony), b(m, mat, prony);
  check_continues_identically(a, b, m, rng);
}

TEST(CommittedState, ElasticModelHasNone) {
  std::mt19937 rng(7);
  const Mesh m = testing::jittered_box(1, 0.5, 0.1, rng);
  TensorMassStVK model(m, StVenantKirchhoff::from_young_poisson(2000.0, 0.4));
  EXPECT_TRUE(model.committed_state().empty());
  model.restore_committed_state({});
  EXPECT_THROW(model.restore_committed_state({1.0}), Error);
}

}  // namespace
}  // namespace tmlab::tm
