// The solver's internals (deal.II level):
//   * the assembled tangent is the derivative of the assembled residual (central differences),
//     for every law, P1/P2 simplices and Q2 hexahedra, with and without Prony history;
//   * the fast model's 10-node tet (tensormass/kernels/hyperelastic_p2.hpp), standard and with mean
//     dilatation, has the reference's P2 energy, force and tangent on the same mesh to round-off, for
//     every law;
//   * mean dilatation (F-bar per cell, the fast model's p2_mean_dilatation): the tangent is the
//     derivative of the residual and the residual that of the energy (central differences), for every
//     law on P2 tets (and Q2 hexes); on an affine field its residual and energy are the standard
//     element's (so a homogeneous solution is one of both), on a non-affine field they are not;
//   * (3) refinement study with a manufactured solution (body force b0 = -Div P(u_exact), exact
//     Dirichlet data on the whole boundary): L2 and H1 errors converge at the rates k+1 and k of
//     P1 and P2 (the finest P2 level is labelled slow);
//   * the triangulation built from tmlab's mesh (vertex i = node i, cell c = tet c) is the one
//     deal.II's own GridIn::read_msh builds from the same file;
//   * the IDA form (ida_dae.hpp): the initial state is a zero residual, and the Newton matrix's
//     solve inverts the central differences of the residual, dF/dy + alpha dF/dy';
//   * the contact terms (contact.hpp): the residual is the derivative of the contact potential and
//     the blocks that of the residual (central differences), on a sphere pressed into a block, for
//     the vertex rule (P1) and the face-point rule (P2, frictionless and bonded); the face-point
//     rule turns a uniform penetration of a flat face into the consistent P2 pressure load
//     (nothing on the corners, the Solid's own dead-pressure assembly), which the vertex rule does not.
// (The same files end to end: test_reference_ida, test_reference_runner.)
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/quadratic_mesh.hpp"
#include "reference_fem/dealii/contact.hpp"
#include "reference_fem/dealii/ida_dae.hpp"
#include "reference_fem/dealii/solid.hpp"
#include "tensormass/kernels/hyperelastic_p2.hpp"
#include "tensormass/materials/law_factory.hpp"

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <random>
#include <set>

