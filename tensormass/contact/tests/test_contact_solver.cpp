// The contact solver on problems with known answers:
//  (a) a block compressed by a frictionless rigid platen: the homogeneous uniaxial St VK solution;
//  (b) a bonded platen: the glued nodes do not slip, and the block is stiffer than with (a);
//  (c) a rigid sphere indenting a block (quarter model): global equilibrium between the contact
//      force and the support reaction, complementarity to tolerance, and the force within a loose
//      band of Hertz (the strict Hertz convergence study is separate: docs/contact.md);
//  (d) the active set settles (no cycling) in every increment of the sphere case;
//  (e) a body penetrating the sample at t = 0 is refused;
//  plus the penalty option (penetration and stiffness reported), the contact tangent against
//  finite differences of the contact residual, and CHOLMOD inside the contact Newton solves (static
//  and implicit) against the default LDL^T.
#include "tensormass/contact/contact_solver.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/contact/contact_implicit.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/system/lumped_mass.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

namespace tmlab::tm {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kYoung = 10e3;  // Pa
constexpr double kPoisson = 0.3;

DirichletCondition roller(const Mesh& mesh, int axis, double value, const std::string& name) {
  DirichletCondition c;
  c.name = name;
  c.nodes = select_nodes(mesh, NodeSelector::plane(axis, value, 1e-12));
  c.components = {axis == 0, axis == 1, axis == 2};
  return c;
}

/// A sample mesh with its St VK tensor-mass model and a mechanical system (no loads).
struct Sample {
  Mesh mesh;
  StVenantKirchhoff material = StVenantKirchhoff::from_young_poisson(kYoung, kPoisson);
  std::unique_ptr<TensorMassStVK> model;
  std::unique_ptr<MechanicalSystem> system;

  Sample(Mesh m, std::vector<DirichletCondition> bc) : mesh(std::move(m)) {
    model = std::make_unique<TensorMassStVK>(mesh, material);
    const VecX node_mass = lumped_node_mass(mesh, 1000.0);
    system = std::make_unique<MechanicalSystem>(*model, lumped_dof_mass(node_mass),
                                                DirichletSet(mesh.num_points(), std::move(bc)),
                                                ExternalLoads(mesh, node_mass));
  }
};

/// Unit block [0, L]^3 on rollers (x = 0, y = 0, z = 0 symmetry planes).
Sample roller_block(double L, int n) {
  Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Constant(L), n, n, n);
  std::vector<DirichletCondition> bc = {roller(mesh, 0, 0.0, "x0"), roller(mesh, 1, 0.0, "y0"),
                                        roller(mesh, 2, 0.0, "z0")};
  return Sample(std::move(mesh), std::move(bc));
}

/// Analytic force on a frictionless platen compressing a St VK block of side L by delta:
/// uniaxial S (S11 = S22 = 0) gives S33 = E E33, and the platen carries P33 A0 = lambda3 S33 L^2.
double uniaxial_force(double L, double delta) {
  const double l3 = 1.0 - delta / L;
  const double e3 = 0.5 * (l3 * l3 - 1.0);
  return -l3 * kYoung * e3 * L * L;
}

