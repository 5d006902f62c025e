// TensorMassStVK against the oracle on a 196,608-tet cube (32^3 hexes x 6 tets), jittered, at a
// finite random deformation: energy, force, tangent action, assembled tangent (refilled in place).
#include "tensormass/testing/tensor_mass_compare.hpp"

#include <gtest/gtest.h>

#include <chrono>

namespace tmlab::tm {
namespace {

TEST(TensorMassLarge, MatchesOracleOn200kTetCube) {
  std::mt19937 rng(31);
  const double h = 1e-3;
  const Mesh m = testing::jittered_box(32, h, 0.2, rng);
  ASSERT_EQ(m.num_tets(), 196608);
  const auto mat = StVenantKirchhoff::from_young_poisson(3000.0, 0.45);
  const auto t0 = std::chrono::steady_clock::now();
  const TensorMassStVK tm(m, mat);
  const auto t1 = std::chrono::steady_clock::now();
  const TotalLagrangianStVK tl(m, mat);
  std::printf("setup: tensor-mass %.3f s (tensors + tangent pattern)\n",
              std::chrono::duration<double>(t1 - t0).count());
  const VecX u = testing::random_displacement(m.num_points(), 0.1 * h, rng);
  const auto e = testing::compare_with_oracle(tm, tl, u, "cube 196608 tets", rng);
  EXPECT_LT(e.max(), 1e-12);

  // second tangent call refills the same storage
  SpMat K;
  tm.tangent(u, K);
  const double* values = K.valuePtr();
  const auto t2 = std::chrono::steady_clock::now();
  tm.tangent(u, K);
  const auto t3 = std::chrono::steady_clock::now();
  EXPECT_EQ(values, K.valuePtr());
  std::printf("tangent refill: %.3f s, nnz %ld\n", std::chrono::duration<double>(t3 - t2).count(),
              static_cast<long>(K.nonZeros()));
}

}  // namespace
}  // namespace tmlab::tm
