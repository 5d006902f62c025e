// TensorMassStVK (corrected tensors, relative displacements) against the total-Lagrangian oracle:
// energy, force, tangent action, assembled tangent to <= 1e-12 relative, on random meshes, the
// liver mesh, after a rigid translation of 100 mesh sizes and a large rotation; rigid motions and
// the affine patch test; in-place tangent refill.
#include "core/mesh/gmsh_reader.hpp"
#include "tensormass/testing/tensor_mass_compare.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace tmlab::tm {
namespace {

using testing::compare_with_oracle;

constexpr double kTol = 1e-12;

StVenantKirchhoff liver_like() { return StVenantKirchhoff::from_young_poisson(3000.0, 0.45); }

TEST(TensorMass, MatchesOracleOnRandomTets) {
  std::mt19937 rng(21);
  const Mesh m = testing::random_tet_soup(200, 0.01, rng);
  const TensorMassStVK tm(m, liver_like());
  const TotalLagrangianStVK tl(m, liver_like());
  for (double amp : {1e-4, 1e-3, 3e-3}) {  // |grad u| ~ 0.02 .. 0.6
    const VecX u = testing::random_displacement(m.num_points(), amp, rng);
    const auto e = compare_with_oracle(tm, tl, u, "random tets, amp " + std::to_string(amp), rng);
    EXPECT_LT(e.max(), kTol);
    for (Index t = 0; t < 5; ++t) EXPECT_LT(testing::rel_err(tm.tet_energy(t, u), tl.tet_energy(t, u)), kTol);
  }
}

TEST(TensorMass, MatchesOracleOnJitteredBox) {
  std::mt19937 rng(22);
  const Mesh m = testing::jittered_box(8, 0.01, 0.25, rng);
  const TensorMassStVK tm(m, liver_like());
  const TotalLagrangianStVK tl(m, liver_like());
  const VecX u = testing::random_displacement(m.num_points(), 2e-3, rng);
  EXPECT_LT(compare_with_oracle(tm, tl, u, "jittered box 3072 tets", rng).max(), kTol);
}

TEST(TensorMass, MatchesOracleOnLiver) {
  namespace fs = std::filesystem;
  const std::string path = std::string(TMLAB_SOURCE_DIR) + "/meshes/liver.msh";
  ASSERT_TRUE(fs::exists(path)) << "missing " << path;
  const Mesh m = read_gmsh(path);
  std::mt19937 rng(23);
  const TensorMassStVK tm(m, liver_like());
  const TotalLagrangianStVK tl(m, liver_like());
  const double h = testing::mean_edge(m);
  const VecX u = testing::random_displacement(m.num_points(), 0.1 * h, rng);
  const auto e = compare_with_oracle(tm, tl, u, "liver " + std::to_string(m.num_tets()) + " tets", rng);
  EXPECT_LT(e.max(), kTol);
}

TEST(TensorMass, MatchesOracleAfterLargeTranslationAndRotation) {
  std::mt19937 rng(24);
  const auto [h, m, u] = testing::deformed_jittered_box(rng);
  const TensorMassStVK tm(m, liver_like());
  const TotalLagrangianStVK tl(m, liver_like());
  EXPECT_LT(compare_with_oracle(tm, tl, u, "deformed", rng).max(), kTol);
  VecX f0;
  tm.internal_force(u, f0);
  const double w0 = tm.energy(u);

  // rigid translation by 100 mesh sizes: same strain, same force
  const VecX ut = testing::rigidly_moved(m, u, Mat3::Identity(), 100.0 * h * Vec3(1, -2, 3).normalized());
  EXPECT_LT(compare_with_oracle(tm, tl, ut, "translated 100 h", rng).max(), kTol);
  VecX ft;
  tm.internal_force(ut, ft);
  std::printf("translated: |f - f0|/|f0| = %.1e, energy %.1e\n", testing::rel_err(ft, f0),
              testing::rel_err(tm.energy(ut), w0));
  EXPECT_LT(testing::rel_err(ft, f0), 1e-11);

  // large rotation (about 2.5 rad) of the deformed state: energy invariant, nodal forces rotate
  const Mat3 R = testing::rotation(Vec3(0.3, -1.0, 0.7), 2.5);
  const VecX ur = testing::rigidly_moved(m, u, R, Vec3(0.02, 0.0, -0.01));
  EXPECT_LT(compare_with_oracle(tm, tl, ur, "rotated 2.5 rad", rng).max(), kTol);
  VecX fr, f0rot(f0.size());
  tm.internal_force(ur, fr);
  for (Index i = 0; i < m.num_points(); ++i) f0rot.segment<3>(3 * i) = R * f0.segment<3>(3 * i);
  EXPECT_LT(testing::rel_err(fr, f0rot), 1e-12);
  EXPECT_LT(testing::rel_err(tm.energy(ur), w0), 1e-12);
}

TEST(TensorMass, RigidMotionsGiveZeroForce) {
  std::mt19937 rng(25);
  const double h = 0.01;
  const Mesh m = testing::jittered_box(4, h, 0.2, rng);
  const TensorMassStVK tm(m, liver_like());
  VecX fref;
  tm.internal_force(testing::random_displacement(m.num_points(), 0.5 * h, rng), fref);
  const VecX zero = VecX::Zero(tm.num_dofs());
  for (double angle : {0.0, 0.5, 1.5, 3.0}) {
    const VecX u =
        testing::rigidly_moved(m, zero, testing::rotation(Vec3(-1, 2, 0.5), angle), Vec3(0.1, 0.3, -0.2));
    VecX f;
    tm.internal_force(u, f);
    std::printf("rigid motion, angle %.1f: |f|/|f_ref| = %.1e, W = %.1e\n", angle, f.norm() / fref.norm(),
                tm.energy(u));
    EXPECT_LT(f.norm(), 1e-12 * fref.norm());
  }
}

TEST(TensorMass, AffinePatchTest) {
  std::mt19937 rng(26);
  const int n = 5;
  const double h = 0.01;
  const Mesh m = testing::jittered_box(n, h, 0.25, rng);
  const TensorMassStVK tm(m, liver_like());
  const TotalLagrangianStVK tl(m, liver_like());
  Mat3 G;
  G << 0.3, 0.1, -0.05, -0.1, 0.2, 0.15, 0.05, -0.2, -0.1;
  const VecX u = testing::affine_displacement(m, G, Vec3(0.01, -0.02, 0.03));
  // uniform Green strain: every tet has the same energy density W(E)
  const Mat3 F = Mat3::Identity() + G;
  const double wE = liver_like().energy_density(0.5 * (F.transpose() * F - Mat3::Identity()));
  double worst = 0.0;
  for (Index t = 0; t < tm.num_tets(); ++t)
    worst = std::max(worst, testing::rel_err(tm.tet_energy(t, u) / tl.rest(t).volume, wE));
  EXPECT_LT(worst, 1e-12);
  VecX f;
  tm.internal_force(u, f);
  double fmax = 0.0, finterior = 0.0;
  for (Index i = 0; i < m.num_points(); ++i) {
    const Vec3 X = m.points[static_cast<std::size_t>(i)];
    const bool interior = (X.array() > 1e-9).all() && (X.array() < n * h - 1e-9).all();
    fmax = std::max(fmax, f.segment<3>(3 * i).norm());
    if (interior) finterior = std::max(finterior, f.segment<3>(3 * i).norm());
  }
  std::printf("patch test: worst W/V rel. err %.1e, max interior |f| / max |f| = %.1e\n", worst,
              finterior / fmax);
  EXPECT_LT(finterior, 1e-12 * fmax);
}

TEST(TensorMass, TangentRefillsInPlace) {
  std::mt19937 rng(27);
  const Mesh m = testing::jittered_box(4, 0.01, 0.2, rng);
  const TensorMassStVK tm(m, liver_like());
  const TotalLagrangianStVK tl(m, liver_like());
  SpMat K;
  tm.tangent(testing::random_displacement(m.num_points(), 1e-3, rng), K);
  EXPECT_TRUE(tm.pattern().matches(K));
  const double* values = K.valuePtr();
  const VecX u = testing::random_displacement(m.num_points(), 1e-3, rng);
  tm.tangent(u, K);
  EXPECT_EQ(values, K.valuePtr());  // no reallocation
  SpMat Kref;
  tl.tangent(u, Kref);
  EXPECT_LT(testing::rel_err(K, Kref), kTol);
  EXPECT_LT(SpMat(K - SpMat(K.transpose())).norm(), 1e-14 * K.norm());
  SpMat other(5, 5);  // a matrix of the wrong shape gets the pattern
  tm.tangent(u, other);
  EXPECT_LT(testing::rel_err(other, Kref), kTol);
}

}  // namespace
}  // namespace tmlab::tm