TEST(ContactSolver, FrictionlessPlatenGivesTheHomogeneousUniaxialSolution) {
  const double L = 0.01, delta = 0.1 * L;
  Sample s = roller_block(L, 3);
  RigidBody platen = RigidBody::plane("platen", Vec3(0, 0, L), -Vec3::UnitZ());
  platen.displacement = Vec3(0, 0, -delta);
  platen.function = TimeFunction::ramp(0.0, 1.0);
  ContactOptions opt;
  opt.gap_tol = 1e-15 * L;  // round-off level: the Uzawa loop runs until the gap is at round-off
  VecX u = VecX::Zero(s.system->num_dofs());
  ContactStaticSolver solver(*s.system, s.mesh, {platen}, opt, NewtonOptions{}, 0.0, u);
  ContactStepReport rep;
  for (int k = 1; k <= 4; ++k) rep = solver.advance(0.25 * (k - 1), 0.25 * k, u);
  const ContactBodyState& st = rep.bodies.at(0);
  const double F = uniaxial_force(L, delta);
  std::cout << "platen: force " << st.force.z() << " N, analytic " << F << " N, relative error "
            << (st.force.z() - F) / F << ", outer iterations (last step) " << rep.outer_iterations << "\n";
  EXPECT_NEAR(st.force.z(), F, 1e-9 * F) << "outer iterations " << rep.outer_iterations;
  EXPECT_NEAR(st.force.x(), 0.0, 1e-12 * F);
  EXPECT_NEAR(st.force.y(), 0.0, 1e-12 * F);
  EXPECT_EQ(st.active_nodes, 16);  // the 4 x 4 top nodes
  EXPECT_NEAR(st.area, L * L, 1e-15);
  EXPECT_LE(st.max_penetration, opt.gap_tol);
  // Homogeneous pressure P33 on every node's tributary area (ref), and the lateral expansion.
  for (double p : st.pressure) EXPECT_NEAR(p, F / (L * L), 1e-8 * F / (L * L));
  const double e3 = 0.5 * (std::pow(1.0 - delta / L, 2) - 1.0);
  const double l1 = std::sqrt(1.0 - 2.0 * kPoisson * e3);
  const Index corner = s.mesh.num_points() - 1;  // (L, L, L)
  EXPECT_NEAR(u[3 * corner + 0], L * (l1 - 1.0), 1e-9 * L);
  EXPECT_NEAR(u[3 * corner + 2], -delta, 1e-13 * L);
  // The moment about the platen's reference point (0, 0, L - delta): the force acts at the
  // centroid of the deformed top face (l1 L / 2, l1 L / 2).
  const double c = 0.5 * l1 * L;
  EXPECT_NEAR(st.moment.x(), c * F, 1e-8 * F * L);
  EXPECT_NEAR(st.moment.y(), -c * F, 1e-8 * F * L);
}

TEST(ContactSolver, TwoPlatensCarryEqualAndOppositeForces) {
  // The block is held in z only by the two frictionless platens (rollers on x = 0 and y = 0 fix
  // x and y): the bottom platen is fixed, the top one moves down. Both carry the uniaxial force.
  const double L = 0.01, delta = 0.08 * L;
  Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Constant(L), 3, 3, 3);
  std::vector<DirichletCondition> bc = {roller(mesh, 0, 0.0, "x0"), roller(mesh, 1, 0.0, "y0")};
  Sample s(std::move(mesh), std::move(bc));
  RigidBody top = RigidBody::plane("top", Vec3(0, 0, L), -Vec3::UnitZ());
  top.displacement = Vec3(0, 0, -delta);
  top.function = TimeFunction::ramp(0.0, 1.0);
  const RigidBody bottom = RigidBody::plane("bottom", Vec3(0, 0, 0), Vec3::UnitZ());
  ContactOptions opt;
  opt.gap_tol = 1e-14 * L;
  VecX u = VecX::Zero(s.system->num_dofs());
  ContactStaticSolver solver(*s.system, s.mesh, {top, bottom}, opt, NewtonOptions{}, 0.0, u);
  ContactStepReport rep;
  for (int k = 1; k <= 2; ++k) rep = solver.advance(0.5 * (k - 1), 0.5 * k, u);
  ASSERT_EQ(rep.bodies.size(), 2u);
  const double F = uniaxial_force(L, delta);
  EXPECT_NEAR(rep.bodies[0].force.z(), F, 1e-9 * F);
  EXPECT_NEAR(rep.bodies[1].force.z(), -F, 1e-9 * F);
  EXPECT_EQ(rep.bodies[0].active_nodes, 16);
  EXPECT_EQ(rep.bodies[1].active_nodes, 16);
  EXPECT_EQ(rep.bodies[0].name, "top");
  EXPECT_EQ(rep.bodies[1].name, "bottom");
}