namespace tmlab::ref {
namespace {

using namespace dealii;

void make_cube(Triangulation<3>& tria, bool simplex, unsigned n) {
  if (simplex)
    GridGenerator::subdivided_hyper_cube_with_simplices(tria, n, 0.0, 1.0);
  else
    GridGenerator::subdivided_hyper_cube(tria, n, 0.0, 1.0);
}

// ---- consistent tangent -------------------------------------------------------------------------

double tangent_fd_error(const std::string& law, bool simplex, unsigned degree, bool with_prony) {
  Triangulation<3> coarse;
  make_cube(coarse, simplex, 2);
  const Material m = Material::make(law, 1000.0, 0.35, 1.5, 0.5);
  std::optional<PronySeries> p;
  if (with_prony)
    p = PronySeries::make(PronyConvention::LongTerm, {0.8, 0.3}, {0.1, 1.0}, PronyIntegration::Midpoint,
                          PronyRelaxation::Full);
  Solid s(MPI_COMM_SELF, coarse, Discretisation{simplex, degree}, m, p, NewtonParameters{});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  TrilinosWrappers::MPI::Vector u(s.locally_owned_dofs(), MPI_COMM_SELF), v(u), up(u), um(u), r0, rp, rm,
      Kv(u);
  for (auto i : s.locally_owned_dofs()) {
    u[i] = 0.03 * d(rng);
    v[i] = d(rng);
  }
  u.compress(VectorOperation::insert);
  v.compress(VectorOperation::insert);
  TrilinosWrappers::SparseMatrix K;
  s.residual_and_tangent(u, 1.0, 0.05, r0, &K);
  K.vmult(Kv, v);
  const double h = 1e-6;
  up = u;
  up.add(h, v);
  um = u;
  um.add(-h, v);
  s.residual_and_tangent(up, 1.0, 0.05, rp, nullptr);
  s.residual_and_tangent(um, 1.0, 0.05, rm, nullptr);
  TrilinosWrappers::MPI::Vector fd(rp);
  fd -= rm;
  fd /= 2 * h;
  fd -= Kv;
  return fd.l2_norm() / Kv.l2_norm();
}

TEST(ReferenceSolid, TangentIsTheDerivativeOfTheResidual) {
  for (const std::string law : {"stvk", "neo_hookean", "yeoh"})
    for (const auto& [simplex, degree] :
         std::vector<std::pair<bool, unsigned>>{{true, 1}, {true, 2}, {false, 2}}) {
      const double e = tangent_fd_error(law, simplex, degree, false);
      EXPECT_LE(e, 1e-7) << law << (simplex ? " P" : " Q") << degree;
      std::printf("[ measured ] tangent vs central differences, %s %s%u: %.2e\n", law.c_str(),
                  simplex ? "P" : "Q", degree, e);
    }
  const double e = tangent_fd_error("neo_hookean", true, 2, true);
  EXPECT_LE(e, 1e-7) << "with Prony history";
  std::printf("[ measured ] tangent vs central differences, neo_hookean P2 + Prony: %.2e\n", e);
}

// ---- mean dilatation (F-bar per cell) --------------------------------------------------------------

/// Every law of materials.hpp as a case file gives it (the fast model builds its law from the same
/// parameters), nu about 0.45 and some strain stiffening.
std::vector<std::pair<MaterialLaw, LawParameters>> every_law_parameters() {
  std::vector<std::pair<MaterialLaw, LawParameters>> out;
  LawParameters ep;
  ep.young = 1000.0, ep.poisson = 0.45;
  out.emplace_back(MaterialLaw::StVK, ep);
  out.emplace_back(MaterialLaw::NeoHookean, ep);
  LawParameters ye;
  ye.c10 = 170.0, ye.c20 = 250.0, ye.c30 = 80.0, ye.kappa = 3500.0;
  out.emplace_back(MaterialLaw::Yeoh, ye);
  LawParameters mr;
  mr.c10 = 150.0, mr.c01 = 50.0, mr.kappa = 4000.0;
  out.emplace_back(MaterialLaw::MooneyRivlin, mr);
  LawParameters og;
  og.mu = {300.0, -20.0}, og.alpha = {2.5, -2.0}, og.kappa = 5000.0;
  out.emplace_back(MaterialLaw::Ogden, og);
  LawParameters vw;
  vw.c1 = 200.0, vw.c2 = 1.5, vw.kappa = 6000.0;
  out.emplace_back(MaterialLaw::VerondaWestmann, vw);
  return out;
}

std::vector<std::pair<std::string, Material>> every_law() {
  std::vector<std::pair<std::string, Material>> out;
  for (const auto& [law, p] : every_law_parameters())
    out.emplace_back(to_string(law), Material::make(law, p));
  return out;
}

/// A Solid on the unit cube (2^3 cells, tets or hexes) without loads, so that its residual is the
/// internal force.
std::unique_ptr<Solid> unloaded_cube(Triangulation<3>& coarse, const Material& m, bool simplex,
                                     unsigned degree, bool mean_dilatation) {
  make_cube(coarse, simplex, 2);
  return std::make_unique<Solid>(MPI_COMM_SELF, coarse, Discretisation{simplex, degree, mean_dilatation}, m,
                                 std::nullopt, NewtonParameters{});
}

TrilinosWrappers::MPI::Vector random_field(const Solid& s, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  TrilinosWrappers::MPI::Vector u(s.locally_owned_dofs(), MPI_COMM_SELF);
  for (auto i : s.locally_owned_dofs()) u[i] = amplitude * d(rng);
  u.compress(VectorOperation::insert);
  return u;
}

double energy_at(const Solid& s, const TrilinosWrappers::MPI::Vector& u) {
  TrilinosWrappers::MPI::Vector g(s.locally_owned_dofs(), s.locally_relevant_dofs(), MPI_COMM_SELF);
  g = u;
  return s.hyperelastic_energy(g);
}

TEST(ReferenceSolidMeanDilatation, TangentAndForceAreTheDerivativesForEveryLaw) {
  for (const auto& [name, m] : every_law())
    for (const auto& [simplex, degree] : std::vector<std::pair<bool, unsigned>>{{true, 2}, {false, 2}}) {
      if (!simplex && name != "neo_hookean") continue;  // one law on Q2 hexes
      Triangulation<3> coarse;
      const auto s = unloaded_cube(coarse, m, simplex, degree, true);
      const auto u = random_field(*s, 0.03, 7), v = random_field(*s, 1.0, 11);
      TrilinosWrappers::MPI::Vector r0, rp, rm, Kv(u), up(u), um(u);
      TrilinosWrappers::SparseMatrix K;
      s->residual_and_tangent(u, 1.0, 0.0, r0, &K);
      K.vmult(Kv, v);
      // The tangent: K v against (R(u + h v) - R(u - h v)) / 2h.
      const double h = 1e-6;
      up.add(h, v);
      um.add(-h, v);
      s->residual_and_tangent(up, 1.0, 0.0, rp, nullptr);
      s->residual_and_tangent(um, 1.0, 0.0, rm, nullptr);
      TrilinosWrappers::MPI::Vector fd(rp);
      fd -= rm;
      fd /= 2 * h;
      fd -= Kv;
      const double ek = fd.l2_norm() / Kv.l2_norm();
      // The force: R(u) . v against the fourth-order central difference of W(u + h v).
      const double he = 1e-5;
      auto W = [&](double a) {
        TrilinosWrappers::MPI::Vector x(u);
        x.add(a, v);
        return energy_at(*s, x);
      };
      const double dW = (8.0 * (W(he) - W(-he)) - (W(2 * he) - W(-2 * he))) / (12.0 * he), rv = r0 * v;
      const double ef = std::abs(dW - rv) / std::abs(rv);
      EXPECT_LE(ek, 1e-7) << name << (simplex ? " P" : " Q") << degree;
      EXPECT_LE(ef, 1e-8) << name << (simplex ? " P" : " Q") << degree;
      std::printf(
          "[ measured ] mean dilatation %s %s%u: tangent vs central differences %.2e, force vs "
          "energy differences %.2e\n",
          name.c_str(), simplex ? "P" : "Q", degree, ek, ef);
    }
}

TEST(ReferenceSolidMeanDilatation, EqualsTheStandardElementOnAnAffineField) {
  // u = (F0 - I) X: F is F0 at every point, so J_q = Jbar and Fbar = F. The P2 interpolant of an
  // affine field is exact, so setting the DoFs at their support points gives it.
  const Material m = Material::make("neo_hookean", 1000.0, 0.45);
  Triangulation<3> ca, cb;
  const auto md = unloaded_cube(ca, m, true, 2, true), st = unloaded_cube(cb, m, true, 2, false);
  Tensor<2, 3> H;  // F0 - I: stretch, shear and a volume change
  H[0][0] = 0.12, H[0][1] = 0.05, H[1][1] = -0.04, H[1][2] = 0.07, H[2][0] = -0.03, H[2][2] = 0.09;
  std::map<global_dof_index, Point<3>> support;
  DoFTools::map_dofs_to_support_points(md->mapping(), md->dof_handler(), support);
  TrilinosWrappers::MPI::Vector u(md->locally_owned_dofs(), MPI_COMM_SELF);
  std::vector<global_dof_index> dofs(md->fe().n_dofs_per_cell());
  for (const auto& cell : md->dof_handler().active_cell_iterators()) {
    cell->get_dof_indices(dofs);
    for (unsigned i = 0; i < dofs.size(); ++i)
      u[dofs[i]] = (H * support.at(dofs[i]))[md->fe().system_to_component_index(i).first];
  }
  u.compress(VectorOperation::insert);
  ASSERT_EQ(md->n_dofs(), st->n_dofs());  // the same DoF numbering: the same mesh and element
  // Residual and energy agree (sum_q w_q l_qi = 0 when every J_q is Jbar); the tangents do not, and
  // need not: l_qi, the derivative of ln alpha_q, is not zero there (the F-bar element's stiffness to
  // non-affine variations is its own).
  TrilinosWrappers::MPI::Vector ra, rb;
  md->residual_and_tangent(u, 1.0, 0.0, ra, nullptr);
  st->residual_and_tangent(u, 1.0, 0.0, rb, nullptr);
  TrilinosWrappers::MPI::Vector d(ra);
  d -= rb;
  // Interior DoFs have zero force under a homogeneous stress: relative to the boundary forces.
  const double er = d.l2_norm() / rb.l2_norm();
  const double wa = energy_at(*md, u), wb = energy_at(*st, u), ew = std::abs(wa - wb) / wb;
  EXPECT_LE(er, 1e-13);
  EXPECT_LE(ew, 1e-13);
  std::printf(
      "[ measured ] affine field: mean dilatation vs standard P2, residual %.2e, energy %.2e "
      "(relative)\n",
      er, ew);
  // A non-affine field: the two elements differ (the option does something).
  const auto w = random_field(*md, 0.03, 9);
  md->residual_and_tangent(w, 1.0, 0.0, ra, nullptr);
  st->residual_and_tangent(w, 1.0, 0.0, rb, nullptr);
  d = ra;
  d -= rb;
  const double en = d.l2_norm() / rb.l2_norm();
  EXPECT_GE(en, 1e-3);
  std::printf("[ measured ] random field: mean dilatation vs standard P2 residual %.2e (relative)\n", en);
}

/// The reference's P2 (standard or mean dilatation) and the fast model's HyperelasticP2 on the same
/// mesh evaluated at the same displacement field: max over energy, internal force and tangent times a
/// vector of the relative differences. DoFs are matched through their support points (the deal.II
/// P2 edge DoFs sit at the edge midpoints, as the quadratic mesh's midside nodes).
struct SameMeshDifferences {
  double energy = 0.0, force = 0.0, tangent = 0.0;
};

SameMeshDifferences fast_vs_reference(MaterialLaw law, const LawParameters& params, bool mean_dilatation) {
  const Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3(0.02, 0.01, 0.01), 3, 2, 2);
  const QuadraticMesh qm = make_quadratic(mesh);
  tm::P2Options po;
  po.volumetric =
      mean_dilatation ? tm::P2Options::Volumetric::MeanDilatation : tm::P2Options::Volumetric::Standard;
  const tm::HyperelasticP2 fast(qm, tm::make_law(law, params, "test"), po);

