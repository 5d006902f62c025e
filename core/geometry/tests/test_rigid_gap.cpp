// Gap functions of the rigid bodies: values at known points, finite-difference checks of the gap
// gradient (= the normal) and of its Hessian (the curvature term of the contact tangent), the
// closest point lying on the surface at the gap distance, and the distance from the axis.
#include "core/geometry/rigid_gap.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace tmlab {
namespace {

/// A body as the gap functions see it: shape, reference point, unit axis, radii.
struct Body {
  ContactShape shape;
  Vec3 c;
  Vec3 axis;
  double radius = 0.0, edge_radius = 0.0;
  GapPoint gap(const Vec3& x) const { return rigid_gap(shape, c, axis, radius, edge_radius, x); }
};

/// Central differences of g and of n = dg/dx at x against the exact normal and Hessian.
void expect_fd_consistent(const Body& b, const Vec3& x, double h, const std::string& what) {
  const GapPoint p = b.gap(x);
  Vec3 grad;
  Eigen::Matrix3d hess;
  for (int j = 0; j < 3; ++j) {
    const Vec3 e = h * Vec3::Unit(j);
    const GapPoint a = b.gap(x + e), m = b.gap(x - e);
    grad(j) = (a.g - m.g) / (2 * h);
    hess.col(j) = (a.normal - m.normal) / (2 * h);
  }
  EXPECT_LT((grad - p.normal).norm(), 1e-7) << what << " gradient at " << x.transpose();
  EXPECT_NEAR(p.normal.norm(), 1.0, 1e-14) << what;
  const double hs = std::max(1.0, p.hessian.norm());
  EXPECT_LT((hess - p.hessian).norm() / hs, 1e-5) << what << " Hessian at " << x.transpose() << "\nfd\n"
                                                  << hess << "\nexact\n"
                                                  << p.hessian;
  // The closest point is on the surface (gap 0) and at distance |g| along the normal.
  EXPECT_NEAR(b.gap(p.closest).g, 0.0, 1e-12) << what;
  EXPECT_NEAR((x - p.closest).norm(), std::abs(p.g), 1e-12) << what;
}

TEST(RigidGap, SphereValuesAndDerivatives) {
  const Body s{ContactShape::Sphere, Vec3(0.1, 0.2, 0.3), -Vec3::UnitZ(), 0.5};
  EXPECT_NEAR(s.gap(Vec3(0.1, 0.2, 1.0)).g, 0.2, 1e-15);
  EXPECT_NEAR(s.gap(Vec3(0.1, 0.2, 0.5)).g, -0.3, 1e-15);
  EXPECT_TRUE(s.gap(Vec3(0.1, 0.2, 1.0)).normal.isApprox(Vec3::UnitZ()));
  EXPECT_EQ(s.gap(s.c).normal, Vec3::UnitZ());  // at the centre: +z, a valid subgradient
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int k = 0; k < 50; ++k) {
    const Vec3 x(U(rng), U(rng), U(rng));
    if ((x - s.c).norm() < 0.05) continue;
    expect_fd_consistent(s, x, 1e-6, "sphere");
  }
}

TEST(RigidGap, PlaneValuesAndDerivatives) {
  const Body p{ContactShape::Plane, Vec3(0, 0, 1), Vec3(1, 0, -1).normalized()};
  EXPECT_NEAR(p.gap(Vec3(0, 0, 0)).g, 1.0 / std::sqrt(2.0), 1e-15);
  EXPECT_EQ(p.gap(Vec3(0.3, 0.1, 0)).hessian, Eigen::Matrix3d::Zero());
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> U(-2.0, 2.0);
  for (int k = 0; k < 20; ++k) expect_fd_consistent(p, Vec3(U(rng), U(rng), U(rng)), 1e-6, "plane");
}

TEST(RigidGap, PunchInEveryRegion) {
  // Axis -z: the flat face at z = 0 faces down, the body occupies z >= 0, r <= R.
  for (double rho : {0.0, 0.1}) {
    const Body p{ContactShape::Punch, Vec3(0, 0, 0), Vec3(0, 0, -1), 0.5, rho};
    const std::string tag = "rho = " + std::to_string(rho);
    // Below the face: g = distance to the face.
    EXPECT_NEAR(p.gap(Vec3(0.1, 0.05, -0.2)).g, 0.2, 1e-15) << tag;
    EXPECT_TRUE(p.gap(Vec3(0.1, 0.05, -0.2)).normal.isApprox(-Vec3::UnitZ())) << tag;
    // Beside the cylinder, above the face level: distance to the side.
    EXPECT_NEAR(p.gap(Vec3(0.8, 0, 1.0)).g, 0.3, 1e-15) << tag;
    // Beyond the rim: distance to the rim circle (radius R - rho at depth rho), minus rho.
    const Vec3 x(0.8, 0.0, -0.4);
    const double expect = std::hypot(0.8 - (0.5 - rho), 0.4 + rho) - rho;
    EXPECT_NEAR(p.gap(x).g, expect, 1e-15) << tag;
    // Inside, near the face: negative, face normal.
    EXPECT_NEAR(p.gap(Vec3(0.0, 0.0, 0.01)).g, -0.01, 1e-15) << tag;
    // Inside, near the side.
    EXPECT_NEAR(p.gap(Vec3(0.45, 0.0, 1.0)).g, -0.05, 1e-15) << tag;

    std::mt19937 rng(9);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    int checked = 0;
    for (int k = 0; k < 400; ++k) {
      const Vec3 y(U(rng), U(rng), U(rng));
      // Keep away from the kinks of the inside (face/side switch), the axis and the rim circle
      // of the core, where g is not C2.
      const double r = std::hypot(y.x(), y.y()), s = -y.z();
      const double dr = r - 0.5 + rho, ds = s + rho;
      if (r < 0.02) continue;
      if (dr <= 0.0 && ds <= 0.0 && std::abs(dr - ds) < 0.01) continue;
      if (std::abs(dr) < 0.01 || std::abs(ds) < 0.01) continue;
      expect_fd_consistent(p, y, 1e-6, "punch " + tag);
      ++checked;
    }
    EXPECT_GT(checked, 200);
  }
}

TEST(RigidGap, RadialDistanceFromTheAxis) {
  const Vec3 c(0, 0, 1), a(0, 0, -1);
  EXPECT_NEAR(radial_distance(ContactShape::Sphere, c, a, Vec3(0.3, 0.4, 7.0)), 0.5, 1e-15);
  EXPECT_NEAR(radial_distance(ContactShape::Punch, c, a, Vec3(0.0, -0.2, -3.0)), 0.2, 1e-15);
  EXPECT_EQ(radial_distance(ContactShape::Plane, c, a, Vec3(0.3, 0.4, 7.0)), 0.0);
}

}  // namespace
}  // namespace tmlab