TEST(ContactSolver, BondedPlatenHoldsTheTopFace) {
  const double L = 0.01, delta = 0.1 * L;
  Sample s = roller_block(L, 3);
  RigidBody platen = RigidBody::plane("platen", Vec3(0, 0, L), -Vec3::UnitZ());
  platen.mode = ContactMode::Bonded;
  platen.displacement = Vec3(0, 0, -delta);
  platen.function = TimeFunction::ramp(0.0, 1.0);
  VecX u = VecX::Zero(s.system->num_dofs());
  ContactStaticSolver solver(*s.system, s.mesh, {platen}, ContactOptions{}, NewtonOptions{}, 0.0, u);
  EXPECT_EQ(solver.state().at(0).active_nodes, 16);  // glued at t = 0
  ContactStepReport rep;
  for (int k = 1; k <= 4; ++k) rep = solver.advance(0.25 * (k - 1), 0.25 * k, u);
  const ContactBodyState& st = rep.bodies.at(0);
  EXPECT_EQ(st.active_nodes, 16);
  for (Index n : st.nodes) {
    EXPECT_LE(std::abs(u[3 * n + 0]), solver.gap_tol()) << "node " << n;
    EXPECT_LE(std::abs(u[3 * n + 1]), solver.gap_tol()) << "node " << n;
    EXPECT_NEAR(u[3 * n + 2], -delta, solver.gap_tol()) << "node " << n;
  }
  // The free side bulges below the glued top, and the glued block is stiffer than the free one.
  const Index side = 3 + 4 * (1 + 4 * 2);  // (L, L/3, 2L/3)
  EXPECT_GT(u[3 * side], 1e-3 * delta);
  EXPECT_GT(st.force.z(), 1.01 * uniaxial_force(L, delta));
  // Glue carries shear: the lateral nodal forces are not all zero.
  double lateral = 0.0;
  for (const Vec3& f : st.nodal_force) lateral = std::max(lateral, std::hypot(f.x(), f.y()));
  EXPECT_GT(lateral, 1e-3 * st.force.z() / 16);
}

/// Quarter of a block [0, W]^2 x [-H, 0] under a sphere of radius R centred on the z axis, graded
/// towards the origin (x = W xi^2: every cell stays an axis-aligned box, so the Kuhn split stays
/// valid); symmetry rollers on x = 0 and y = 0, the bottom clamped.
Sample quarter_block(double R, int n) {
  const double W = 3.0 * R, H = 3.0 * R;
  Mesh mesh = make_box_mesh(Vec3(0, 0, -1), Vec3(1, 1, 0), n, n, n);
  for (Vec3& p : mesh.points) {
    p.x() = W * p.x() * p.x();
    p.y() = W * p.y() * p.y();
    p.z() = -H * p.z() * p.z();
  }
  DirichletCondition bottom;
  bottom.name = "bottom";
  bottom.nodes = select_nodes(mesh, NodeSelector::plane(2, -H, 1e-12 * H));
  std::vector<DirichletCondition> bc = {roller(mesh, 0, 0.0, "x0"), roller(mesh, 1, 0.0, "y0"), bottom};
  return Sample(std::move(mesh), std::move(bc));
}

double hertz_force(double R, double d) {
  return 4.0 / 3.0 * kYoung / (1.0 - kPoisson * kPoisson) * std::sqrt(R) * std::pow(d, 1.5);
}