  std::vector<Point<3>> points;
  for (const Vec3& x : mesh.points) points.emplace_back(x[0], x[1], x[2]);
  std::vector<std::array<unsigned, 4>> tets;
  for (const auto& t : mesh.tets)
    tets.push_back({static_cast<unsigned>(t[0]), static_cast<unsigned>(t[1]), static_cast<unsigned>(t[2]),
                    static_cast<unsigned>(t[3])});
  Triangulation<3> coarse;
  build_tet_triangulation(points, tets, coarse);
  Solid s(MPI_COMM_SELF, coarse, Discretisation{true, 2, mean_dilatation}, Material::make(law, params),
          std::nullopt, NewtonParameters{});

  // DoF d of the reference = component c of node a of the quadratic mesh: fast index 3 a + c.
  std::map<global_dof_index, Point<3>> support;
  DoFTools::map_dofs_to_support_points(s.mapping(), s.dof_handler(), support);
  std::vector<Eigen::Index> fast_index(s.n_dofs(), -1);
  std::vector<global_dof_index> dofs(s.fe().n_dofs_per_cell());
  for (const auto& cell : s.dof_handler().active_cell_iterators()) {
    cell->get_dof_indices(dofs);
    for (unsigned i = 0; i < dofs.size(); ++i) {
      const Point<3>& x = support.at(dofs[i]);
      Index node = -1;
      for (Index a = 0; a < qm.num_points() && node < 0; ++a)
        if ((qm.points[static_cast<std::size_t>(a)] - Vec3(x[0], x[1], x[2])).norm() < 1e-12) node = a;
      if (node < 0) throw std::runtime_error("no quadratic-mesh node at a P2 support point");
      fast_index[dofs[i]] = 3 * node + s.fe().system_to_component_index(i).first;
    }
  }
  // A non-affine field with gradients up to ~0.1 and a direction.
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  TrilinosWrappers::MPI::Vector u(s.locally_owned_dofs(), MPI_COMM_SELF), v(u), r, Kv(u);
  tm::VecX uf(fast.num_dofs()), vf(fast.num_dofs()), ff, Kvf;
  for (auto i : s.locally_owned_dofs()) {
    u[i] = uf[fast_index[i]] = 2e-4 * d(rng);
    v[i] = vf[fast_index[i]] = d(rng);
  }
  u.compress(VectorOperation::insert);
  v.compress(VectorOperation::insert);
  TrilinosWrappers::SparseMatrix K;
  s.residual_and_tangent(u, 1.0, 0.0, r, &K);  // no loads: r = f_int
  K.vmult(Kv, v);
  fast.internal_force(uf, ff);
  fast.tangent_apply(uf, vf, Kvf);
  double df = 0.0, nf = 0.0, dk = 0.0, nk = 0.0;
  for (auto i : s.locally_owned_dofs()) {
    df += std::pow(r[i] - ff[fast_index[i]], 2), nf += r[i] * r[i];
    dk += std::pow(Kv[i] - Kvf[fast_index[i]], 2), nk += Kv[i] * Kv[i];
  }
  const double we = energy_at(s, u), wf = fast.energy(uf);
  return {std::abs(we - wf) / std::abs(we), std::sqrt(df / nf), std::sqrt(dk / nk)};
}

TEST(ReferenceSolidMeanDilatation, EqualsTheFastModelsP2ElementsOnTheSameMesh) {
  // The discrete equations are the same (same rule, QGaussSimplex<3>(3); same F-bar; same laws), so
  // energy, force and tangent agree to round-off: P2 and P2 with mean dilatation, every law.
  for (const auto& [law, params] : every_law_parameters())
    for (const bool md : {false, true}) {
      const SameMeshDifferences e = fast_vs_reference(law, params, md);
      EXPECT_LE(e.energy, 1e-12) << to_string(law) << (md ? " mean dilatation" : "");
      EXPECT_LE(e.force, 1e-12) << to_string(law) << (md ? " mean dilatation" : "");
      EXPECT_LE(e.tangent, 1e-12) << to_string(law) << (md ? " mean dilatation" : "");
      std::printf(
          "[ measured ] fast HyperelasticP2%s vs reference, %s: energy %.2e, force %.2e, tangent "
          "%.2e (relative)\n",
          md ? " mean dilatation" : "", to_string(law).c_str(), e.energy, e.force, e.tangent);
    }
}

TEST(ReferenceSolidMeanDilatation, RefusesPronyHistory) {
  Triangulation<3> coarse;
  make_cube(coarse, true, 1);
  const auto p = PronySeries::make(PronyConvention::LongTerm, {0.5}, {0.1}, PronyIntegration::Midpoint,
                                   PronyRelaxation::Full);
  try {
    Solid s(MPI_COMM_SELF, coarse, Discretisation{true, 2, true}, Material::make("neo_hookean", 1000.0, 0.3),
            p, NewtonParameters{});
    FAIL() << "Prony history accepted with mean dilatation";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("mean-dilatation"), std::string::npos) << e.what();
  }
}

