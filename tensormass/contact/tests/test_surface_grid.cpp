// Boundary-surface extraction and the candidate-search grid: tributary areas add up to the surface
// area, and on jittered, deformed boxes of 24,576 and 105,456 tets the grid returns exactly the nodes
// a brute-force scan returns, for boxes and for the bodies' near regions, before and after refit().
#include "tensormass/contact/rigid_body.hpp"
#include "tensormass/contact/surface_grid.hpp"
#include "tensormass/testing/test_meshes.hpp"

#include "core/mesh/mesh_generator.hpp"

#include <gtest/gtest.h>

#include <random>

namespace tmlab::tm {
namespace {

TEST(ContactSurface, TributaryAreasSumToTheSurfaceArea) {
  const Mesh mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(1.0, 2.0, 3.0), 3, 4, 5);
  const ContactSurface s = ContactSurface::extract(mesh);
  double total = 0.0;
  for (double a : s.area) total += a;
  EXPECT_NEAR(total, 2.0 * (1 * 2 + 1 * 3 + 2 * 3), 1e-12);
  // Projected on the normal of a body pressing from above (-z) or from the x = 0 side (+x), only the
  // faces facing that body count: the top face (1 x 2), the x = 0 face (2 x 3).
  double top = 0.0, side = 0.0;
  for (Index k = 0; k < s.size(); ++k) {
    top += s.contact_area(k, -Vec3::UnitZ());
    side += s.contact_area(k, Vec3::UnitX());
  }
  EXPECT_NEAR(top, 2.0, 1e-12);
  EXPECT_NEAR(side, 6.0, 1e-12);
  // Nodes of a 4x5x6-point grid minus the 2x3x4 interior ones.
  EXPECT_EQ(s.size(), 4 * 5 * 6 - 2 * 3 * 4);
  for (Index n = 0; n < mesh.num_points(); ++n) {
    const Index k = s.local[static_cast<std::size_t>(n)];
    if (k >= 0) {
      EXPECT_EQ(s.nodes[static_cast<std::size_t>(k)], n);
    }
  }
}

std::vector<Index> brute_force(const Mesh& mesh, const ContactSurface& s, const VecX& u, const Vec3& lo,
                               const Vec3& hi) {
  std::vector<Index> out;
  for (Index k = 0; k < s.size(); ++k) {
    const Index n = s.nodes[static_cast<std::size_t>(k)];
    const Vec3 x = mesh.points[static_cast<std::size_t>(n)] + u.segment<3>(3 * n);
    if ((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all()) out.push_back(k);
  }
  return out;
}

/// On a jittered box of n^3 x 6 tets (side 0.16 m whatever n), randomly displaced: the grid returns
/// exactly the brute-force candidate sets for random boxes, the near regions of a sphere, a rounded
/// punch, a plane and an oblique plane, before and after a deformation and refit().
void check_grid_against_brute_force(int n, unsigned seed, Index min_tets) {
  std::mt19937 rng(seed);
  const Mesh mesh = testing::jittered_box(n, 0.16 / n, 0.2, rng);
  ASSERT_GE(mesh.num_tets(), min_tets);
  const ContactSurface s = ContactSurface::extract(mesh);
  VecX u = testing::random_displacement(mesh.num_points(), 0.002, rng);
  SurfaceGrid grid(mesh, s, u);
  EXPECT_GT(grid.dims()[0] * grid.dims()[1] * grid.dims()[2], 8);

  const std::vector<RigidBody> bodies = {
      RigidBody::sphere("s", Vec3(0.08, 0.08, 0.2), 0.05),
      RigidBody::punch("p", Vec3(0.05, 0.1, 0.165), Vec3(0, 0, -1), 0.04, 0.005),
      RigidBody::plane("z", Vec3(0, 0, 0.158), Vec3(0, 0, -1)),
      RigidBody::plane("oblique", Vec3(0, 0, 0.15), Vec3(0.3, 0, -1))};
  std::uniform_real_distribution<double> U(-0.02, 0.18);
  std::size_t total = 0;
  for (int pass = 0; pass < 2; ++pass) {
    for (int q = 0; q < 30; ++q) {
      Vec3 a(U(rng), U(rng), U(rng)), b(U(rng), U(rng), U(rng));
      const Vec3 lo = a.cwiseMin(b), hi = a.cwiseMax(b);
      const auto got = grid.query(lo, hi);
      EXPECT_EQ(got, brute_force(mesh, s, u, lo, hi)) << "box query " << q << " pass " << pass;
      total += got.size();
    }
    for (const RigidBody& body : bodies) {
      const double margin = 0.004;
      Vec3 lo, hi;
      body.bounding_box(0.0, margin, lo, hi);
      std::vector<Index> got, want;
      for (Index k : grid.query(lo, hi)) {
        const Index i = s.nodes[static_cast<std::size_t>(k)];
        if (body.gap(mesh.points[static_cast<std::size_t>(i)] + u.segment<3>(3 * i), 0.0).g <= margin)
          got.push_back(k);
      }
      for (Index k = 0; k < s.size(); ++k) {
        const Index i = s.nodes[static_cast<std::size_t>(k)];
        if (body.gap(mesh.points[static_cast<std::size_t>(i)] + u.segment<3>(3 * i), 0.0).g <= margin)
          want.push_back(k);
      }
      EXPECT_EQ(got, want) << body.name << " pass " << pass;
      if (pass == 0) {
        EXPECT_FALSE(want.empty()) << body.name;
      }
    }
    // Deform further (a shear and a squash) and refit: the same cell size, new bins.
    const double cell = grid.cell_size();
    for (Index i = 0; i < mesh.num_points(); ++i) {
      const Vec3& X = mesh.points[static_cast<std::size_t>(i)];
      u.segment<3>(3 * i) += Vec3(0.3 * X.z(), 0.0, -0.2 * X.z());
    }
    grid.refit(mesh, s, u);
    EXPECT_EQ(grid.cell_size(), cell);
  }
  EXPECT_GT(total, 1000u);
}

TEST(SurfaceGrid, SameCandidatesAsBruteForceOnALargeMesh) {
  check_grid_against_brute_force(16, 11, 20000);  // 16^3 * 6 = 24,576 tets
}

// Issue 13's "surface detection that holds at 100k tets": the same comparison on 26^3 * 6 = 105,456
// tets (4,058 surface nodes). Build and refit times at this size: tmlab_bench_kernels
// --benchmark_filter='SurfaceGrid|ContactSurface' (docs/contact.md).
TEST(SurfaceGrid, SameCandidatesAsBruteForceAt100kTets) { check_grid_against_brute_force(26, 12, 100000); }

}  // namespace
}  // namespace tmlab::tm
