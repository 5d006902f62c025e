// Rest geometry: V, a_j with sum_j a_j = 0 and sum_j P_j (x) a_j = I; bad tets name their index.
#include "core/base/error.hpp"
#include "tensormass/kernels/tet_geometry.hpp"
#include "tensormass/testing/test_meshes.hpp"

#include <gtest/gtest.h>

#include <string>

namespace tmlab::tm {
namespace {

TEST(TetGeometry, ReferenceTet) {
  const TetRest r = tet_rest(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), "tetrahedron 0");
  EXPECT_NEAR(r.volume, 1.0 / 6.0, 1e-16);
  EXPECT_LT((r.grad[0] - Vec3(-1, -1, -1)).norm(), 1e-15);
  EXPECT_LT((r.grad[1] - Vec3(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((r.grad[3] - Vec3(0, 0, 1)).norm(), 1e-15);
}

TEST(TetGeometry, PartitionOfUnityAndLinearPrecision) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 100; ++trial) {
    const auto p = testing::random_tet_points(rng, 0.01, testing::random_vec(rng, 1.0));
    const TetRest r = tet_rest(p[0], p[1], p[2], p[3], "tetrahedron " + std::to_string(trial));
    const double V = (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) / 6.0;
    EXPECT_NEAR(r.volume, V, 1e-13 * V);
    Vec3 s = Vec3::Zero();
    Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
    for (int j = 0; j < 4; ++j) {
      s += r.grad[j];
      I += p[static_cast<std::size_t>(j)] * r.grad[j].transpose();  // sum_j P_j (x) a_j = I
    }
    EXPECT_LT(s.norm(), 1e-13 * r.grad[1].norm());
    EXPECT_LT((I - Eigen::Matrix3d::Identity()).norm(), 1e-10);
  }
}

TEST(TetGeometry, InvertedAndDegenerateTetsNameTheElement) {
  Mesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 0)};
  m.tets = {{0, 1, 2, 3}, {0, 2, 1, 3}};
  try {
    compute_tet_rest(m);
    FAIL() << "inverted tet accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("tetrahedron 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("inverted"), std::string::npos) << e.what();
  }
  m.tets = {{0, 1, 2, 3}, {0, 1, 2, 3}, {0, 1, 4, 2}};  // flat: 4 in the plane of 0, 1, 2
  try {
    compute_tet_rest(m);
    FAIL() << "flat tet accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("tetrahedron 2"), std::string::npos) << e.what();
  }
  m.tets = {{0, 1, 2, 7}};
  EXPECT_THROW(compute_tet_rest(m), Error);
}

}  // namespace
}  // namespace tmlab::tm
