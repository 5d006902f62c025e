// External loads: resultants of dead pressure and traction, the follower load stiffness by finite
// differences; the consistent quadratic load of a pressure and a traction on 6-node faces.
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

#include <cmath>

namespace tmlab::tm {
namespace {

TEST(ExternalLoads, DeadPressureAndTractionResultantsAndFollowerStiffnessByFiniteDifference) {
  Mesh mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), 2, 2, 2);
  NodeSelector top;
  top.kind = NodeSelector::Kind::Plane;
  top.axis = 2;
  top.value = 1.0;
  SurfacePressure p{"top", select_faces(mesh, top), 100.0, false, TimeFunction::constant()};
  ExternalLoads dead(mesh, VecX::Ones(mesh.num_points()));
  dead.add(p);
  VecX f;
  dead.assemble(VecX::Zero(3 * mesh.num_points()), 0.0, f);
  Vec3 total = Vec3::Zero();
  for (Index i = 0; i < mesh.num_points(); ++i) total += f.segment<3>(3 * i);
  EXPECT_NEAR(total.z(), -100.0, 1e-12);  // p * area, pushing into the body
  EXPECT_NEAR(total.x(), 0.0, 1e-12);

  // A dead traction vector: its resultant is traction * reference area.
  ExternalLoads trac(mesh, VecX::Ones(mesh.num_points()));
  trac.add(
      SurfaceTraction{"top", select_faces(mesh, top), Vec3(10.0, -20.0, 5.0), TimeFunction::ramp(0.0, 2.0)});
  trac.assemble(VecX::Zero(3 * mesh.num_points()), 1.0, f);
  Vec3 ttotal = Vec3::Zero();
  for (Index i = 0; i < mesh.num_points(); ++i) ttotal += f.segment<3>(3 * i);
  EXPECT_LT((ttotal - Vec3(5.0, -10.0, 2.5)).norm(), 1e-12);

  p.follower = true;
  ExternalLoads fol(mesh, VecX::Ones(mesh.num_points()));
  fol.add(p);
  VecX u(3 * mesh.num_points());
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] = 0.05 * std::sin(1.3 * static_cast<double>(i));
  std::vector<Eigen::Triplet<double>> trip;
  fol.add_load_stiffness(u, 0.0, trip);
  SpMat K(u.size(), u.size());
  K.setFromTriplets(trip.begin(), trip.end());
  VecX dir(u.size());
  for (Eigen::Index i = 0; i < u.size(); ++i) dir[i] = std::cos(0.9 * static_cast<double>(i));
  const double h = 1e-6;
  VecX fp, fm;
  fol.assemble(u + h * dir, 0.0, fp);
  fol.assemble(u - h * dir, 0.0, fm);
  const VecX fd = -(fp - fm) / (2 * h);
  EXPECT_LT((K * dir - fd).norm() / fd.norm(), 1e-7);
}

TEST(ExternalLoads, QuadraticFaceLoadIsTheConsistentLoad) {
  // On each flat 6-node face a uniform load puts nothing on the corners and a third of the face's
  // total on each midside node; the totals are p A (against the outward normal) and t A.
  const Mesh mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 2, 1), 2, 2, 2);
  const QuadraticMesh qm = make_quadratic(mesh);
  Mesh nodes = mesh;
  nodes.points = qm.points;
  const std::vector<Tri> faces = select_faces(mesh, NodeSelector::plane(2, 1.0));
  std::vector<Tri6> tri6;
  for (const Tri& f : faces) tri6.push_back(qm.triangle(f));
  const double p = 100.0, s = 0.5;
  const Vec3 t(1.0, -2.0, 3.0);
  ExternalLoads loads(nodes, VecX::Zero(qm.num_points()));
  loads.add(QuadraticFaceLoad{"top", tri6, p, t, TimeFunction::constant(s)});
  VecX f;
  loads.assemble(VecX::Zero(3 * qm.num_points()), 0.0, f);
  const double area = 2.0;
  const Vec3 face_load = s * (t - p * Vec3::UnitZ());  // per unit area; the top's outward normal is +z
  Vec3 total = Vec3::Zero();
  for (Index i = 0; i < qm.num_points(); ++i) {
    total += f.segment<3>(3 * i);
    if (!qm.is_midside(i)) {
      EXPECT_LT(f.segment<3>(3 * i).norm(), 1e-13) << i;
    }
  }
  EXPECT_LT((total - area * face_load).norm(), 1e-12);
  for (const Tri6& q : tri6) {
    // Each midside node gets A_f / 3 from each top face on its edge (1 or 2 faces).
    for (int k = 3; k < 6; ++k) {
      int n_faces = 0;
      for (const Tri6& o : tri6)
        for (int m = 3; m < 6; ++m)
          n_faces += o[static_cast<std::size_t>(m)] == q[static_cast<std::size_t>(k)];
      const double face_area = area / static_cast<double>(tri6.size());
      EXPECT_LT(
          (f.segment<3>(3 * q[static_cast<std::size_t>(k)]) - n_faces * face_area / 3.0 * face_load).norm(),
          1e-12);
    }
  }
  EXPECT_THROW(loads.add(QuadraticFaceLoad{"none", {}, p, t, TimeFunction::constant()}), Error);
}

}  // namespace
}  // namespace tmlab::tm