// ---- manufactured solution ----------------------------------------------------------------------

constexpr double kA = 0.1;  // amplitude: displacement gradients up to ~0.3

class ExactSolution : public Function<3> {
 public:
  ExactSolution() : Function<3>(3) {}
  double value(const Point<3>& X, const unsigned c) const override {
    const double x = X[0], y = X[1], z = X[2];
    if (c == 0) return kA * std::sin(x + 2 * y);
    if (c == 1) return kA * std::cos(2 * x - z);
    return kA * std::sin(y * z + x);
  }
  Tensor<1, 3> gradient(const Point<3>& X, const unsigned c) const override {
    const double x = X[0], y = X[1], z = X[2];
    Tensor<1, 3> g;
    if (c == 0) {
      g[0] = kA * std::cos(x + 2 * y), g[1] = 2 * kA * std::cos(x + 2 * y);
    } else if (c == 1) {
      g[0] = -2 * kA * std::sin(2 * x - z), g[2] = kA * std::sin(2 * x - z);
    } else {
      const double cc = kA * std::cos(y * z + x);
      g[0] = cc, g[1] = z * cc, g[2] = y * cc;
    }
    return g;
  }
};

/// b0 = -Div P(F(X)), P = F S(E), by fourth-order central differences of the exact P.
Tensor<1, 3> manufactured_body_force(const Material& m, const Point<3>& X) {
  const ExactSolution u;
  auto P = [&](const Point<3>& Y) {
    Tensor<2, 3> F = unit_symmetric_tensor<3>();
    for (unsigned c = 0; c < 3; ++c) F[c] += u.gradient(Y, c);
    const SymTensor2 E = 0.5 * (symmetrize(transpose(F) * F) - unit_symmetric_tensor<3>());
    return Tensor<2, 3>(F * Tensor<2, 3>(m.stress(E)));
  };
  const double h = 1e-3;
  Tensor<1, 3> div;
  for (unsigned j = 0; j < 3; ++j) {
    Tensor<1, 3> e;
    e[j] = h;
    const Tensor<2, 3> dP = (8.0 * (P(X + e) - P(X - e)) - (P(X + 2 * e) - P(X - 2 * e))) / (12.0 * h);
    for (unsigned i = 0; i < 3; ++i) div[i] += dP[i][j];
  }
  return -div;
}

