// The inversion-depth study (depth_limit.hpp) on its coarsest setting: the quarter block with 4
// cells per axis, St VK and neo-Hookean with the same small-strain moduli. St VK softens in
// compression: a tet inverts, or collapses past St VK's compression limit, at a finite depth;
// neo-Hookean's energy grows without bound as J -> 0, so it reaches deeper or never inverts.
#include "core/base/error.hpp"
#include "studies/depth_limit/depth_limit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace tmlab::tm {
namespace {

DepthLimitOptions coarse() {
  DepthLimitOptions o;
  o.cells = {4};
  o.max_depth = 0.010;
  o.increment = 0.5e-3;
  return o;
}

DepthLimitLaw law_named(const std::string& name, const DepthLimitOptions& o) {
  for (const DepthLimitLaw& l : default_depth_limit_laws(o.young, o.poisson))
    if (l.name == name) return l;
  throw Error("no default law " + name);
}

TEST(InversionDepth, GradedQuarterBlockIsValidAndRefinedAtTheTip) {
  DepthLimitOptions o = coarse();
  const Mesh m = inversion_block(o, 4);
  EXPECT_EQ(m.num_tets(), 6 * 4 * 4 * 4);
  double zmax = 0.0, xmax = 0.0;
  for (const Vec3& x : m.points) {
    zmax = std::max(zmax, x.z());
    xmax = std::max(xmax, x.x());
  }
  EXPECT_DOUBLE_EQ(zmax, o.height);
  EXPECT_DOUBLE_EQ(xmax, o.half_width);
  // A node at the indentation point (the sphere's first contact).
  bool tip = false;
  for (const Vec3& x : m.points) tip = tip || (x - Vec3(0, 0, o.height)).norm() < 1e-15;
  EXPECT_TRUE(tip);
}

TEST(InversionDepth, DefaultLawsShareTheSmallStrainModuli) {
  const auto laws = default_depth_limit_laws(3000.0, 0.45);
  ASSERT_EQ(laws.size(), 6u);
  const double G = 3000.0 / 2.9;
  EXPECT_NEAR(2.0 * (laws[2].parameters["c10"].get<double>() + laws[2].parameters["c01"].get<double>()), G,
              1e-12 * G);
  EXPECT_NEAR(2.0 * laws[3].parameters["c10"].get<double>(), G, 1e-12 * G);
  EXPECT_NEAR(0.5 * laws[4].parameters["mu"][0].get<double>() * laws[4].parameters["alpha"][0].get<double>(),
              G, 1e-12 * G);
  EXPECT_NEAR(laws[5].parameters["c1"].get<double>() * laws[5].parameters["c2"].get<double>(), G, 1e-12 * G);
}

TEST(InversionDepth, StVKReachesItsLimitAtAFiniteDepthAndNeoHookeanGoesDeeper) {
  const DepthLimitOptions o = coarse();
  const DepthLimitRun stvk = run_inversion(o, law_named("stvk", o), 4);
  const DepthLimitRun nh = run_inversion(o, law_named("neo_hookean", o), 4);
  for (const DepthLimitRun* r : {&stvk, &nh})
    std::cout << r->law << ": " << r->outcome << ", limit depth " << r->limit_depth << " m, deepest "
              << r->deepest << " m, min J " << r->deepest_min_j << (r->message.empty() ? "" : ": ")
              << r->message << "\n";
  // St VK: a tet inverts, or the static solve loses the equilibrium (the tet collapses past St VK's
  // compression limit), at a finite depth within the range; the bracket holds it.
  ASSERT_NE(stvk.outcome, "max_depth");
  ASSERT_TRUE(std::isfinite(stvk.limit_depth));
  EXPECT_GT(stvk.limit_depth, 0.0);
  EXPECT_LT(stvk.limit_depth, o.max_depth);
  EXPECT_GE(stvk.limit_depth, stvk.bracket_low);
  EXPECT_LE(stvk.limit_depth, stvk.bracket_high);
  EXPECT_NEAR(stvk.bracket_high - stvk.bracket_low, o.increment, 1e-12);
  if (stvk.outcome == "inverted") {
    EXPECT_LE(stvk.samples.back().min_j, 0.0);
  }
  // The force grew with the depth.
  ASSERT_GE(stvk.samples.size(), 2u);
  EXPECT_GT(stvk.samples.front().force, 0.0);
  EXPECT_GT(stvk.samples.back().force, stvk.samples.front().force);
  // Neo-Hookean: never a converged inverted state, and deeper than St VK's limit (or no limit).
  EXPECT_NE(nh.outcome, "inverted");
  for (const DepthLimitSample& s : nh.samples) EXPECT_GT(s.min_j, 0.0);
  EXPECT_GT(nh.deepest, stvk.limit_depth);
  EXPECT_TRUE(!std::isfinite(nh.limit_depth) || nh.limit_depth > stvk.limit_depth);
}

TEST(InversionDepth, BadOptionsAreErrors) {
  DepthLimitOptions o = coarse();
  o.max_depth = o.height;
  EXPECT_THROW(run_depth_limit_study(o), Error);
  o = coarse();
  o.cells = {1};
  EXPECT_THROW(run_depth_limit_study(o), Error);
  o = coarse();
  o.laws = {{"ogden", {{"mu", {-1.0}}, {"alpha", {2.0}}, {"kappa", 1e4}}}};  // unstable Ogden
  EXPECT_THROW(run_depth_limit_study(o), Error);
}

}  // namespace
}  // namespace tmlab::tm
