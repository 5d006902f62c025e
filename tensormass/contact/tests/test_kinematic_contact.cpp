// Kinematic contact of the explicit step (kinematic_contact.hpp) on a block under a rigid plane:
//  a frictionless platen moves every penetrating node back onto its surface (du = -g n), touches
//  no other node, and reports the force m du / dt^2 node by node and in total;
//  a node whose Dirichlet conditions hold the normal direction fixed is an error naming it;
//  a body penetrating at t0 is refused;
//  a bonded platen glues the nodes touching it and carries them along, through a checkpoint too.
#include "tensormass/contact/kinematic_contact.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/system/lumped_mass.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>

namespace tmlab::tm {
namespace {

constexpr double kL = 0.01;  // block side, m

/// Nodes of the plane x_axis = value held in the given components.
struct Hold {
  int axis = 2;
  double value = 0.0;
  std::array<bool, 3> components{};
};

/// The block [0, L]^3 (2 x 2 x 2 cells) with its St VK model and a system held by `holds`.
struct Block {
  Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Constant(kL), 2, 2, 2);
  StVenantKirchhoff material = StVenantKirchhoff::from_young_poisson(10e3, 0.3);
  std::unique_ptr<TensorMassStVK> model;
  std::unique_ptr<MechanicalSystem> system;

