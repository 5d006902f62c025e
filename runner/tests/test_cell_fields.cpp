// Per-tet kinematics: the smallest volume ratio finds an inverted tet, and the output fields of a
// homogeneous stretch are its closed form (J, Green strain, the St VK Cauchy stress, von Mises).
#include "runner/cell_fields.hpp"
#include "runner/tests/runner_test_case.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::tm::runner {
namespace {

class CellFieldsTest : public RunnerTestCase {};

/// u = (lambda - 1) x e_x at every node.
VecX stretch_x(const Mesh& mesh, double lambda) {
  VecX u = VecX::Zero(3 * mesh.num_points());
  for (Index i = 0; i < mesh.num_points(); ++i) u[3 * i] = (lambda - 1.0) * mesh.points[i].x();
  return u;
}

TEST_F(CellFieldsTest, MinVolumeRatioOfRestStretchAndInversion) {
  const CaseConfig cfg = config(uniaxial(0.001));
  const Problem p(cfg);
  EXPECT_NEAR(min_volume_ratio(p.mesh, VecX::Zero(3 * p.mesh.num_points())).first, 1.0, 1e-14);
  EXPECT_NEAR(min_volume_ratio(p.mesh, stretch_x(p.mesh, 1.2)).first, 1.2, 1e-12);
  // Every x mirrored: every tet inverted, J = -1.
  const auto [j, where] = min_volume_ratio(p.mesh, stretch_x(p.mesh, -1.0));
  EXPECT_NEAR(j, -1.0, 1e-12);
  EXPECT_GE(where, 0);
  EXPECT_LT(where, p.mesh.num_tets());
}

TEST_F(CellFieldsTest, HomogeneousStretchMatchesTheClosedForm) {
  const CaseConfig cfg = config(uniaxial(0.001));
  const Problem p(cfg);
  const double l = 1.1, e11 = 0.5 * (l * l - 1.0);
  const double E = 10000.0, nu = 0.3;
  const double lam = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  // St VK: S = lambda tr(E) I + 2 mu E; sigma = F S F^T / J with F = diag(l, 1, 1), J = l.
  const double s11 = (lam + 2 * mu) * e11, s22 = lam * e11;
  const double sig11 = l * s11, sig22 = s22 / l;
  const double vm = std::abs(sig11 - sig22);  // von Mises of diag(a, b, b)
  const CellFields c = cell_fields(p, stretch_x(p.mesh, l));
  ASSERT_EQ(c.jratio.size(), static_cast<std::size_t>(p.mesh.num_tets()));
  for (std::size_t t = 0; t < c.jratio.size(); ++t) {
    EXPECT_NEAR(c.jratio[t], l, 1e-12);
    EXPECT_NEAR(c.strain[t](0, 0), e11, 1e-12);
    EXPECT_NEAR(c.strain[t](1, 1), 0.0, 1e-12);
    EXPECT_NEAR(c.cauchy[t](0, 0), sig11, 1e-8 * sig11);
    EXPECT_NEAR(c.cauchy[t](2, 2), sig22, 1e-8 * sig11);
    EXPECT_NEAR(c.von_mises[t], vm, 1e-8 * vm);
  }
}

}  // namespace
}  // namespace tmlab::tm::runner