TEST(ContactSolver, SphereIndentationEquilibriumComplementarityAndHertzBand) {
  const double R = 0.01, d = 0.1 * R;
  Sample s = quarter_block(R, 10);
  RigidBody sphere = RigidBody::sphere("indenter", Vec3(0, 0, R), R);
  sphere.displacement = Vec3(0, 0, -d);
  sphere.function = TimeFunction::ramp(0.0, 1.0);
  VecX u = VecX::Zero(s.system->num_dofs());
  ContactStaticSolver solver(*s.system, s.mesh, {sphere}, ContactOptions{}, NewtonOptions{}, 0.0, u);
  solver.set_linear_solver(ConstrainedLinearSolver::Kind::ConjugateGradient);
  const int steps = 5;
  int previous_active = 0;
  ContactStepReport rep;
  for (int k = 1; k <= steps; ++k) {
    rep = solver.advance(double(k - 1) / steps, double(k) / steps, u);
    std::cout << "step " << k << ": outer " << rep.outer_iterations << ", Newton "
              << rep.solver.newton_iterations << ", cut-backs " << rep.solver.cutbacks << ", active changes "
              << ::testing::PrintToString(rep.active_changes) << ", natural residual " << rep.natural_residual
              << "\n";
    // (d) the outer loop stopped with an unchanged active set, well before its limit.
    ASSERT_FALSE(rep.active_changes.empty());
    EXPECT_EQ(rep.active_changes.back(), 0) << "step " << k;
    EXPECT_LT(rep.outer_iterations, solver.options().max_outer_iterations) << "step " << k;
    EXPECT_LE(rep.natural_residual, solver.gap_tol());
    // Deeper indentation never loses contact nodes in this monotone loading.
    EXPECT_GE(rep.bodies[0].active_nodes, previous_active) << "step " << k;
    previous_active = rep.bodies[0].active_nodes;
  }
  const ContactBodyState& st = rep.bodies.at(0);
  ASSERT_GT(st.active_nodes, 3);
  // Equilibrium: the force on the sphere equals the support reaction at the clamped bottom (the
  // symmetry rollers carry no z force), and the sum of the nodal contact forces.
  VecX fint;
  s.model->internal_force(u, fint);
  const Vec3 reaction = s.system->bc().resultant(2, fint);
  EXPECT_NEAR(st.force.z(), reaction.z(), 1e-8 * st.force.z());
  Vec3 sum = Vec3::Zero();
  for (const Vec3& f : st.nodal_force) sum += f;
  EXPECT_LT((sum + st.force).norm(), 1e-12 * st.force.norm());
  // Complementarity: lambda >= 0 on every node, no node penetrates beyond gap_tol (checked over
  // the whole boundary, not just the active nodes), lambda g ~ 0.
  EXPECT_GE(st.min_multiplier, 0.0);
  EXPECT_LE(st.max_penetration, solver.gap_tol());
  double lambda_max = 0.0;
  for (const Vec3& f : st.nodal_force) lambda_max = std::max(lambda_max, f.norm());
  EXPECT_LE(st.complementarity, lambda_max * solver.gap_tol());
  for (Index n : solver.surface().nodes) {
    const Vec3 x = s.mesh.points[static_cast<std::size_t>(n)] + u.segment<3>(3 * n);
    EXPECT_GE(solver.bodies()[0].gap(x, 1.0).g, -solver.gap_tol()) << "node " << n;
  }
  // Pressure is compressive on every active node.
  for (double p : st.pressure) EXPECT_GT(p, 0.0);
  // Hertz within a loose band on this coarse quarter mesh (10^3 graded cells, finite block of
  // 3 R, geometric nonlinearity at d/R = 0.1): 25 %. The contact radius sqrt(R d) within 40 %.
  const double F = 4.0 * st.force.z();
  const double Fh = hertz_force(R, d);
  std::cout << "sphere d/R = 0.1, quarter mesh n = 10: F = " << F << " N, Hertz " << Fh << " N, ratio "
            << F / Fh << ", a_eq = " << std::sqrt(4.0 * st.area / kPi) << " a_max = " << st.radius_max
            << " Hertz a = " << std::sqrt(R * d) << ", eps = " << solver.stiffness() << " N/m\n";
  EXPECT_NEAR(F / Fh, 1.0, 0.25);
  EXPECT_NEAR(std::sqrt(4.0 * st.area / kPi) / std::sqrt(R * d), 1.0, 0.4);
  // Moment about the centre: the quarter's resultant passes off the axis, but the sphere's
  // normal forces all pass through its centre: no moment about it.
  EXPECT_LT(st.moment.norm(), 1e-9 * st.force.norm() * R);
}

TEST(ContactSolver, PenaltyOptionReportsItsStiffnessAndPenetration) {
  const double L = 0.01, delta = 0.05 * L;
  Sample s = roller_block(L, 2);
  RigidBody platen = RigidBody::plane("platen", Vec3(0, 0, L), -Vec3::UnitZ());
  platen.displacement = Vec3(0, 0, -delta);
  platen.function = TimeFunction::ramp(0.0, 1.0);
  ContactOptions opt;
  opt.method = ContactMethod::Penalty;
  opt.stiffness = 1e3;  // N/m: soft on purpose so the penetration is visible
  VecX u = VecX::Zero(s.system->num_dofs());
  ContactStaticSolver solver(*s.system, s.mesh, {platen}, opt, NewtonOptions{}, 0.0, u);
  EXPECT_EQ(solver.stiffness(), 1e3);
  const ContactStepReport rep = solver.advance(0.0, 1.0, u);
  EXPECT_EQ(rep.outer_iterations, 1);
  const ContactBodyState& st = rep.bodies.at(0);
  // Each node carries eps * penetration; the penalty solution penetrates, and is softer.
  EXPECT_GT(st.max_penetration, 1e-3 * delta);
  for (std::size_t i = 0; i < st.nodes.size(); ++i)
    EXPECT_NEAR(st.nodal_force[i].z(), 1e3 * st.gap[i], 1e-15);  // n = -z, g < 0
  EXPECT_LT(st.force.z(), uniaxial_force(L, delta));
}

