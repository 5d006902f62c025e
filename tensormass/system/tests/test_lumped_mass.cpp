// Lumped mass: a quarter of each tet's mass on each of its nodes, so the total is density x volume.
#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/system/dirichlet.hpp"
#include "tensormass/system/external_loads.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace tmlab::tm
