// Rigid bodies: the gap of core/geometry at the body's position and normalised axis, the
// prescribed motion, the search bounding box, and the refused descriptions.
#include "tensormass/contact/rigid_body.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tmlab::tm {
namespace {

TEST(RigidBody, GapIsTheCoreGapAtItsPosition) {
  // The gap functions themselves (values, finite differences) are tested in
  // core/geometry/tests/test_rigid_gap.cpp; a body evaluates them at c(t) with its normalised axis.
  RigidBody p = RigidBody::punch("punch", Vec3(0.1, 0, 0.3), Vec3(1, 0, -2), 0.4, 0.05);
  EXPECT_NEAR(p.axis.norm(), 1.0, 1e-15);  // normalised by validate()
  p.displacement = Vec3(0, 0.1, -0.2);
  p.function = TimeFunction::ramp(0.0, 2.0);
  for (const Vec3& x : {Vec3(0.3, 0.2, -0.1), Vec3(0.9, -0.1, 0.5), Vec3(0.1, 0.05, 0.2)}) {
    const GapPoint g = p.gap(x, 1.0);
    const GapPoint h = rigid_gap(ContactShape::Punch, p.position(1.0), p.axis, 0.4, 0.05, x);
    EXPECT_EQ(g.g, h.g);
    EXPECT_EQ(g.normal, h.normal);
    EXPECT_EQ(g.closest, h.closest);
    EXPECT_EQ(g.hessian, h.hessian);
  }
  const RigidBody q = RigidBody::plane("platen", Vec3(0, 0, 1), Vec3(1, 0, -1));
  EXPECT_NEAR(q.gap(Vec3(0, 0, 0), 0.0).g, 1.0 / std::sqrt(2.0), 1e-15);
  EXPECT_EQ(q.radial_distance(Vec3(3, 2, 1), 0.0), 0.0);
}

TEST(RigidBody, MotionFollowsTheTimeFunction) {
  RigidBody s = RigidBody::sphere("ball", Vec3(0, 0, 1), 0.5);
  s.displacement = Vec3(0, 0, -0.2);
  s.function = TimeFunction::ramp(0.0, 2.0);
  EXPECT_TRUE(s.position(1.0).isApprox(Vec3(0, 0, 0.9)));
  EXPECT_NEAR(s.gap(Vec3(0, 0, 0), 2.0).g, 0.3, 1e-15);
  EXPECT_NEAR(s.radial_distance(Vec3(0.3, 0.4, 7.0), 2.0), 0.5, 1e-15);
}

TEST(RigidBody, BoundingBoxHoldsTheNearRegion) {
  // Every random point with g <= margin lies in the box.
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> U(-2.0, 2.0);
  const double margin = 0.1;
  const std::vector<RigidBody> bodies = {RigidBody::sphere("s", Vec3(0.2, 0, 0), 0.7),
                                         RigidBody::punch("p", Vec3(0, 0.1, 0), Vec3(1, 1, -1), 0.6, 0.1),
                                         RigidBody::punch("q", Vec3(0, 0, 0), Vec3(0, 0, -1), 0.6),
                                         RigidBody::plane("z", Vec3(0, 0, 0.3), Vec3(0, 0, -1)),
                                         RigidBody::plane("oblique", Vec3(0, 0, 0.3), Vec3(0, 1, -1))};
  for (const RigidBody& b : bodies) {
    Vec3 lo, hi;
    b.bounding_box(0.0, margin, lo, hi);
    int inside = 0;
    for (int k = 0; k < 20000; ++k) {
      const Vec3 x(U(rng), U(rng), U(rng));
      if (b.gap(x, 0.0).g > margin) continue;
      ++inside;
      EXPECT_TRUE((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all()) << b.name;
    }
    EXPECT_GT(inside, 100) << b.name;
  }
}

TEST(RigidBody, InvalidBodiesAreRefused) {
  EXPECT_THROW(RigidBody::sphere("s", Vec3::Zero(), 0.0), Error);
  EXPECT_THROW(RigidBody::plane("p", Vec3::Zero(), Vec3::Zero()), Error);
  EXPECT_THROW(RigidBody::punch("q", Vec3::Zero(), Vec3::UnitZ(), 1.0, 1.5), Error);
  try {
    RigidBody::sphere("indenter", Vec3::Zero(), -1.0);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("indenter"), std::string::npos);
  }
}

}  // namespace
}  // namespace tmlab::tm