TEST(ContactSolver, ContactTermsMatchFiniteDifferences) {
  // A block glued to a bonded plane at its bottom (the only z support), pressed by a sphere and by
  // a punch whose rounded rim touches nodes (curvature terms). After a solve has set the candidate
  // sets and multipliers, the contact residual is checked against finite differences of the
  // contact energy, and the contact tangent against finite differences of the residual.
  const double L = 0.01;
  Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Constant(L), 3, 3, 3);
  std::vector<DirichletCondition> bc = {roller(mesh, 0, 0.0, "x0"), roller(mesh, 1, 0.0, "y0")};
  Sample s(std::move(mesh), std::move(bc));
  const double R = 0.5 * L;
  RigidBody sphere = RigidBody::sphere("s", Vec3(L / 3, L / 3, L + R), R);
  sphere.displacement = Vec3(0, 0, -0.03 * L);
  sphere.function = TimeFunction::ramp(0.0, 1.0);
  RigidBody punch = RigidBody::punch("p", Vec3(2 * L / 3, 2 * L / 3, L), -Vec3::UnitZ(), 0.4 * L, 0.1 * L);
  punch.displacement = Vec3(0, 0, -0.03 * L);
  punch.function = TimeFunction::ramp(0.0, 1.0);
  RigidBody glue = RigidBody::plane("glue", Vec3(0, 0, 0), Vec3::UnitZ());
  glue.mode = ContactMode::Bonded;
  VecX u = VecX::Zero(s.system->num_dofs());
  ContactStaticSolver solver(*s.system, s.mesh, {sphere, punch, glue}, ContactOptions{}, NewtonOptions{}, 0.0,
                             u);
  const ContactStepReport rep = solver.advance(0.0, 1.0, u);
  EXPECT_EQ(rep.bodies[0].active_nodes, 1);  // the node under the sphere
  // The face centre node and nodes under the rounded rim (radial distance beyond R - rho = 0.3 L).
  ASSERT_GE(rep.bodies[1].active_nodes, 2);
  double rim = 0.0;
  for (Index node : rep.bodies[1].nodes)
    rim =
        std::max(rim, solver.bodies()[1].radial_distance(s.mesh.points[static_cast<std::size_t>(node)], 1.0));
  EXPECT_GT(rim, 0.3 * L);
  EXPECT_EQ(rep.bodies[2].active_nodes, 16);  // the glued bottom

  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (Eigen::Index i = 0; i < u.size(); ++i) u[i] += 1e-4 * L * U(rng);
  const Eigen::Index n = u.size();
  auto residual = [&](const VecX& v) {
    VecX r = VecX::Zero(n);
    solver.add_contact_terms(v, 1.0, &r, nullptr, nullptr);
    return r;
  };
  auto energy = [&](const VecX& v) {
    double e = 0.0;
    solver.add_contact_terms(v, 1.0, nullptr, nullptr, &e);
    return e;
  };
  SpMat J;
  s.model->tangent(u, J);
  J *= 0.0;  // the mesh-graph pattern, zero values
  solver.add_contact_terms(u, 1.0, nullptr, &J, nullptr);
  const VecX r = residual(u);
  ASSERT_GT(r.norm(), 0.0);
  // Residual = dPhi/du along random directions.
  const double h = 1e-7 * L;
  for (int k = 0; k < 5; ++k) {
    VecX v(n);
    for (Eigen::Index i = 0; i < n; ++i) v[i] = U(rng);
    const double fd = (energy(u + h * v) - energy(u - h * v)) / (2 * h);
    EXPECT_NEAR(fd, r.dot(v), 1e-6 * r.norm() * v.norm()) << "direction " << k;
  }
  // Tangent columns of every DOF of the nodes the contact terms act on.
  const Eigen::MatrixXd Jd(J);
  const double jscale = Jd.cwiseAbs().maxCoeff();
  int columns = 0;
  for (const ContactBodyState& st : rep.bodies)
    for (Index node : st.nodes)
      for (int c = 0; c < 3; ++c) {
        const Eigen::Index j = 3 * node + c;
        VecX e = VecX::Zero(n);
        e[j] = h;
        const VecX fd = (residual(u + e) - residual(u - e)) / (2 * h);
        EXPECT_LT((fd - Jd.col(j)).norm(), 1e-6 * jscale) << "node " << node << " component " << c;
        ++columns;
      }
  EXPECT_EQ(columns, 3 * (rep.bodies[0].active_nodes + rep.bodies[1].active_nodes + 16));
}

