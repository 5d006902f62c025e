// MechanicalSystem: Rayleigh damping C v = alpha M v + beta K_0 v with K_0 the tangent at rest.
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

TEST(MechanicalSystem, RayleighDampingIsMassPlusReferenceStiffness) {
  const Mesh mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), 2, 2, 2);
  TensorMassStVK model(mesh, StVenantKirchhoff::from_young_poisson(1000.0, 0.3));
  const VecX nm = lumped_node_mass(mesh, 2.0);
  const MechanicalSystem sys(model, lumped_dof_mass(nm), DirichletSet(mesh.num_points(), {}),
                             ExternalLoads(mesh, nm), RayleighDamping{0.7, 0.03});
  VecX v(sys.num_dofs());
  for (Eigen::Index i = 0; i < v.size(); ++i) v[i] = std::sin(0.37 * static_cast<double>(i));
  VecX cv;
  sys.damping_force(v, cv);
  SpMat K0;
  model.tangent(VecX::Zero(sys.num_dofs()), K0);
  const VecX expected = 0.7 * sys.mass().cwiseProduct(v) + 0.03 * (K0 * v);
  EXPECT_LT((cv - expected).norm(), 1e-12 * expected.norm());
  EXPECT_LT(SpMat(sys.reference_tangent() - K0).norm(), 1e-12 * K0.norm());
}

}  // namespace
}  // namespace tmlab::tm
