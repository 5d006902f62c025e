// Contact at face quadrature points (quadratic meshes, contact_points.hpp), with a stand-in model
// on the 10-node mesh's points (independent springs, the P2 node graph as the tangent's pattern) so
// that the contact terms are tested on their own:
//  (a) the nodal points are the surface nodes with weight 1; the face points' weights sum to the
//      boundary area and integrate the corner shape functions to 0 and the midside ones to A/3;
//  (b) a flat plane penetrating a face uniformly (penalty, z held) loads it with the consistent
//      quadratic load: nothing on the corners, a third of each face's force on each midside node,
//      total eps_a * depth * area, and the body's force is sum_f lambda_f sum_q w_q n_q; one
//      constraint per face, eps_a = eps N_b / S;
//  (c) the face-point residual against finite differences of the contact energy, and the tangent
//      against finite differences of the residual (sphere and bonded plane: curvature and glue);
//  (d) a body penetrating a face point at t = 0 is refused;
//  (e) a sphere pressed into a block of springs converges in a few outer iterations with the
//      default options (one multiplier per face: no redundant constraints), with lambda_f >= 0,
//      every face's weighted gap >= -gap_tol and lambda_f |g_f| within tolerance.
#include "tensormass/contact/contact_solver.hpp"

#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/quadratic_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

namespace tmlab::tm {
namespace {

/// W = k/2 |u|^2 on every node; the tangent k I on the 10-node tets' node graph (zeros off the diagonal).
class Springs final : public ElasticModel {
 public:
  Springs(const QuadraticMesh& qm, double k) : qm_(qm), k_(k) {}
  Index num_nodes() const override { return qm_.num_points(); }
  double energy(const VecX& u) const override { return 0.5 * k_ * u.squaredNorm(); }
  void internal_force(const VecX& u, VecX& f) const override { f = k_ * u; }
  void tangent_apply(const VecX&, const VecX& v, VecX& Kv) const override { Kv = k_ * v; }
  void tangent(const VecX&, SpMat& K) const override {
    std::vector<Eigen::Triplet<double>> t;
    for (const Tet10& tet : qm_.tets)
      for (Index a : tet)
        for (Index b : tet)
          for (int c = 0; c < 3; ++c)
            for (int d = 0; d < 3; ++d) t.emplace_back(3 * a + c, 3 * b + d, 0.0);
    for (Index i = 0; i < 3 * num_nodes(); ++i) t.emplace_back(i, i, k_);
    K.resize(3 * num_nodes(), 3 * num_nodes());
    K.setFromTriplets(t.begin(), t.end());
  }

 private:
  const QuadraticMesh& qm_;
  double k_;
};

struct QuadraticSample {
  Mesh mesh;
  QuadraticMesh qm;
  std::unique_ptr<Springs> model;
  std::unique_ptr<MechanicalSystem> system;
  Mesh nodes;  // the linear tets over the quadratic points (for ExternalLoads)