struct Errors {
  double l2, h1;
  global_dof_index dofs;
};

Errors mms_errors(unsigned degree, unsigned n, LinearSolver solver = LinearSolver::Direct) {
  Triangulation<3> coarse;
  make_cube(coarse, true, n);
  const Material m = Material::make("neo_hookean", 1000.0, 0.3);
  NewtonParameters np;
  np.linear_solver = solver;
  Solid s(MPI_COMM_SELF, coarse, Discretisation{true, degree}, m, std::nullopt, np);
  const ExactSolution exact;
  const int cond = s.add_condition("boundary", TimeFunction::ramp(0.0, 1.0));
  std::map<global_dof_index, Point<3>> support;
  DoFTools::map_dofs_to_support_points(s.mapping(), s.dof_handler(), support);
  const IndexSet boundary = DoFTools::extract_boundary_dofs(s.dof_handler());
  std::vector<global_dof_index> dofs(s.fe().n_dofs_per_cell());
  for (const auto& cell : s.dof_handler().active_cell_iterators()) {
    cell->get_dof_indices(dofs);
    for (unsigned i = 0; i < dofs.size(); ++i)
      if (boundary.is_element(dofs[i])) {
        const unsigned c = s.fe().system_to_component_index(i).first;
        s.prescribe(dofs[i], c, cond, exact.value(support.at(dofs[i]), c));
      }
  }
  const int lf = s.add_load_function(TimeFunction::ramp(0.0, 1.0));
  s.add_body_force([m](const Point<3>& X) { return manufactured_body_force(m, X); }, lf);
  s.advance(0.0, 0.5);
  s.advance(0.5, 1.0);
  Vector<float> cellwise(coarse.n_active_cells());
  const QGaussSimplex<3> q(degree + 2);
  VectorTools::integrate_difference(s.mapping(), s.dof_handler(), s.solution(), exact, cellwise, q,
                                    VectorTools::L2_norm);
  const double l2 = VectorTools::compute_global_error(s.triangulation(), cellwise, VectorTools::L2_norm);
  VectorTools::integrate_difference(s.mapping(), s.dof_handler(), s.solution(), exact, cellwise, q,
                                    VectorTools::H1_seminorm);
  const double h1 = VectorTools::compute_global_error(s.triangulation(), cellwise, VectorTools::H1_seminorm);
  return {l2, h1, s.n_dofs()};
}

void refinement_study(unsigned degree, const std::vector<unsigned>& ns,
                      LinearSolver solver = LinearSolver::Direct) {
  std::vector<Errors> e;
  for (unsigned n : ns) {
    e.push_back(mms_errors(degree, n, solver));
    const std::size_t k = e.size() - 1;
    if (k == 0)
      std::printf("[ measured ] P%u n=%2u dofs=%7u  L2 %.3e  H1 %.3e\n", degree, n,
                  static_cast<unsigned>(e[k].dofs), e[k].l2, e[k].h1);
    else
      std::printf("[ measured ] P%u n=%2u dofs=%7u  L2 %.3e (rate %.2f)  H1 %.3e (rate %.2f)\n", degree, n,
                  static_cast<unsigned>(e[k].dofs), e[k].l2, std::log2(e[k - 1].l2 / e[k].l2), e[k].h1,
                  std::log2(e[k - 1].h1 / e[k].h1));
  }
  const std::size_t k = e.size() - 1;
  EXPECT_GT(std::log2(e[k - 1].l2 / e[k].l2), degree + 1 - 0.3) << "L2 rate of P" << degree;
  EXPECT_GT(std::log2(e[k - 1].h1 / e[k].h1), degree - 0.2) << "H1 rate of P" << degree;
}

TEST(ReferenceSolid, ManufacturedSolutionConvergesAtTheExpectedRates) {
  refinement_study(1, {2, 4, 8});
  refinement_study(2, {2, 4, 8});
}

TEST(ReferenceSolidSlow, ManufacturedSolutionP2Fine) { refinement_study(2, {8, 16}, LinearSolver::CgAmg); }

// ---- GridIn ---------------------------------------------------------------------------------------

