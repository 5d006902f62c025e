// Newton tests (issue 12, "nonlinear solves that do not fight themselves"):
//  - the potentials the energy line search decreases are the antiderivatives of the residuals
//    (static under dead loads; the incremental potential of an implicit step with Rayleigh damping),
//    checked by central finite differences;
//  - the slender cantilever of the elastica (PL^2/EI = 10, tip rotation ~80 degrees) in 40 load steps
//    converges with the default (energy) line search without a cut-back, while the residual-norm
//    search rejects the good first step of large rotations and needs cut-backs or fails;
//  - an increment cut back once grows back after success;
//  - a residual stalled at round-off stops as converged (at_roundoff) instead of iterating to the limit.
#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/solvers/implicit_dynamics.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/lumped_mass.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tmlab::tm {
namespace {

/// The elastica cantilever of issue 12: a 100 x 147.8 x 10000 prism (1 x 1 x 100 hexes, 600 tets),
/// St VK with E = 100, nu = 0, clamped at z = 0, a dead tip load P in -x with P L^2 / (E I) = 10
/// (I = 147.8 * 100^3 / 12 about the bending axis), ramped over the pseudo-time [0, 1].
struct Elastica {
  Mesh mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(100, 147.8, 10000), 1, 1, 100);
  StVenantKirchhoff material = StVenantKirchhoff::from_young_poisson(100.0, 0.0);
  TensorMassStVK model{mesh, material};

  MechanicalSystem system() {
    const double L = 10000.0, EI = 100.0 * 147.8 * std::pow(100.0, 3) / 12.0;
    NodeSelector base, tip;
    base.kind = tip.kind = NodeSelector::Kind::Plane;
    base.axis = tip.axis = 2;
    base.value = 0.0;
    tip.value = L;
    DirichletCondition fixed;
    fixed.name = "clamp";
    fixed.nodes = select_nodes(mesh, base);
    const VecX node_mass = lumped_node_mass(mesh, 1.0);
    ExternalLoads loads(mesh, node_mass);
    NodalForce f;
    f.name = "tip";
    f.nodes = select_nodes(mesh, tip);
    f.force = Vec3(-10.0 * EI / (L * L), 0, 0);
    f.function = TimeFunction::ramp(0.0, 1.0);
    loads.add(f);
    return MechanicalSystem(model, lumped_dof_mass(node_mass), DirichletSet(mesh.num_points(), {fixed}),
                            loads, RayleighDamping{});
  }
};

struct ElasticaRun {
  int iterations = 0, cutbacks = 0, roundoff_steps = 0;
  bool failed = false;
  double tip_x = 0.0;
};

/// The first `run_steps` of `steps` load steps.
ElasticaRun run_elastica(const NewtonOptions& options, int steps = 40, int run_steps = 40) {
  Elastica e;
  const MechanicalSystem sys = e.system();
  StaticSolver solver(sys, options, 8);
  VecX u = VecX::Zero(sys.model().num_dofs());
  ElasticaRun run;
  try {
    for (int k = 1; k <= run_steps; ++k) {
      const StaticStepReport rep = solver.advance(double(k - 1) / steps, double(k) / steps, u);
      run.iterations += rep.newton_iterations;
      run.cutbacks += rep.cutbacks;
      run.roundoff_steps += rep.at_roundoff ? 1 : 0;
    }
  } catch (const Error&) {
    run.failed = true;
  }
  for (Index i = 0; i < e.mesh.num_points(); ++i) run.tip_x = std::min(run.tip_x, u[3 * i]);
  return run;
}