/// A contact solve with the given linear solver of its Newton iterations (NewtonOptions::linear_solver):
/// its displacement, the contact force and how many CHOLMOD solves fell back to LDL^T.
struct ContactRun {
  VecX u;
  Vec3 force = Vec3::Zero();
  NewtonLinearSolver kind = NewtonLinearSolver::Direct;
  int fallbacks = 0;
  LinearSolveStats stats;
};

/// A rigid plane compressing the roller block by 10 % (3 increments): the contact tangent adds
/// eps n n^T only, so every tangent is positive definite.
ContactRun platen_run(NewtonLinearSolver linear) {
  const double L = 0.01;
  Sample s = roller_block(L, 6);
  RigidBody platen = RigidBody::plane("platen", Vec3(0, 0, L), -Vec3::UnitZ());
  platen.displacement = Vec3(0, 0, -0.1 * L);
  platen.function = TimeFunction::ramp(0.0, 1.0);
  NewtonOptions no;
  no.linear_solver = linear;
  ContactRun out;
  out.u = VecX::Zero(s.system->num_dofs());
  ContactStaticSolver solver(*s.system, s.mesh, {platen}, ContactOptions{}, no, 0.0, out.u);
  ContactStepReport rep;
  for (int k = 1; k <= 3; ++k) rep = solver.advance((k - 1) / 3.0, k / 3.0, out.u);
  out.force = rep.bodies.at(0).force;
  out.kind = solver.linear_solver().kind();
  out.fallbacks = solver.linear_solver().fallbacks();
  return out;
}

/// The sphere indenting the quarter block, static (3 increments) or implicit Newmark (4 steps of
/// 0.1 ms). The sphere's contact tangent -p H (H = (I - n n^T) / |x - c|, the convex surface's
/// curvature) makes some tangents of these fine graded cells indefinite: CHOLMOD falls back there.
ContactRun sphere_run(NewtonLinearSolver linear, bool implicit) {
  const double R = 0.01, d = 0.05 * R;
  Sample s = quarter_block(R, 6);
  RigidBody sphere = RigidBody::sphere("indenter", Vec3(0, 0, R), R);
  sphere.displacement = Vec3(0, 0, -d);
  NewtonOptions no;
  no.linear_solver = linear;
  ContactRun out;
  ContactStepReport rep;
  if (!implicit) {
    sphere.function = TimeFunction::ramp(0.0, 1.0);
    out.u = VecX::Zero(s.system->num_dofs());
    ContactStaticSolver solver(*s.system, s.mesh, {sphere}, ContactOptions{}, no, 0.0, out.u);
    for (int k = 1; k <= 3; ++k) rep = solver.advance((k - 1) / 3.0, k / 3.0, out.u);
    out.kind = solver.linear_solver().kind();
    out.fallbacks = solver.linear_solver().fallbacks();
    out.stats = solver.linear_solver().stats();
  } else {
    const double dt = 1e-4;
    sphere.function = TimeFunction::ramp(0.0, 4 * dt);
    ContactImplicitDynamics integ(*s.system, s.mesh, {sphere}, ContactOptions{}, ImplicitScheme::Newmark, no,
                                  dt);
    const VecX zero = VecX::Zero(s.system->num_dofs());
    integ.initialize(0.0, zero, zero);
    for (int k = 0; k < 4; ++k) rep = integ.step(integ.time(), dt);
    out.u = integ.displacement();
    out.kind = integ.contact().linear_solver().kind();
    out.fallbacks = integ.contact().linear_solver().fallbacks();
    out.stats = integ.contact().linear_solver().stats();
  }
  out.force = rep.bodies.at(0).force;
  return out;
}

