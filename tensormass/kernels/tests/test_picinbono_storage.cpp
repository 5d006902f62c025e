// Picinbono's mesh-level storage on absolute displacements (the paper's form) against the relative
// per-tet form: equal at round-off near the rest position, catastrophic cancellation after a large
// rigid translation (the force must not change at all under translation).
#include "tensormass/kernels/picinbono_storage.hpp"
#include "tensormass/testing/tensor_mass_compare.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm {
namespace {

using testing::rel_err;

StVenantKirchhoff liver_like() { return StVenantKirchhoff::from_young_poisson(3000.0, 0.45); }

TEST(PicinbonoStorage, EntityCountsOfAKuhnCube) {
  std::mt19937 rng(51);
  const int n = 3;
  const Mesh m = testing::jittered_box(n, 0.01, 0.0, rng);
  const PicinbonoAbsoluteStVK pic(m, liver_like());
  EXPECT_EQ(pic.num_nodes(), (n + 1) * (n + 1) * (n + 1));
  EXPECT_EQ(pic.num_tets(), 6u * n * n * n);
  // Euler characteristic of a ball: V - E + F - T = 1
  const long chi = pic.num_nodes() - static_cast<long>(pic.num_edges()) +
                   static_cast<long>(pic.num_triangles()) - static_cast<long>(pic.num_tets());
  EXPECT_EQ(chi, 1);
  std::printf("%ld tets: storage %zu bytes (%.0f B/tet)\n", static_cast<long>(pic.num_tets()),
              pic.storage_bytes(),
              static_cast<double>(pic.storage_bytes()) / static_cast<double>(pic.num_tets()));
}

TEST(PicinbonoStorage, EqualsRelativeFormAtRestScale) {
  std::mt19937 rng(52);
  const double h = 0.01;
  const Mesh m = testing::jittered_box(6, h, 0.25, rng);
  const PicinbonoAbsoluteStVK pic(m, liver_like());
  const TensorMassStVK tm(m, liver_like());
  const TotalLagrangianStVK tl(m, liver_like());
  for (double amp : {0.01, 0.1}) {
    const VecX u = testing::random_displacement(m.num_points(), amp * h, rng);
    VecX fp, ft, fo;
    pic.internal_force(u, fp);
    tm.internal_force(u, ft);
    tl.internal_force(u, fo);
    std::printf("amp %.2f h: Picinbono vs relative: energy %.1e force %.1e; vs oracle: force %.1e\n", amp,
                rel_err(pic.energy(u), tm.energy(u)), rel_err(fp, ft), rel_err(fp, fo));
    EXPECT_LT(rel_err(pic.energy(u), tm.energy(u)), 1e-12);
    EXPECT_LT(rel_err(fp, ft), 1e-12);
    EXPECT_LT(rel_err(fp, fo), 1e-12);
  }
}

TEST(PicinbonoStorage, LosesDigitsAfterLargeTranslation) {
  std::mt19937 rng(53);
  const auto [h, m, u] = testing::deformed_jittered_box(rng);
  const PicinbonoAbsoluteStVK pic(m, liver_like());
  const TensorMassStVK tm(m, liver_like());
  VecX f0;
  tm.internal_force(u, f0);  // the exact answer for every translated copy of u
  const double w0 = tm.energy(u);
  const Vec3 dir = Vec3(1.0, 0.6, -0.8).normalized();
  for (double shift : {1e1, 1e2, 1e3, 1e4}) {
    const VecX ut = testing::rigidly_moved(m, u, Mat3::Identity(), shift * h * dir);
    VecX fp, ft;
    pic.internal_force(ut, fp);
    tm.internal_force(ut, ft);
    const double ep = rel_err(fp, f0), et = rel_err(ft, f0);
    const double wp = rel_err(pic.energy(ut), w0), wt = rel_err(tm.energy(ut), w0);
    std::printf("translation %.0e h: force rel. err. Picinbono %.1e relative %.1e | energy %.1e vs %.1e\n",
                shift, ep, et, wp, wt);
    EXPECT_LT(et, 1e-14 * (1.0 + shift));  // relative form: round-off of the input U only
    if (shift >= 1e3) {
      EXPECT_GT(ep, 100.0 * et);
      EXPECT_GT(ep, 1e-6);
      EXPECT_GT(wp, 1e-6);
    }
  }
}

}  // namespace
}  // namespace tmlab::tm