/// Central-difference check of dPi/du = R along random directions, relative to |R . w|.
void expect_potential_gradient(NonlinearSystem& sys, const VecX& u, const DirichletSet& bc) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  VecX r;
  sys.residual(u, r);
  for (int trial = 0; trial < 4; ++trial) {
    VecX w(u.size());
    for (Eigen::Index i = 0; i < w.size(); ++i) w[i] = bc.mask()[i] ? 0.0 : U(rng);
    const double h = 1e-6 * std::max(1.0, u.lpNorm<Eigen::Infinity>());
    double pp = 0.0, pm = 0.0;
    ASSERT_TRUE(sys.potential(u + h * w, pp));
    ASSERT_TRUE(sys.potential(u - h * w, pm));
    const double fd = (pp - pm) / (2.0 * h), exact = r.dot(w);
    EXPECT_NEAR(fd, exact, 1e-6 * std::abs(exact) + 1e-9) << "direction " << trial;
  }
}

TEST(Newton, StaticPotentialIsTheAntiderivativeOfTheResidual) {
  Elastica e;
  const MechanicalSystem sys = e.system();
  VecX u = VecX::Random(sys.model().num_dofs()) * 50.0;
  for (Index d : sys.bc().dofs()) u[d] = 0.0;
  StaticResidual res(sys, 0.7, u);
  expect_potential_gradient(res, u, sys.bc());
}

TEST(Newton, ImplicitIncrementalPotentialIsTheAntiderivativeOfTheResidual) {
  Elastica e;
  const MechanicalSystem base = e.system();
  const MechanicalSystem sys(e.model, base.mass(), base.bc(), base.loads(), RayleighDamping{0.3, 0.02});
  const Index n = sys.model().num_dofs();
  VecX un = VecX::Random(n) * 20.0, vn = VecX::Random(n) * 3.0, an = VecX::Random(n);
  for (Index d : sys.bc().dofs()) un[d] = vn[d] = an[d] = 0.0;
  for (ImplicitScheme scheme : {ImplicitScheme::Newmark, ImplicitScheme::BackwardEuler}) {
    ImplicitStepResidual res(sys, 0.5, implicit_coefficients(scheme, 0.01), un, vn, an);
    VecX u = un + VecX::Random(n) * 5.0;
    for (Index d : sys.bc().dofs()) u[d] = 0.0;
    expect_potential_gradient(res, u, sys.bc());
  }
}

TEST(Newton, NoPotentialWithFollowerLoadsOrHistory) {
  // A follower pressure is not conservative: the line search must not use an energy.
  Mesh mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), 1, 1, 1);
  TensorMassStVK model(mesh, StVenantKirchhoff::from_young_poisson(1.0, 0.3));
  const VecX node_mass = lumped_node_mass(mesh, 1.0);
  ExternalLoads loads(mesh, node_mass);
  SurfacePressure p;
  p.faces = boundary_faces(mesh);
  p.pressure = 0.1;
  p.follower = true;
  loads.add(p);
  const MechanicalSystem sys(model, lumped_dof_mass(node_mass), DirichletSet(mesh.num_points(), {}), loads,
                             RayleighDamping{});
  StaticResidual res(sys, 1.0, VecX::Zero(sys.model().num_dofs()));
  double value = 0.0;
  EXPECT_FALSE(res.potential(VecX::Zero(sys.model().num_dofs()), value));
}

TEST(Newton, ElasticaConvergesWithoutCutbacksUnderTheEnergyLineSearch) {
  const ElasticaRun energy = run_elastica(NewtonOptions{});
  ASSERT_FALSE(energy.failed);
  EXPECT_EQ(energy.cutbacks, 0);
  // 40 steps of a large rotation: a handful of iterations per step (measured 267 in all).
  EXPECT_LT(energy.iterations, 40 * 10);
  // The tip moves far towards -x (the elastica gives x_tip/L = -0.81 in this direction; the
  // 600-tet P1 model locks in bending, so the fast model moves less: here only a sanity bound).
  EXPECT_LT(energy.tip_x, -0.3 * 10000.0);

  // Without any line search the same answer (the full Newton step is good here).
  NewtonOptions none;
  none.line_search = LineSearch::None;
  const ElasticaRun full = run_elastica(none);
  ASSERT_FALSE(full.failed);
  EXPECT_NEAR(full.tip_x, energy.tip_x, 1e-6 * std::abs(energy.tip_x));
}

