// Lumped mass: a quarter of each tet's mass on each of its nodes, so the total is density x volume.
// HRZ lumping of 10-node tets: positive masses, total exact, and on a single tet the ratio of the
// consistent mass diagonal computed here in closed form (int L0^a L1^b L2^c L3^d dV =
// 6 V a! b! c! d! / (a+b+c+d+3)!, independent of the P2 rule the implementation integrates with).
#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/quadratic_mesh.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/system/dirichlet.hpp"
#include "tensormass/system/external_loads.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

namespace tmlab::tm {
namespace {

TEST(LumpedMass, TotalIsDensityTimesVolumeAndEveryNodeCarriesMass) {
  const Mesh mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(0.02, 0.01, 0.03), 2, 3, 4);
  const VecX m = lumped_node_mass(mesh, 1000.0);
  ASSERT_EQ(m.size(), mesh.num_points());
  EXPECT_NEAR(m.sum(), 1000.0 * 0.02 * 0.01 * 0.03, 1e-15);
  EXPECT_GT(m.minCoeff(), 0.0);
  const VecX md = lumped_dof_mass(m);
  ASSERT_EQ(md.size(), 3 * mesh.num_points());
  for (Index i = 0; i < mesh.num_points(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(md[3 * i + c], m[i]);
}

/// int over the tet of L0^k0 L1^k1 L2^k2 L3^k3, divided by V.
double barycentric_moment(int k0, int k1, int k2, int k3) {
  auto fact = [](int n) {
    double f = 1.0;
    for (int i = 2; i <= n; ++i) f *= i;
    return f;
  };
  return 6.0 * fact(k0) * fact(k1) * fact(k2) * fact(k3) / fact(k0 + k1 + k2 + k3 + 3);
}

TEST(HrzLumpedMass, SingleTetHasTheRatioOfTheConsistentDiagonal) {
  Mesh lin;
  lin.points = {Vec3(0.1, 0.0, 0.0), Vec3(1.3, 0.2, 0.1), Vec3(0.3, 0.9, -0.1), Vec3(0.2, 0.3, 1.1)};
  lin.tets = {Tet{0, 1, 2, 3}};
  const QuadraticMesh qm = make_quadratic(lin);
  const double rho = 1100.0;
  const double V = (lin.points[1] - lin.points[0])
                       .cross(lin.points[2] - lin.points[0])
                       .dot(lin.points[3] - lin.points[0]) /
                   6.0;
  // consistent diagonal / (rho V): vertex int (L(2L-1))^2 = int 4L^4 - 4L^3 + L^2, midside int 16 L_a^2 L_b^2
  const double mv = 4 * barycentric_moment(4, 0, 0, 0) - 4 * barycentric_moment(3, 0, 0, 0) +
                    barycentric_moment(2, 0, 0, 0);
  const double me = 16 * barycentric_moment(2, 2, 0, 0);
  EXPECT_NEAR(mv, 6.0 / 420.0, 1e-15);
  EXPECT_NEAR(me, 32.0 / 420.0, 1e-15);
  // row sums of the consistent matrix are negative at the vertices: why HRZ
  // (row sum = int N_v sum_b N_b = int N_v = int 2 L^2 - L = -V/20)
  EXPECT_NEAR(2 * barycentric_moment(2, 0, 0, 0) - barycentric_moment(1, 0, 0, 0), -1.0 / 20.0, 1e-15);
  const VecX m = hrz_lumped_node_mass(qm, rho);
  ASSERT_EQ(m.size(), 10);
  const double scale = rho * V / (4 * mv + 6 * me);
  for (int a = 0; a < 4; ++a) EXPECT_NEAR(m[a], scale * mv, 1e-14 * rho * V) << a;
  for (int a = 4; a < 10; ++a) EXPECT_NEAR(m[a], scale * me, 1e-14 * rho * V) << a;
  EXPECT_NEAR(m[0] / (rho * V), 1.0 / 36.0, 1e-15);
  EXPECT_NEAR(m[4] / m[0], 32.0 / 6.0, 1e-13);
  EXPECT_NEAR(m.sum(), rho * V, 1e-14 * rho * V);
}

TEST(HrzLumpedMass, PositiveWithExactTotalOnAMesh) {
  const Mesh mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(0.02, 0.01, 0.03), 2, 3, 4);
  const QuadraticMesh qm = make_quadratic(mesh);
  const VecX m = hrz_lumped_node_mass(qm, 1000.0);
  ASSERT_EQ(m.size(), qm.num_points());
  EXPECT_NEAR(m.sum(), 1000.0 * 0.02 * 0.01 * 0.03, 1e-15);
  EXPECT_GT(m.minCoeff(), 0.0);
  EXPECT_THROW(hrz_lumped_node_mass(qm, 0.0), Error);
}

}  // namespace
}  // namespace tmlab::tm