void expect_same_answer(const ContactRun& chol, const ContactRun& ldlt, const std::string& what) {
  EXPECT_EQ(ldlt.kind, NewtonLinearSolver::Direct) << what;
  EXPECT_EQ(chol.kind, NewtonLinearSolver::Cholmod) << what;  // taken from NewtonOptions
  ASSERT_GT(std::abs(ldlt.force.z()), 0.0) << what;
  EXPECT_LT((chol.u - ldlt.u).lpNorm<Eigen::Infinity>(), 1e-10 * ldlt.u.lpNorm<Eigen::Infinity>()) << what;
  EXPECT_LT((chol.force - ldlt.force).norm(), 1e-10 * ldlt.force.norm()) << what;
}

TEST(ContactSolver, CholmodInTheContactSolvesGivesTheLdltAnswer) {
  // Oracle: the same contact solves with CHOLMOD's LL^T and with Eigen's LDL^T (the default) agree
  // to 1e-10 (relative to the largest displacement and to the contact force). The platen's
  // tangents are positive definite: every solve is CHOLMOD's own. The sphere's are not always:
  // those solves fall back to LDL^T (counted), static and implicit, with the same answer.
  const ContactRun platen = platen_run(NewtonLinearSolver::Cholmod);
  expect_same_answer(platen, platen_run(NewtonLinearSolver::Direct), "platen");
  EXPECT_EQ(platen.fallbacks, 0);
  for (const bool implicit : {false, true}) {
    const ContactRun chol = sphere_run(NewtonLinearSolver::Cholmod, implicit);
    expect_same_answer(chol, sphere_run(NewtonLinearSolver::Direct, implicit),
                       implicit ? "implicit" : "static");
    std::cout << (implicit ? "implicit" : "static") << " sphere: " << chol.fallbacks
              << " CHOLMOD solves fell back to LDL^T\n";
    // Each fallback is a truly indefinite tangent (negative LDL^T pivots: the sphere's -p H), none
    // a round-off failure, and CHOLMOD's own solves share one symbolic analysis.
    EXPECT_EQ(chol.stats.fallbacks_indefinite, chol.fallbacks);
    EXPECT_EQ(chol.stats.fallbacks_round_off, 0);
    EXPECT_EQ(chol.stats.cholmod_analyses, 1);
    EXPECT_EQ(chol.stats.cholmod_solves + chol.stats.ldlt_solves, chol.stats.solves);
  }
}

TEST(ContactSolver, BodyPenetratingAtTheStartIsRefused) {
  const double L = 0.01;
  Sample s = roller_block(L, 2);
  // A sphere whose centre sits 0.999 R above the top face: it penetrates by 1e-3 R.
  const double R = 0.004;
  const RigidBody sphere = RigidBody::sphere("indenter", Vec3(0.5 * L, 0.5 * L, L + 0.999 * R), R);
  VecX u = VecX::Zero(s.system->num_dofs());
  try {
    ContactStaticSolver solver(*s.system, s.mesh, {sphere}, ContactOptions{}, NewtonOptions{}, 0.0, u);
    FAIL() << "a penetrating body was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'indenter'"), std::string::npos) << what;
    EXPECT_NE(what.find("penetrates"), std::string::npos) << what;
    EXPECT_NE(what.find("t = 0"), std::string::npos) << what;
  }
  // Touching (to round-off) is accepted.
  const RigidBody touching = RigidBody::sphere("indenter", Vec3(0.5 * L, 0.5 * L, L + R), R);
  EXPECT_NO_THROW(
      ContactStaticSolver(*s.system, s.mesh, {touching}, ContactOptions{}, NewtonOptions{}, 0.0, u));
}

}  // namespace
}  // namespace tmlab::tm
