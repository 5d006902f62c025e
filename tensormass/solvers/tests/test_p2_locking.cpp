// Locking of the tets as nu -> 0.5 on the model-locking problem (verification/cases/model-locking:
// the quarter deep beam, 40 x 20 x 20 mm, simply supported by diaphragms, symmetry planes, own
// weight, St VK with E = 1 MPa: a 16 micrometre deflection, the near-linear range), solved with the
// kernel API and StaticSolver (not the runner) on one 4 x 4 x 4-cell box mesh:
//   P1 (HyperelasticTL), P2 (HyperelasticP2 standard) and P2 mean dilatation,
// each against the reference P2 mean dilatation on the 8 x 8 x 8-cell mesh at the same nu (max
// nodal error over the coarse vertices relative to max |u_ref|). Gravity is the consistent load of
// each element (int rho g N_a: for P2 the row sums of the consistent mass, negative at the
// vertices; for P1 rho V/4 per vertex).
// Checks (what locking means, not tuned values): the P1 error grows from nu = 0.3 to 0.499 by at
// least 2 (the model-locking case's threshold), each quadratic element's ratio err(0.499)/err(0.3) is
// below P1's, the mean-dilatation ratio is below plain P2's, and at nu = 0.3 the two quadratic
// elements are at least three times more accurate than P1. The measured numbers are printed.
#include "core/mesh/mesh_generator.hpp"
#include "tensormass/kernels/hyperelastic_p2.hpp"
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/kernels/p2_quadrature.hpp"
#include "tensormass/kernels/tet_geometry.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/lumped_mass.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