TEST(ReferenceSolid, TriangulationFromTmlabMeshIsTheOneGridInReads) {
  const std::string file = std::string(TMLAB_SOURCE_DIR) + "/meshes/cube_n2.msh";
  const Mesh mesh = read_mesh(file);
  std::vector<Point<3>> pts;
  for (const auto& p : mesh.points) pts.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::array<unsigned, 4>> tets;
  for (const auto& t : mesh.tets)
    tets.push_back({unsigned(t[0]), unsigned(t[1]), unsigned(t[2]), unsigned(t[3])});
  Triangulation<3> ours, theirs;
  build_tet_triangulation(pts, tets, ours);
  GridIn<3> gi;
  gi.attach_triangulation(theirs);
  std::ifstream in(file);
  gi.read_msh(in);
  ASSERT_EQ(ours.n_vertices(), theirs.n_vertices());
  ASSERT_EQ(ours.n_active_cells(), theirs.n_active_cells());
  for (unsigned i = 0; i < ours.n_vertices(); ++i)
    EXPECT_LE(ours.get_vertices()[i].distance(theirs.get_vertices()[i]), 1e-15) << "vertex " << i;
  auto a = ours.begin_active();
  auto b = theirs.begin_active();
  for (; a != ours.end(); ++a, ++b)
    for (unsigned v = 0; v < 4; ++v)
      EXPECT_EQ(a->vertex_index(v), b->vertex_index(v)) << "cell " << a->index();
  // And vertex i is node i of the tmlab mesh (the same order, so displacement.h5 columns match).
  for (unsigned i = 0; i < ours.n_vertices(); ++i) EXPECT_EQ(ours.get_vertices()[i], pts[i]);
}

// ---- the IDA form ---------------------------------------------------------------------------------

TEST(ReferenceIdaDae, NewtonMatrixSolveInvertsTheResidualsDerivative) {
  Triangulation<3> coarse;
  make_cube(coarse, true, 2);
  const PronySeries prony = PronySeries::make(PronyConvention::LongTerm, {0.8, 0.3}, {0.1, 1.0},
                                              PronyIntegration::Midpoint, PronyRelaxation::Full);
  Solid s(MPI_COMM_SELF, coarse, Discretisation{true, 1}, Material::make("neo_hookean", 1000.0, 0.35), prony,
          NewtonParameters{});
  // x = 0 clamped; x = 1 pulled along x by a ramp (prescribed values that move); gravity-like load.
  const int clamp = s.add_condition("clamp", TimeFunction::constant(1.0));
  const int pull = s.add_condition("pull", TimeFunction::ramp(0.0, 1.0));
  std::map<global_dof_index, Point<3>> support;
  DoFTools::map_dofs_to_support_points(s.mapping(), s.dof_handler(), support);
  std::set<global_dof_index> prescribed;
  std::vector<global_dof_index> dofs(s.fe().n_dofs_per_cell());
  for (const auto& cell : s.dof_handler().active_cell_iterators()) {
    cell->get_dof_indices(dofs);
    for (unsigned i = 0; i < dofs.size(); ++i) {
      const double x = support.at(dofs[i])[0];
      const unsigned c = s.fe().system_to_component_index(i).first;
      if (x < 1e-12) s.prescribe(dofs[i], c, clamp, 0.0);
      if (x > 1.0 - 1e-12 && c == 0) s.prescribe(dofs[i], c, pull, 0.05);
      if (x < 1e-12 || (x > 1.0 - 1e-12 && c == 0)) prescribed.insert(dofs[i]);
    }
  }
  const int load = s.add_load_function(TimeFunction::ramp(0.0, 1.0));
  s.add_body_force([](const Point<3>&) { return Tensor<1, 3>({0.0, 0.0, -200.0}); }, load);
  s.finalize_setup();
  QuasiStaticDae dae(s);
  ASSERT_EQ(dae.size(),
            dae.n_dofs() + std::size_t(6 * 2) * s.triangulation().n_active_cells() * s.quadrature().size());

  // At rest, t = 0, no rates: every row of F is zero.
  Vector<double> y = dae.initial_state(), yp(dae.size()), r(dae.size());
  ASSERT_EQ(dae.residual(0.0, y, yp, r), 0);
  EXPECT_LE(r.linfty_norm(), 1e-12);

  // A strained state with history and rates, mid-ramp.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  for (unsigned i = 0; i < dae.size(); ++i) {
    y[i] = i < dae.n_dofs() ? 0.02 * d(rng) : 20.0 * d(rng);  // m; Pa
    yp[i] = i < dae.n_dofs() ? 0.0 : 50.0 * d(rng);
  }
  const double t = 0.5, alpha = 20.0;
  ASSERT_EQ(dae.setup_jacobian(t, y, alpha), 0);
  Vector<double> b(dae.size()), x(dae.size());
  for (unsigned i = 0; i < dae.size(); ++i)
    b[i] = prescribed.count(i) ? 0.0 : (i < dae.n_dofs() ? 1.0 : 100.0) * d(rng);
  ASSERT_EQ(dae.solve_with_jacobian(b, x), 0);
  const double h = 1e-6 / x.linfty_norm();
  Vector<double> yh(y), yph(yp), rp(dae.size()), rm(dae.size());
  yh.add(h, x);
  yph.add(alpha * h, x);
  ASSERT_EQ(dae.residual(t, yh, yph, rp), 0);
  yh = y;
  yh.add(-h, x);
  yph = yp;
  yph.add(-alpha * h, x);
  ASSERT_EQ(dae.residual(t, yh, yph, rm), 0);
  Vector<double> jx(rp);
  jx -= rm;
  jx /= 2 * h;  // (dF/dy + alpha dF/dy') x by central differences
  jx -= b;
  const double e = jx.l2_norm() / b.l2_norm();
  EXPECT_LE(e, 1e-6);
  std::printf("[ measured ] IDA Newton matrix: |J (J^-1 b) - b| / |b| = %.2e\n", e);
}