TEST(Newton, ResidualNormLineSearchFightsTheLargeRotation) {
  // The pre-2026-11 default: backtracking on |R| rejects the good steps, so the load increment is
  // cut back (and did not recover before this fix). It must cost clearly more than the energy search.
  // The first two of the 40 load steps show it (the old default failed in the first).
  NewtonOptions residual;
  residual.line_search = LineSearch::Residual;
  const ElasticaRun r = run_elastica(residual, 40, 2);
  const ElasticaRun e = run_elastica(NewtonOptions{}, 40, 2);
  ASSERT_FALSE(e.failed);
  EXPECT_TRUE(r.failed || r.cutbacks > 0 || r.iterations > 2 * e.iterations)
      << "residual merit: " << r.iterations << " iterations, " << r.cutbacks << " cut-backs";
}

/// R(u) = k (u^3 + u) - f per DOF with k = 1e12: the residual cannot fall below ~k eps |u|^3 (1e-4
/// here), so a target of 1e-8 is below round-off.
class StiffCubic final : public NonlinearSystem {
 public:
  void residual(const VecX& u, VecX& r) override {
    r.resize(u.size());
    for (Eigen::Index i = 0; i < u.size(); ++i) r[i] = k * (u[i] * u[i] * u[i] + u[i]) - f;
  }
  void jacobian(const VecX& u, SpMat& J) override {
    J.resize(u.size(), u.size());
    std::vector<Eigen::Triplet<double>> t;
    for (Eigen::Index i = 0; i < u.size(); ++i) t.emplace_back(i, i, k * (3.0 * u[i] * u[i] + 1.0));
    J.setFromTriplets(t.begin(), t.end());
  }
  bool symmetric() const override { return true; }
  double force_scale() const override { return f; }
  double k = 1e12, f = 3e12 * 1.3;
};

TEST(Newton, StallsAtRoundOffAreConvergedNotIteratedToTheLimit) {
  StiffCubic sys;
  const DirichletSet bc(1, {});  // one node, three free DOFs
  ConstrainedLinearSolver linear;
  NewtonOptions o;
  o.rtol = 1e-30;  // target = atol = 1e-5: above the floor only by a small factor, or below it
  o.atol = 1e-5;
  o.max_iterations = 60;
  VecX u = VecX::Zero(3);
  const NewtonResult stop = newton_solve(sys, bc, 0.0, u, o, linear);
  EXPECT_TRUE(stop.converged);
  EXPECT_LT(stop.iterations, 20);
  VecX r;
  sys.residual(u, r);
  EXPECT_LT(r.norm(), 1e3 * o.atol);

  EXPECT_TRUE(stop.at_roundoff);  // the floor (~6e-4) is above the target: round-off, not the target
  EXPECT_TRUE(stop.stalled);

  // A target far below the round-off floor (1e-12 against ~6e-4): stopped early, not converged.
  o.atol = 1e-12;
  VecX u2 = VecX::Zero(3);
  const NewtonResult no = newton_solve(sys, bc, 0.0, u2, o, linear);
  EXPECT_FALSE(no.converged);
  EXPECT_TRUE(no.stalled);
  EXPECT_LT(no.iterations, 20);
}

TEST(StaticSolver, CutBackIncrementGrowsBackAfterSuccess) {
  // One load step of the whole elastica load: Newton fails on the full increment and on its half
  // (the iteration limit is small), the increment is cut back, and the following sub-increments
  // grow again: fewer sub-increments than if the cut-back increment were kept to the end.
  NewtonOptions o;
  o.max_iterations = 8;
  Elastica e;
  const MechanicalSystem sys = e.system();
  StaticSolver solver(sys, o, 12);
  VecX u = VecX::Zero(sys.model().num_dofs());
  const StaticStepReport rep = solver.advance(0.0, 1.0, u);
  ASSERT_GT(rep.cutbacks, 0);
  const int without_growth = 1 << rep.cutbacks;  // the smallest increment kept to the end
  EXPECT_LT(rep.sub_increments, without_growth) << rep.cutbacks << " cut-backs";
}