  QuadraticSample(double L, int n, const std::vector<std::array<bool, 3>>& held_components)
      : mesh(make_box_mesh(Vec3::Zero(), Vec3::Constant(L), n, n, n)), qm(make_quadratic(mesh)) {
    nodes = mesh;
    nodes.points = qm.points;
    model = std::make_unique<Springs>(qm, 1.0);
    std::vector<DirichletCondition> bc;
    for (const auto& comp : held_components) {
      DirichletCondition c;
      c.name = "held";
      for (Index i = 0; i < qm.num_points(); ++i) c.nodes.push_back(i);
      c.components = comp;
      bc.push_back(c);
    }
    const VecX m = VecX::Ones(qm.num_points());
    system = std::make_unique<MechanicalSystem>(*model, VecX::Ones(3 * qm.num_points()),
                                                DirichletSet(qm.num_points(), std::move(bc)),
                                                ExternalLoads(nodes, m));
  }
};

TEST(ContactFacePoints, WeightsAndShapeIntegrals) {
  const double L = 0.01;
  const Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Constant(L), 2, 2, 2);
  const QuadraticMesh qm = make_quadratic(mesh);
  const ContactSurface s = ContactSurface::extract(mesh);
  const ContactPoints nodal = ContactPoints::at_nodes(mesh, s);
  ASSERT_EQ(nodal.size(), s.size());
  for (Index k = 0; k < nodal.size(); ++k) {
    EXPECT_EQ(nodal.node[static_cast<std::size_t>(k)], s.nodes[static_cast<std::size_t>(k)]);
    EXPECT_EQ(nodal.weight[static_cast<std::size_t>(k)], 1.0);
  }
  const ContactPoints fp = ContactPoints::at_face_quadrature(qm, s);
  EXPECT_FALSE(fp.nodal);
  ASSERT_EQ(fp.size(), 6 * static_cast<Index>(s.faces.size()));
  double area = 0.0;
  std::vector<double> integral(static_cast<std::size_t>(qm.num_points()), 0.0);
  for (Index q = 0; q < fp.size(); ++q) {
    const std::size_t qq = static_cast<std::size_t>(q);
    area += fp.weight[qq];
    for (Index i = fp.start[qq]; i < fp.start[qq + 1]; ++i)
      integral[static_cast<std::size_t>(fp.node[static_cast<std::size_t>(i)])] +=
          fp.weight[qq] * fp.shape[static_cast<std::size_t>(i)];
    // The rest point lies on the boundary of the cube.
    const Vec3& x = fp.rest[qq];
    const double to_face = std::min({x.minCoeff(), L - x.maxCoeff()});
    EXPECT_NEAR(to_face, 0.0, 1e-15);
  }
  EXPECT_NEAR(area, 6 * L * L, 1e-15);
  // Corners: int N_a = 0 on every face. Midside nodes: A_f / 3 per adjacent face; the face
  // diagonals' nodes have 2 faces of area h^2/2, the cell edges' 2 (on a face) or 4 (cube edge).
  for (Index v = 0; v < qm.num_vertices; ++v) EXPECT_NEAR(integral[static_cast<std::size_t>(v)], 0.0, 1e-18);
  double midside = 0.0;
  for (Index p = qm.num_vertices; p < qm.num_points(); ++p) midside += integral[static_cast<std::size_t>(p)];
  EXPECT_NEAR(midside, 6 * L * L, 1e-15);
}

TEST(ContactFacePoints, UniformPenetrationGivesTheConsistentQuadraticLoad) {
  const double L = 0.01, depth = 1e-4;
  QuadraticSample s(L, 2, {{false, false, true}});  // z held everywhere: the face stays put
  RigidBody plane = RigidBody::plane("top", Vec3(0, 0, L), -Vec3::UnitZ());
  plane.displacement = Vec3(0, 0, -depth);
  plane.function = TimeFunction::ramp(0.0, 1.0);
  ContactOptions opt;
  opt.method = ContactMethod::Penalty;
  opt.stiffness = 50.0;  // N/m for a vertex: eps_a = 50 / (area per boundary vertex)
  VecX u = VecX::Zero(s.system->num_dofs());
  ContactStaticSolver solver(*s.system, s.mesh, &s.qm, {plane}, opt, NewtonOptions{}, 0.0, u);
  EXPECT_FALSE(solver.points().nodal);
  const ContactSurface& surf = solver.surface();
  ASSERT_EQ(solver.points().num_constraints(), static_cast<Index>(surf.faces.size()));
  double area = 0.0;
  for (double a : surf.face_area) area += a;
  // eps_a = eps N_b / S, S = sum_f sum_a (int_f N_a)^2 / A_f = sum_f 3 (A_f/3)^2 / A_f = area / 3.
  EXPECT_NEAR(solver.stiffness(), 50.0 * static_cast<double>(solver.points().nodes.size()) / (area / 3.0),
              1e-9 * solver.stiffness());
  const ContactStepReport rep = solver.advance(0.0, 1.0, u);
  const ContactBodyState& b = rep.bodies[0];
  const double pressure = solver.stiffness() * depth, total = pressure * L * L;
  EXPECT_EQ(b.active_nodes, 8);  // the top face's 8 triangles
  EXPECT_NEAR(b.force.z(), total, 1e-12 * total);
  EXPECT_NEAR(b.force.head<2>().norm(), 0.0, 1e-12 * total);
  EXPECT_NEAR(b.area, L * L, 1e-15);
  Vec3 sum = Vec3::Zero();
  double corners = 0.0;
  for (std::size_t i = 0; i < b.nodes.size(); ++i) {
    const Index n = b.nodes[i];
    sum += b.nodal_force[i];
    if (!s.qm.is_midside(n)) {
      corners = std::max(corners, b.nodal_force[i].norm());
      continue;
    }
    // A midside node of the top face carries a third of each adjacent top triangle's load.
    const Edge& e = s.qm.edges[static_cast<std::size_t>(n - s.qm.num_vertices)];
    double adjacent = 0.0;
    for (std::size_t f = 0; f < surf.faces.size(); ++f) {
      const Tri& t = surf.faces[f];
      const bool top = surf.face_normal[f].z() > 0.5;
      const bool has = std::count(t.begin(), t.end(), e[0]) + std::count(t.begin(), t.end(), e[1]) == 2;
      if (top && has) adjacent += surf.face_area[f];
    }
    EXPECT_NEAR(b.nodal_force[i].z(), -pressure * adjacent / 3.0, 1e-12 * total) << "node " << n;
    EXPECT_NEAR(b.pressure[i], pressure, 1e-9 * pressure);
  }
  EXPECT_LT(corners, 1e-12 * total);
  EXPECT_NEAR(sum.z(), -total, 1e-12 * total);
}

TEST(ContactFacePoints, ContactTermsMatchFiniteDifferences) {
  const double L = 0.01;
  QuadraticSample s(L, 2, {});
  const double R = 0.5 * L;
  RigidBody sphere = RigidBody::sphere("s", Vec3(0.4 * L, 0.45 * L, L + R), R);
  sphere.displacement = Vec3(0, 0, -0.1 * L);
  sphere.function = TimeFunction::ramp(0.0, 1.0);
  RigidBody glue = RigidBody::plane("glue", Vec3(0, 0, 0), Vec3::UnitZ());
  glue.mode = ContactMode::Bonded;
  ContactOptions opt;
  opt.stiffness = 1000.0;
  VecX u = VecX::Zero(s.system->num_dofs());
  ContactStaticSolver solver(*s.system, s.mesh, &s.qm, {sphere, glue}, opt, NewtonOptions{}, 0.0, u);
  const ContactStepReport rep = solver.advance(0.0, 1.0, u);
  ASSERT_GE(rep.bodies[0].active_nodes, 1);
  EXPECT_EQ(rep.bodies[1].active_nodes, 8);  // every triangle of the glued bottom face
  // Equilibrium of the springs with the contact forces: the springs' total k sum u is the force
  // the bodies exert on the sample, minus the force the sample exerts on them.
  VecX f;
  s.model->internal_force(u, f);
  Vec3 spring = Vec3::Zero();
  for (Index i = 0; i < s.qm.num_points(); ++i) spring += f.segment<3>(3 * i);
  ASSERT_GT(spring.norm(), 0.0);
  EXPECT_NEAR((spring + rep.bodies[0].force + rep.bodies[1].force).norm(), 0.0,
              1e-6 * rep.bodies[0].force.norm());

  std::mt19937 rng(5);
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
  J *= 0.0;
  const Eigen::Index nnz = J.nonZeros();
  solver.add_contact_terms(u, 1.0, nullptr, &J, nullptr);
  EXPECT_EQ(J.nonZeros(), nnz);  // the P2 node graph holds the contact tangent
  const VecX r = residual(u);
  ASSERT_GT(r.norm(), 0.0);
  const double h = 1e-7 * L;
  for (int k = 0; k < 5; ++k) {
    VecX v(n);
    for (Eigen::Index i = 0; i < n; ++i) v[i] = U(rng);
    const double fd = (energy(u + h * v) - energy(u - h * v)) / (2 * h);
    EXPECT_NEAR(fd, r.dot(v), 1e-6 * r.norm() * v.norm()) << k;
    const VecX jfd = (residual(u + h * v) - residual(u - h * v)) / (2 * h);
    EXPECT_LE((jfd - J * v).norm(), 1e-6 * (J * v).norm()) << k;
  }
}

TEST(ContactFacePoints, PenetrationAtTheStartIsRefused) {
  const double L = 0.01;
  QuadraticSample s(L, 2, {});
  // A sphere dipping 1e-3 L into the top face above one of its quadrature points, clear of every
  // node (the penetrated disc's radius sqrt(2 R 1e-3 L) = 0.02 L is shorter than any point's
  // distance to a node): only the face points see it.
  const ContactPoints fp = ContactPoints::at_face_quadrature(s.qm, ContactSurface::extract(s.mesh));
  Index top = -1;
  for (Index q = 0; q < fp.size() && top < 0; ++q)
    if (fp.rest[static_cast<std::size_t>(q)].z() > L - 1e-12) top = q;
  ASSERT_GE(top, 0);
  const double R = 0.2 * L;
  RigidBody sphere =
      RigidBody::sphere("s", fp.rest[static_cast<std::size_t>(top)] + Vec3(0, 0, R - 1e-3 * L), R);
  VecX u = VecX::Zero(s.system->num_dofs());
  try {
    ContactStaticSolver solver(*s.system, s.mesh, &s.qm, {sphere}, ContactOptions{}, NewtonOptions{}, 0.0, u);
    ADD_FAILURE() << "not refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("quadrature point"), std::string::npos) << e.what();
  }
}

TEST(ContactFacePoints, SphereConvergesInAFewOuterIterations) {
  // A sphere pressed 0.1 L into the top of a 4^3 block of springs with the default options
  // (eps from the stiffness factor, gap_tol, 30 outer iterations): one multiplier per face settles
  // in a few outer iterations per increment.
  const double L = 0.01;
  QuadraticSample s(L, 4, {});
  const double R = 0.4 * L;
  RigidBody sphere = RigidBody::sphere("s", Vec3(0.52 * L, 0.47 * L, L + R), R);
  sphere.displacement = Vec3(0, 0, -0.1 * L);
  sphere.function = TimeFunction::ramp(0.0, 1.0);
  VecX u = VecX::Zero(s.system->num_dofs());
  ContactStaticSolver solver(*s.system, s.mesh, &s.qm, {sphere}, ContactOptions{}, NewtonOptions{}, 0.0, u);
  int most = 0;
  for (int step = 1; step <= 2; ++step) {
    const ContactStepReport rep = solver.advance(0.5 * (step - 1), 0.5 * step, u);
    EXPECT_EQ(rep.solver.cutbacks, 0) << step;
    most = std::max(most, rep.outer_iterations_total);
    EXPECT_LE(rep.natural_residual, solver.gap_tol());
  }
  EXPECT_LE(most, 8);
  std::printf("[ measured ] P2 sphere on springs: at most %d outer iterations per increment\n", most);
  const ContactBodyState& b = solver.state()[0];
  ASSERT_GE(b.active_nodes, 3);
  EXPECT_GT(b.force.z(), 0.0);
  EXPECT_GE(b.min_multiplier, 0.0);
  // Complementarity per face: A_f lambda_f |g_f| <= A_f lambda_f gap_tol, and A_f lambda_f < 2 |F| (the
  // contact normals are within 37 degrees of the axis here); no face penetrates by more than gap_tol
  // on average.
  EXPECT_LE(b.complementarity, 2.0 * b.force.norm() * solver.gap_tol());
  const ContactPoints& pts = solver.points();
  for (Index c = 0; c < pts.num_constraints(); ++c) {
    double g = 0.0;
    for (Index q = pts.group[static_cast<std::size_t>(c)]; q < pts.group[static_cast<std::size_t>(c) + 1];
         ++q)
      g += pts.weight[static_cast<std::size_t>(q)] * sphere.gap(pts.position(u, q), 1.0).g;
    EXPECT_GE(g / pts.group_area[static_cast<std::size_t>(c)], -solver.gap_tol()) << "face " << c;
  }
}

}  // namespace
}  // namespace tmlab::tm