// ---- contact terms --------------------------------------------------------------------------------

/// A unit block (4^3 Kuhn-split cells) as a Solid of the given degree, with each mesh node's vertex
/// DoFs (the runner's add_contact).
struct ContactBlock {
  Mesh mesh = make_box_mesh(Vec3::Zero(), Vec3::Constant(1.0), 4, 4, 4);  // a node at the top centre
  Triangulation<3> coarse;
  std::unique_ptr<Solid> solid;
  std::vector<std::array<global_dof_index, 3>> node_dofs;

  explicit ContactBlock(unsigned degree) {
    std::vector<Point<3>> pts;
    for (const auto& p : mesh.points) pts.emplace_back(p.x(), p.y(), p.z());
    std::vector<std::array<unsigned, 4>> tets;
    for (const auto& t : mesh.tets)
      tets.push_back({unsigned(t[0]), unsigned(t[1]), unsigned(t[2]), unsigned(t[3])});
    build_tet_triangulation(pts, tets, coarse);
    solid = std::make_unique<Solid>(MPI_COMM_SELF, coarse, Discretisation{true, degree},
                                    Material::make("stvk", 1000.0, 0.35), std::nullopt, NewtonParameters{});
    solid->finalize_setup();
    const auto vmap = coarse_vertex_map(*solid, coarse);
    node_dofs.resize(mesh.points.size());
    for (const auto& cell : solid->dof_handler().active_cell_iterators())
      for (unsigned v = 0; v < cell->n_vertices(); ++v)
        for (unsigned c = 0; c < 3; ++c)
          node_dofs[vmap[cell->active_cell_index()][v]][c] = cell->vertex_dof_index(v, c);
  }
  RigidContact contact(const ContactSpec& spec, ContactRule rule) const {
    return RigidContact(spec, "case.json", mesh, node_dofs, std::vector<char>(mesh.points.size(), 1),
                        MPI_COMM_SELF, rule);
  }
};

ContactSpec ball_spec(ContactBodyMode mode) {
  ContactSpec spec;
  spec.enabled = true;
  spec.stiffness = 1e3;
  ContactBodySpec ball;
  ball.name = "ball";
  ball.key = "contact.bodies[0]";
  ball.shape = ContactShape::Sphere;
  ball.mode = mode;
  ball.reference = Vec3(0.5, 0.5, 1.3);  // touching the top face at t = 0
  ball.radius = 0.3;
  ball.displacement = Vec3(0.0, 0.0, -0.2);
  ball.function = TimeFunction::ramp(0.0, 1.0);
  spec.bodies = {ball};
  return spec;
}

/// Central differences of the contact potential and residual at a random state, the ball 0.2 into
/// the block: returns |FD(r) - K v| / |K v| and checks r = dPhi/du.
double contact_fd_error(const ContactBlock& blk, RigidContact& contact) {
  Solid& s = *blk.solid;
  contact.start(s, 0.0, 1.0, std::vector<double>(3 * blk.mesh.points.size(), 0.0));
  contact.begin_increment();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  TrilinosWrappers::MPI::Vector u(s.locally_owned_dofs(), MPI_COMM_SELF), v(u), w(u), r(u), rp(u), rm(u),
      rhs(u), Kv(u);
  for (auto i : s.locally_owned_dofs()) {
    u[i] = 1e-3 * d(rng);
    v[i] = d(rng);
  }
  u.compress(VectorOperation::insert);
  v.compress(VectorOperation::insert);
  if (contact.rule() == ContactRule::FacePoints) {
    // Nonzero multipliers from the ball 0.1 in; a bonded ball glues the points it touches there.
    contact.update(u, 0.5);
    contact.commit(u, 0.5);
    contact.begin_increment();
  }
  const double t = 1.0;  // the ball 0.2 into the block: the middle of the top face is active
  TrilinosWrappers::SparseMatrix K;
  {
    TrilinosWrappers::MPI::Vector r0;
    s.residual_and_tangent(u, 0.0, 0.0, r0, &K);  // the pattern
    K = 0.0;
  }
  AffineConstraints<double> none;
  none.close();
  contact.add_terms(u, t, r, &none, &K, &rhs);
  EXPECT_GT(r.l2_norm(), 0.0) << "no point in contact";
  const double h = 1e-7;
  w = u;
  w.add(h, v);
  const double ep = contact.energy(w, t);
  contact.add_terms(w, t, rp, nullptr, nullptr, nullptr);
  w = u;
  w.add(-h, v);
  const double em = contact.energy(w, t);
  contact.add_terms(w, t, rm, nullptr, nullptr, nullptr);
  const double dphi = (ep - em) / (2 * h);
  EXPECT_NEAR(dphi, r * v, 1e-6 * std::abs(r * v));  // r = dPhi/du
  K.vmult(Kv, v);
  TrilinosWrappers::MPI::Vector fd(rp);
  fd -= rm;
  fd /= 2 * h;
  fd -= Kv;
  return fd.l2_norm() / Kv.l2_norm();
}