TEST(Newton, ConjugateGradientLinearSolverGivesTheDirectAnswer) {
  // The first two elastica load steps with preconditioned CG inside Newton, against the direct solver.
  Elastica e;
  const MechanicalSystem sys = e.system();
  VecX u_direct = VecX::Zero(sys.model().num_dofs()), u_cg = u_direct;
  ConstrainedLinearSolver direct(NewtonLinearSolver::Direct),
      cg(ConstrainedLinearSolver::Kind::ConjugateGradient, 1e-12);
  for (double t : {0.025, 0.05}) {
    StaticResidual r1(sys, t, u_direct), r2(sys, t, u_cg);
    ASSERT_TRUE(newton_solve(r1, sys.bc(), t, u_direct, NewtonOptions{}, direct).converged);
    ASSERT_TRUE(newton_solve(r2, sys.bc(), t, u_cg, NewtonOptions{}, cg).converged);
    EXPECT_GT(cg.last_iterations(), 0);
  }
  EXPECT_LT((u_cg - u_direct).lpNorm<Eigen::Infinity>(), 1e-6 * u_direct.lpNorm<Eigen::Infinity>());
  // A non-symmetric tangent is refused by CG with a clear message.
  SpMat J = SpMat(3, 3);
  J.setIdentity();
  VecX du;
  EXPECT_THROW(cg.solve(J, VecX::Ones(3), DirichletSet(1, {}), VecX::Zero(3), false, du), Error);
}

}  // namespace
}  // namespace tmlab::tm