  explicit Block(const std::vector<Hold>& holds) {
    std::vector<DirichletCondition> bc;
    for (const Hold& h : holds) {
      DirichletCondition c;
      c.name = "hold" + std::to_string(bc.size());
      c.nodes = select_nodes(mesh, NodeSelector::plane(h.axis, h.value, 1e-12));
      c.components = h.components;
      bc.push_back(c);
    }
    model = std::make_unique<TensorMassStVK>(mesh, material);
    const VecX node_mass = lumped_node_mass(mesh, 1000.0);
    system = std::make_unique<MechanicalSystem>(*model, lumped_dof_mass(node_mass),
                                                DirichletSet(mesh.num_points(), std::move(bc)),
                                                ExternalLoads(mesh, node_mass));
  }
  std::vector<Index> top() const { return select_nodes(mesh, NodeSelector::plane(2, kL, 1e-12)); }
};

RigidBody top_platen() { return RigidBody::plane("platen", Vec3(0, 0, kL), -Vec3::UnitZ()); }

TEST(KinematicContact, FrictionlessPlatenMovesPenetratingNodesOntoItsSurface) {
  Block b({Hold{2, 0.0, {false, false, true}}});
  const VecX u0 = VecX::Zero(3 * b.mesh.num_points());
  KinematicContact contact(*b.system, b.mesh, {top_platen()}, ContactOptions{}, 0.0, u0);
  // The predictor: every top node 0.1 mm into the platen and 0.2 mm sideways; the rest below it.
  VecX u = VecX::Zero(u0.size());
  const std::vector<Index> top = b.top();
  for (Index n : top) u.segment<3>(3 * n) = Vec3(2e-4, 0.0, 1e-4);
  const double dt = 1e-3;
  const VecX du = contact.correct(0.5, dt, u);
  const ContactBodyState& st = contact.state().at(0);
  ASSERT_EQ(st.active_nodes, static_cast<int>(top.size()));
  Vec3 total = Vec3::Zero();
  for (Index n = 0; n < b.mesh.num_points(); ++n) {
    const bool on_top = std::find(top.begin(), top.end(), n) != top.end();
    const Vec3 expect = on_top ? Vec3(0.0, 0.0, -1e-4) : Vec3::Zero();  // -g n: frictionless, no slip
    EXPECT_LT((du.segment<3>(3 * n) - expect).norm(), 1e-15) << "node " << n;
  }
  for (std::size_t i = 0; i < st.nodes.size(); ++i) {
    const Index n = st.nodes[i];
    const Vec3 f = b.system->mass()[3 * n] * du.segment<3>(3 * n) / (dt * dt);
    EXPECT_LT((st.nodal_force[i] - f).norm(), 1e-12 * f.norm()) << "node " << n;
    EXPECT_LE(std::abs(st.gap[i]), 1e-15);
    total += f;
  }
  EXPECT_LT((st.force + total).norm(), 1e-12 * total.norm());  // on the body: minus the sample's
  EXPECT_GT(st.force.z(), 0.0);                                // the sample pushes the platen up
  // A predictor clear of the platen: no correction, no force.
  const VecX none = contact.correct(0.6, dt, VecX::Zero(u0.size()));
  EXPECT_EQ(none.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(contact.state().at(0).active_nodes, 0);
}

TEST(KinematicContact, ANodeHeldAlongTheNormalIsAnErrorNamingIt) {
  Block b({Hold{2, kL, {false, false, true}}});  // the top held in z
  const VecX u0 = VecX::Zero(3 * b.mesh.num_points());
  RigidBody moving = top_platen();
  moving.displacement = Vec3(0, 0, -1e-4);
  moving.function = TimeFunction::ramp(0.0, 1.0);
  KinematicContact pressed(*b.system, b.mesh, {moving}, ContactOptions{}, 0.0, u0);
  try {
    pressed.correct(1.0, 1e-3, u0);
    FAIL() << "a platen pressing on nodes held in z was enforced";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Dirichlet"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("node "), std::string::npos) << e.what();
  }
}

TEST(KinematicContact, ABodyPenetratingAtTheStartIsRefused) {
  Block b({});
  RigidBody low = RigidBody::plane("platen", Vec3(0, 0, 0.9 * kL), -Vec3::UnitZ());
  try {
    KinematicContact contact(*b.system, b.mesh, {low}, ContactOptions{}, 0.0,
                             VecX::Zero(3 * b.mesh.num_points()));
    FAIL() << "a platen 1 mm inside the block was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("penetrates the sample at t = 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'platen'"), std::string::npos) << e.what();
  }
}

TEST(KinematicContact, ABondedPlatenCarriesTheGluedNodesAlsoAfterACheckpoint) {
  Block b({Hold{2, 0.0, {true, true, true}}});
  RigidBody glue = top_platen();
  glue.mode = ContactMode::Bonded;
  glue.displacement = Vec3(1e-3, 0.0, 5e-4);  // sideways and away from the block: glued nodes follow
  glue.function = TimeFunction::ramp(0.0, 1.0);
  const VecX u0 = VecX::Zero(3 * b.mesh.num_points());
  KinematicContact contact(*b.system, b.mesh, {glue}, ContactOptions{}, 0.0, u0);
  const std::vector<double> saved = contact.committed_state();
  const VecX du = contact.correct(0.5, 1e-3, u0);
  const std::vector<Index> top = b.top();
  EXPECT_EQ(contact.state().at(0).active_nodes, static_cast<int>(top.size()));
  for (Index n = 0; n < b.mesh.num_points(); ++n) {
    const bool on_top = std::find(top.begin(), top.end(), n) != top.end();
    const Vec3 expect = on_top ? Vec3(5e-4, 0.0, 2.5e-4) : Vec3::Zero();
    EXPECT_LT((du.segment<3>(3 * n) - expect).norm(), 1e-15) << "node " << n;
  }
  // A fresh contact with a platen that starts clear glues nothing, until the checkpoint says so.
  RigidBody clear = glue;
  clear.reference = Vec3(0, 0, kL + 1e-6);
  KinematicContact restored(*b.system, b.mesh, {clear}, ContactOptions{}, 0.0, u0);
  EXPECT_EQ(restored.correct(0.5, 1e-3, u0).cwiseAbs().maxCoeff(), 0.0);
  restored.restore_committed_state(saved, contact.state());
  const VecX again = restored.correct(0.5, 1e-3, u0);
  for (Index n : top) EXPECT_LT((again.segment<3>(3 * n) - Vec3(5e-4, 0.0, 2.5e-4 + 1e-6)).norm(), 1e-15);
  EXPECT_THROW(restored.restore_committed_state({1.0}, contact.state()), Error);
}

}  // namespace
}  // namespace tmlab::tm