TEST(ReferenceNodalContact, TermsAreTheDerivativesOfTheContactPotential) {
  const ContactBlock blk(1);
  RigidContact contact = blk.contact(ball_spec(ContactBodyMode::Frictionless), ContactRule::Vertices);
  const double e = contact_fd_error(blk, contact);
  EXPECT_LE(e, 1e-5);  // K = d r / du
  std::printf("[ measured ] reference contact tangent vs central differences: %.2e\n", e);
}

TEST(ReferenceFaceContact, TermsAreTheDerivativesOfTheContactPotential) {
  const ContactBlock blk(2);
  for (ContactBodyMode mode : {ContactBodyMode::Frictionless, ContactBodyMode::Bonded}) {
    RigidContact contact = blk.contact(ball_spec(mode), ContactRule::FacePoints);
    const double e = contact_fd_error(blk, contact);
    EXPECT_LE(e, 1e-5) << to_string(mode);
    // 6 points on each of the 6 x 2 x 16 boundary triangles.
    EXPECT_EQ(contact.n_points(), 6u * 192u);
    std::printf("[ measured ] P2 face-point contact (%s) tangent vs central differences: %.2e\n",
                to_string(mode).c_str(), e);
  }
}

/// A rigid plane pushed 1e-4 into the top of the rest block (penalty, zero multipliers): every top
/// point has the same penetration, so the face-point rule presses the top with the uniform pressure
/// eps_a 1e-4. Its nodal forces are the consistent load of that pressure, the Solid's own dead
/// pressure on the top faces: on P2 nothing on the corner nodes and a third of each triangle's force
/// on each midside node. The vertex rule puts the whole load on the corners instead.
TEST(ReferenceFaceContact, UniformPenetrationGivesTheConsistentPressureLoad) {
  ContactSpec spec;
  spec.enabled = true;
  spec.method = ContactEnforcement::Penalty;
  spec.stiffness = 1e3;
  ContactBodySpec plane;
  plane.name = "platen";
  plane.key = "contact.bodies[0]";
  plane.shape = ContactShape::Plane;
  plane.reference = Vec3(0.0, 0.0, 1.0);
  plane.axis = Vec3(0.0, 0.0, -1.0);
  plane.displacement = Vec3(0.0, 0.0, -1e-4);
  plane.function = TimeFunction::ramp(0.0, 1.0);
  spec.bodies = {plane};
  for (ContactRule rule : {ContactRule::FacePoints, ContactRule::Vertices}) {
    ContactBlock blk(2);
    Solid& s = *blk.solid;
    RigidContact contact = blk.contact(spec, rule);
    contact.start(s, 0.0, 1.0, std::vector<double>(3 * blk.mesh.points.size(), 0.0));
    contact.begin_increment();
    TrilinosWrappers::MPI::Vector u(s.locally_owned_dofs(), MPI_COMM_SELF), r(u);
    contact.add_terms(u, 1.0, r, nullptr, nullptr, nullptr);
    r.compress(VectorOperation::add);

    // The consistent load of the same pressure, -f_ext (r = f_int - f_ext): the top faces (z = 1).
    const double p = (rule == ContactRule::FacePoints ? contact.stiffness() : 0.0) * 1e-4;
    ContactBlock ref(2);
    const int lf = ref.solid->add_load_function(TimeFunction::constant(1.0));
    for (const auto& cell : ref.solid->triangulation().active_cell_iterators())
      for (const unsigned f : cell->face_indices())
        if (cell->face(f)->at_boundary() && std::abs(cell->face(f)->center()[2] - 1.0) < 1e-12)
          ref.solid->add_pressure(cell->id(), f, lf, p);
    TrilinosWrappers::MPI::Vector fext;
    ref.solid->external_force(0.0, fext);

    // Vertex and edge DoFs of the top; the two DoF numberings are the same (same mesh, same FE).
    std::set<global_dof_index> corner;
    for (const auto& nd : blk.node_dofs)
      for (global_dof_index d : nd) corner.insert(d);
    double corner_max = 0.0, total = 0.0, err = 0.0;
    for (auto i : s.locally_owned_dofs()) {
      total += r[i];
      err = std::max(err, std::abs(r[i] + fext[i]));
      if (corner.count(i)) corner_max = std::max(corner_max, std::abs(r[i]));
    }
    if (rule == ContactRule::FacePoints) {
      const double F = p * 1.0;          // the pressure on the unit top face
      EXPECT_NEAR(total, F, 1e-12 * F);  // r_z = +p per unit area: the sample is pushed down
      EXPECT_LE(corner_max, 1e-14 * F);
      EXPECT_LE(err, 1e-13 * F);
      std::printf("[ measured ] face-point rule vs consistent P2 pressure load: %.2e of the force\n",
                  err / F);
    } else {
      // The vertex rule: eps 1e-4 on each of the 25 top vertices, nothing on the edge nodes.
      EXPECT_NEAR(total, 25 * 1e3 * 1e-4, 1e-12);
      EXPECT_NEAR(corner_max, 1e3 * 1e-4, 1e-13);
    }
  }
}

}  // namespace
}  // namespace tmlab::ref