namespace tmlab::tm {
namespace {

TEST(Newton, CholmodLinearSolverGivesTheDirectAnswer) {
  // Oracle: the first two elastica load steps with CHOLMOD's LL^T inside Newton against Eigen's
  // LDL^T: the answers equal to round-off (the number of iterations may differ: the slender beam's
  // round-off floor is reached along slightly different paths).
  Elastica e;
  const MechanicalSystem sys = e.system();
  VecX u_direct = VecX::Zero(sys.model().num_dofs()), u_chol = u_direct;
  ConstrainedLinearSolver direct(NewtonLinearSolver::Direct), chol(NewtonLinearSolver::Cholmod);
  int iterations = 0;
  for (double t : {0.025, 0.05}) {
    StaticResidual r1(sys, t, u_direct), r2(sys, t, u_chol);
    const NewtonResult a = newton_solve(r1, sys.bc(), t, u_direct, NewtonOptions{}, direct);
    const NewtonResult b = newton_solve(r2, sys.bc(), t, u_chol, NewtonOptions{}, chol);
    ASSERT_TRUE(a.converged);
    ASSERT_TRUE(b.converged);
    iterations += b.iterations;
  }
  EXPECT_EQ(chol.fallbacks(), 0);
  // Every solve was CHOLMOD's, on one symbolic analysis across the iterations and both load steps.
  EXPECT_EQ(chol.stats().solves, iterations);
  EXPECT_EQ(chol.stats().cholmod_solves, iterations);
  EXPECT_EQ(chol.stats().cholmod_analyses, 1);
  EXPECT_EQ(chol.stats().ldlt_solves, 0);
  EXPECT_EQ(direct.stats().cholmod_solves, 0);
  EXPECT_EQ(direct.stats().ldlt_analyses, 1);
  EXPECT_GT(u_direct.lpNorm<Eigen::Infinity>(), 0.0);
  EXPECT_LT((u_chol - u_direct).lpNorm<Eigen::Infinity>(), 1e-10 * u_direct.lpNorm<Eigen::Infinity>());

  // The StaticSolver takes the choice from NewtonOptions, where CHOLMOD is the default.
  NewtonOptions o;
  EXPECT_EQ(o.linear_solver, NewtonLinearSolver::Cholmod);
  EXPECT_EQ(ConstrainedLinearSolver().kind(), NewtonLinearSolver::Cholmod);
  StaticSolver solver(sys, o);
  VecX u = VecX::Zero(sys.model().num_dofs());
  ASSERT_TRUE(solver.advance(0.0, 0.025, u).newton.converged);
  EXPECT_EQ(solver.linear_solver().kind(), NewtonLinearSolver::Cholmod);
  VecX u_ref = VecX::Zero(sys.model().num_dofs());
  StaticResidual r(sys, 0.025, u_ref);
  ConstrainedLinearSolver direct2(NewtonLinearSolver::Direct);
  ASSERT_TRUE(newton_solve(r, sys.bc(), 0.025, u_ref, NewtonOptions{}, direct2).converged);
  EXPECT_LT((u - u_ref).lpNorm<Eigen::Infinity>(), 1e-10 * u_ref.lpNorm<Eigen::Infinity>());
}

/// A symmetric indefinite (non-singular) 6 x 6 tridiagonal matrix: one negative diagonal entry
/// among dominant positive ones, so exactly one negative eigenvalue. DOF 3 (node 1, x) is constrained.
struct Indefinite {
  DirichletSet bc = [] {
    DirichletCondition fix;
    fix.name = "fix";
    fix.nodes = {1};
    fix.components = {true, false, false};
    return DirichletSet(2, {fix});
  }();
  SpMat J = [] {
    SpMat m(6, 6);
    std::vector<Eigen::Triplet<double>> t;
    const double d[6] = {2.0, -3.0, 5.0, 7.0, 4.0, 6.0};
    for (int i = 0; i < 6; ++i) t.emplace_back(i, i, d[i]);
    for (int i = 0; i + 1 < 6; ++i) {
      t.emplace_back(i, i + 1, 0.5);
      t.emplace_back(i + 1, i, 0.5);
    }
    m.setFromTriplets(t.begin(), t.end());
    return m;
  }();
  VecX rhs = (VecX(6) << 1.0, 2.0, -1.0, 0.0, 3.0, 0.5).finished();
  VecX du_c = [] {
    VecX v = VecX::Zero(6);
    v[3] = 0.25;
    return v;
  }();
};

TEST(Newton, CholmodFallsBackToLdltOnAnIndefiniteTangent) {
  // LL^T does not exist: the solve is done by LDL^T, counted with its reason (one negative pivot:
  // indefinite) under the Newton iteration that asked, and gives the exact solution; an SPD matrix
  // is not counted.
  const Indefinite m{};
  ConstrainedLinearSolver chol(NewtonLinearSolver::Cholmod), direct(NewtonLinearSolver::Direct);
  VecX a, b;
  chol.solve(m.J, m.rhs, m.bc, m.du_c, true, a, 1);
  direct.solve(m.J, m.rhs, m.bc, m.du_c, true, b);
  EXPECT_EQ(chol.fallbacks(), 1);
  const LinearSolveStats& s = chol.stats();
  EXPECT_EQ(s.fallbacks_indefinite, 1);
  EXPECT_EQ(s.fallbacks_round_off, 0);
  EXPECT_EQ(s.max_negative_pivots, 1);
  EXPECT_EQ(s.fallbacks_by_iteration, (std::vector<long>{0, 1, 0, 0}));
  EXPECT_EQ(s.ldlt_solves, 1);
  EXPECT_EQ(s.cholmod_solves, 0);
  EXPECT_EQ(direct.fallbacks(), 0);  // LDL^T asked for: no fallback
  EXPECT_LT((a - b).lpNorm<Eigen::Infinity>(), 1e-14);
  EXPECT_DOUBLE_EQ(a[3], 0.25);
  // The free rows hold: (J du)_f = rhs_f.
  const VecX Jdu = m.J * a;
  for (int i : {0, 1, 2, 4, 5}) EXPECT_NEAR(Jdu[i], m.rhs[i], 1e-13) << i;

  SpMat K = m.J;
  K.coeffRef(1, 1) = 3.0;  // now positive definite
  chol.solve(K, m.rhs, m.bc, m.du_c, true, a, 0);
  direct.solve(K, m.rhs, m.bc, m.du_c, true, b);
  EXPECT_EQ(chol.fallbacks(), 1);
  EXPECT_EQ(chol.stats().cholmod_solves, 1);
  EXPECT_EQ(chol.stats().solves, 2);
  EXPECT_LT((a - b).lpNorm<Eigen::Infinity>(), 1e-14);
  // Iterations past the histogram's end share its last entry.
  chol.solve(m.J, m.rhs, m.bc, m.du_c, true, a, 17);
  EXPECT_EQ(chol.stats().fallbacks_by_iteration, (std::vector<long>{0, 1, 0, 1}));
}

TEST(Newton, NewtonFilesEachFallbackUnderItsIteration) {
  // A quadratic potential with an indefinite Hessian (no minimum, one saddle): Newton's first step
  // lands on the stationary point; the one solve fell back, at iteration 1 (index 0).
  struct Saddle final : NonlinearSystem {
    Indefinite m;
    void residual(const VecX& u, VecX& r) override { r = m.J * u - m.rhs; }
    void jacobian(const VecX&, SpMat& J) override { J = m.J; }
    bool symmetric() const override { return true; }
    double force_scale() const override { return m.rhs.norm(); }
  } saddle;
  ConstrainedLinearSolver chol(NewtonLinearSolver::Cholmod);
  VecX u = VecX::Zero(6);
  const NewtonResult r = newton_solve(saddle, saddle.m.bc, 0.0, u, NewtonOptions{}, chol);
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_EQ(chol.stats().fallbacks_indefinite, 1);
  EXPECT_EQ(chol.stats().fallbacks_by_iteration, (std::vector<long>{1, 0, 0, 0}));
}

TEST(Newton, SymbolicAnalysisIsRedoneOnlyWhenThePatternChanges) {
  // The same pattern with new values: one analysis. A pattern with the same number of non-zeros in
  // other places (which a count of non-zeros would take for the old one): analysed again.
  const DirichletSet bc(2, {});
  // Diagonal `diag`, 0.5 at the symmetric pairs (i, j): diagonally dominant, positive definite.
  auto matrix = [](double diag, const std::vector<std::pair<int, int>>& pairs) {
    SpMat m(6, 6);
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < 6; ++i) t.emplace_back(i, i, diag);
    for (const auto& [i, j] : pairs) {
      t.emplace_back(i, j, 0.5);
      t.emplace_back(j, i, 0.5);
    }
    m.setFromTriplets(t.begin(), t.end());
    return m;
  };
  const std::vector<std::pair<int, int>> near = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}};
  const std::vector<std::pair<int, int>> other = {{0, 2}, {1, 3}, {2, 4}, {3, 5}, {0, 5}};
  const VecX rhs = VecX::LinSpaced(6, 1.0, 2.0), zero = VecX::Zero(6);
  for (const NewtonLinearSolver kind : {NewtonLinearSolver::Cholmod, NewtonLinearSolver::Direct}) {
    ConstrainedLinearSolver s(kind);
    VecX du;
    s.solve(matrix(4.0, near), rhs, bc, zero, true, du);
    s.solve(matrix(5.0, near), rhs, bc, zero, true, du);
    const SpMat far = matrix(6.0, other);
    ASSERT_EQ(far.nonZeros(), matrix(4.0, near).nonZeros());
    s.solve(far, rhs, bc, zero, true, du);
    EXPECT_LT((far * du - rhs).lpNorm<Eigen::Infinity>(), 1e-14);
    const LinearSolveStats& st = s.stats();
    const long analyses = kind == NewtonLinearSolver::Cholmod ? st.cholmod_analyses : st.ldlt_analyses;
    EXPECT_EQ(analyses, 2) << (kind == NewtonLinearSolver::Cholmod ? "cholmod" : "ldlt");
    EXPECT_EQ(st.solves, 3);
  }
}

}  // namespace
}  // namespace tmlab::tm