namespace tmlab::tm {
namespace {

const Vec3 kSize(0.02, 0.01, 0.02);
constexpr double kE = 1e6, kRho = 1000.0;

/// int N_a dV per node (the consistent load of a unit body force) on the quadratic mesh.
VecX p2_load_volumes(const QuadraticMesh& qm) {
  const P2Quadrature rule = p2_quadrature();
  VecX v = VecX::Zero(qm.num_points());
  for (const Tet10& tet : qm.tets)
    for (std::size_t q = 0; q < rule.weights.size(); ++q) {
      const auto N = p2_shape_values(rule.points[q]);
      const auto G = p2_shape_gradients(rule.points[q]);
      Mat3 J = Mat3::Zero();
      for (std::size_t a = 0; a < 10; ++a)
        J += qm.points[static_cast<std::size_t>(tet[a])] * G[a].transpose();
      for (std::size_t a = 0; a < 10; ++a) v[tet[a]] += rule.weights[q] * J.determinant() * N[a];
    }
  return v;
}

VecX p1_load_volumes(const Mesh& m) {
  const auto rest = compute_tet_rest(m);
  VecX v = VecX::Zero(m.num_points());
  for (std::size_t t = 0; t < m.tets.size(); ++t)
    for (Index n : m.tets[t]) v[n] += rest[t].volume / 4.0;
  return v;
}

/// Static solve of the beam for a model on the points `pts` with load volumes `vol`.
VecX solve_beam(ElasticModel& model, const std::vector<Vec3>& pts, const VecX& vol) {
  std::vector<DirichletCondition> bc(3);
  bc[0].name = "symmetry_x";
  bc[0].components = {true, false, false};
  bc[1].name = "symmetry_y";
  bc[1].components = {false, true, false};
  bc[2].name = "support";
  bc[2].components = {false, true, true};
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (std::abs(pts[i][0]) < 1e-12) bc[0].nodes.push_back(static_cast<Index>(i));
    if (std::abs(pts[i][1]) < 1e-12) bc[1].nodes.push_back(static_cast<Index>(i));
    if (std::abs(pts[i][0] - kSize[0]) < 1e-12) bc[2].nodes.push_back(static_cast<Index>(i));
  }
  Mesh cloud;
  cloud.points = pts;
  const VecX mass = kRho * vol;  // the consistent gravity load is m_a g with these "masses"
  ExternalLoads loads(cloud, mass);
  Gravity g;
  g.acceleration = Vec3(0, 0, -9.81);
  g.function = TimeFunction::ramp(0.0, 1.0);
  loads.add(g);
  MechanicalSystem sys(model, lumped_dof_mass(mass.cwiseAbs()), DirichletSet(model.num_nodes(), bc), loads);
  NewtonOptions no;
  no.rtol = 1e-8;
  StaticSolver solver(sys, no);
  VecX u = VecX::Zero(model.num_dofs());
  const StaticStepReport rep = solver.advance(0.0, 1.0, u);
  EXPECT_TRUE(rep.newton.converged);
  return u;
}

/// max over the coarse vertices of |u - u_ref| / max |u_ref| (vertices matched by position).
double vertex_error(const std::vector<Vec3>& pts, const VecX& u, Index nv, const std::vector<Vec3>& ref_pts,
                    const VecX& ref) {
  double umax = 0.0, emax = 0.0;
  for (Index j = 0; j < static_cast<Index>(ref_pts.size()); ++j)
    umax = std::max(umax, ref.segment<3>(3 * j).norm());
  for (Index i = 0; i < nv; ++i) {
    Index match = -1;
    for (Index j = 0; j < static_cast<Index>(ref_pts.size()); ++j)
      if ((ref_pts[static_cast<std::size_t>(j)] - pts[static_cast<std::size_t>(i)]).norm() < 1e-12) match = j;
    EXPECT_GE(match, 0);
    if (match >= 0) emax = std::max(emax, (u.segment<3>(3 * i) - ref.segment<3>(3 * match)).norm());
  }
  return emax / umax;
}

TEST(P2Locking, ErrorRatiosOnTheDeepBeam) {
  const Mesh coarse = make_box_mesh(Vec3::Zero(), kSize, 4, 4, 4);
  const Mesh fine = make_box_mesh(Vec3::Zero(), kSize, 8, 8, 8);
  const QuadraticMesh qc = make_quadratic(coarse), qf = make_quadratic(fine);
  const VecX vol_p1 = p1_load_volumes(coarse), vol_c = p2_load_volumes(qc), vol_f = p2_load_volumes(qf);
  P2Options md;
  md.volumetric = P2Options::Volumetric::MeanDilatation;
  const double nus[] = {0.3, 0.45, 0.49, 0.499};
  double e1[4], e2[4], e3[4], ref_diff[4];
  for (int k = 0; k < 4; ++k) {
    const Law law = StVenantKirchhoff::from_young_poisson(kE, nus[k]);
    HyperelasticP2 ref_md(qf, law, md), ref_std(qf, law);
    const VecX ur = solve_beam(ref_md, qf.points, vol_f);
    const VecX ur_std = solve_beam(ref_std, qf.points, vol_f);
    ref_diff[k] = vertex_error(qf.points, ur_std, qf.num_points(), qf.points, ur);
    HyperelasticTL p1(coarse, law);
    HyperelasticP2 p2(qc, law), p2md(qc, law, md);
    e1[k] = vertex_error(coarse.points, solve_beam(p1, coarse.points, vol_p1), coarse.num_points(), qf.points,
                         ur);
    e2[k] = vertex_error(qc.points, solve_beam(p2, qc.points, vol_c), qc.num_vertices, qf.points, ur);
    e3[k] = vertex_error(qc.points, solve_beam(p2md, qc.points, vol_c), qc.num_vertices, qf.points, ur);
    std::printf("nu %.3f: error P1 %.4g  P2 %.4g  P2-MD %.4g   (fine P2 vs fine P2-MD: %.3g)\n", nus[k],
                e1[k], e2[k], e3[k], ref_diff[k]);
  }
  const double r1 = e1[3] / e1[0], r2 = e2[3] / e2[0], r3 = e3[3] / e3[0];
  std::printf("locking ratio err(0.499)/err(0.3): P1 %.3g  P2 %.3g  P2-MD %.3g\n", r1, r2, r3);
  EXPECT_GE(r1, 2.0);
  EXPECT_LT(r2, r1);
  EXPECT_LT(r3, r2);
  EXPECT_LT(3.0 * e2[0], e1[0]);
  EXPECT_LT(3.0 * e3[0], e1[0]);
}

}  // namespace
}  // namespace tmlab::tm
