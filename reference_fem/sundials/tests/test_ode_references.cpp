// SUNDIALS references (ode_references.hpp): the single-DOF closed forms met by CVODE, ARKStep and IDA
// within their tolerances, the observed orders of ViscoelasticStVK's recursions against the closed
// form, and the fixed-step tensor-mass model (ImplicitDynamics + ViscoelasticStVK) converging to the
// CVODE solution of the semi-discrete ODE at the expected order. Numbers quoted in
// docs/theory/sundials-references.md are printed by these tests.
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "reference_fem/sundials/ode_references.hpp"
#include "tensormass/solvers/implicit_dynamics.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/lumped_mass.hpp"

#include "tensormass/testing/ode_test_problems.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <vector>

namespace tmlab::tm {
namespace {

using Integ = ViscoelasticOptions::Integration;
constexpr double kPi = 3.14159265358979323846;

// ------------------------------------------------------------------ SDOF oscillator

/// max over t = 0.05, 0.10, ..., 2 s and over x, v, h of |y - exact| / max_t |exact| (per component).
double oscillator_error(OdeMethod m, LinearSolverKind k, double rtol, IntegratorStats* stats) {
  SlsOscillator sys(1.0, 4.0 * kPi * kPi, 1.0, 0.1, 0.0, 1.0);
  OdeOptions o;
  o.rtol = rtol;
  o.atol = 1e-3 * rtol;
  o.linear = k;
  OdeIntegrator ode(sys, m, o, 0.0, sys.initial_state());
  std::vector<Eigen::Vector3d> got, ref;
  VecX y;
  for (int i = 1; i <= 40; ++i) {
    const double t = 0.05 * i;
    ode.advance(t, y);
    got.emplace_back(y);
    ref.push_back(sys.exact(t));
  }
  Eigen::Vector3d scale = Eigen::Vector3d::Zero(), err = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < got.size(); ++i) {
    scale = scale.cwiseMax(ref[i].cwiseAbs());
    err = err.cwiseMax((got[i] - ref[i]).cwiseAbs());
  }
  *stats = ode.stats();
  return err.cwiseQuotient(scale).maxCoeff();
}

TEST(OdeReferences, OscillatorClosedFormSatisfiesTheOde) {
  SlsOscillator sys(1.0, 4.0 * kPi * kPi, 1.0, 0.1, 0.0, 1.0);
  EXPECT_LT((sys.exact(0.0) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-13);
  for (double t : {0.1, 0.7, 1.9}) {  // y' = A y by central differences
    const double h = 1e-5;
    const Eigen::Vector3d d = (sys.exact(t + h) - sys.exact(t - h)) / (2 * h);
    EXPECT_LT((d - sys.matrix() * sys.exact(t)).norm(), 1e-7 * (1 + d.norm()));
  }
}

TEST(OdeReferences, CvodeAndArkodeMeetTheirTolerancesOnTheOscillator) {
  struct Variant {
    OdeMethod m;
    LinearSolverKind k;
  };
  const Variant variants[] = {
      {OdeMethod::CvodeBdf, LinearSolverKind::Dense},   {OdeMethod::CvodeBdf, LinearSolverKind::Spgmr},
      {OdeMethod::ArkodeDirk, LinearSolverKind::Dense}, {OdeMethod::ArkodeDirk, LinearSolverKind::Spgmr},
      {OdeMethod::ArkodeImex, LinearSolverKind::Dense}, {OdeMethod::ArkodeImex, LinearSolverKind::Spgmr}};
  for (const Variant& v : variants) {
    double previous = 1e300;
    for (double rtol : {1e-4, 1e-6, 1e-8, 1e-10}) {
      IntegratorStats s;
      const double err = oscillator_error(v.m, v.k, rtol, &s);
      std::printf("oscillator %-22s rtol %.0e: error %.2e (%.2f rtol), steps %6ld newton %6ld linear %6ld\n",
                  (to_string(v.m) + " + " + to_string(v.k)).c_str(), rtol, err, err / rtol, s.steps,
                  s.nonlinear_iterations, s.linear_iterations);
      // Local error control only: ARKStep's global error over two periods stays below 0.1 rtol, CVODE's
      // BDF accumulates 3-25 rtol (largest at rtol = 1e-10, ~860 steps), so CVODE is held to 30 rtol.
      const double bound = v.m == OdeMethod::CvodeBdf ? 30.0 : 10.0;
      EXPECT_LE(err, bound * rtol) << to_string(v.m) << " rtol " << rtol;
      EXPECT_LT(err, previous) << to_string(v.m) << " rtol " << rtol;
      previous = err;
    }
  }
}

// ------------------------------------------------------------------ SDOF creep

SlsCreep creep_problem() { return SlsCreep(100.0, 1.5, 0.5, 1.0, 2.0 * kPi * 0.5); }

TEST(OdeReferences, CreepClosedFormSatisfiesTheDae) {
  SlsCreep c = creep_problem();
  for (double t : {0.05, 0.4, 1.7}) {
    const double h = 1e-5;
    const double x = c.exact_x(t), z = x - c.exact_H(t);
    const double zp =
        ((c.exact_x(t + h) - c.exact_H(t + h)) - (c.exact_x(t - h) - c.exact_H(t - h))) / (2 * h);
    VecX y(2), yp(2), r;
    y << x, z;
    yp << 0.0, zp;
    c.residual(t, y, yp, r);
    EXPECT_LT(std::abs(r[0]), 1e-14);
    EXPECT_LT(std::abs(r[1]), 1e-8 * std::abs(zp) + 1e-12);
  }
}

TEST(OdeReferences, RecursionsShowTheirOrderAgainstTheCreepClosedForm) {
  SlsCreep c = creep_problem();
  const double t_end = 2.0;
  double scale = 0.0;
  for (int i = 1; i <= 2000; ++i) scale = std::max(scale, std::abs(c.exact_x(i * t_end / 2000)));
  const struct {
    Integ s;
    const char* name;
    double order;
  } schemes[] = {{Integ::Midpoint, "midpoint", 2.0},
                 {Integ::ExactLinear, "exact_linear", 2.0},
                 {Integ::BackwardEuler, "backward_euler", 1.0}};
  for (const auto& sc : schemes) {
    std::vector<double> errs;
    for (int level = 0; level < 5; ++level) {
      const double dt = 0.1 / (1 << level);
      const int n = static_cast<int>(std::lround(t_end / dt));
      const std::vector<double> x = c.recursion(sc.s, dt, n);
      double e = 0.0;
      for (int k = 0; k < n; ++k)
        e = std::max(e, std::abs(x[static_cast<std::size_t>(k)] - c.exact_x((k + 1) * dt)));
      errs.push_back(e / scale);
    }
    const double order = std::log2(errs[3] / errs[4]);
    std::printf("creep recursion %-15s error dt=0.1: %.3e, dt=0.00625: %.3e, observed order %.3f\n", sc.name,
                errs.front(), errs.back(), order);
    EXPECT_NEAR(order, sc.order, 0.1) << sc.name;
  }
}

TEST(OdeReferences, IdaMeetsItsTolerancesOnTheCreepDae) {
  SlsCreep c = creep_problem();
  double previous = 1e300;
  for (double rtol : {1e-4, 1e-6, 1e-8, 1e-10}) {
    DaeOptions o;
    o.rtol = rtol;
    o.atol = 1e-3 * rtol * 0.01;  // x ~ 1e-2
    DaeIntegrator ida(c, o, 0.0, VecX::Zero(2), VecX::Zero(2));
    VecX y, yp;
    double err = 0.0, scale = 0.0;
    for (int i = 1; i <= 40; ++i) {
      const double t = 0.05 * i;
      ida.advance(t, y, yp);
      err = std::max(err, std::abs(y[0] - c.exact_x(t)));
      scale = std::max(scale, std::abs(c.exact_x(t)));
    }
    const IntegratorStats s = ida.stats();
    std::printf("creep IDA rtol %.0e: error %.2e (%.2f rtol), steps %5ld newton %5ld\n", rtol, err / scale,
                err / scale / rtol, s.steps, s.nonlinear_iterations);
    EXPECT_LE(err / scale, 10.0 * rtol);
    EXPECT_LT(err / scale, previous);
    previous = err / scale;
  }
}

// ------------------------------------------------------------------ tensor-mass dynamics

/// The released block (ode_test_problems.hpp): nu = 0.35, one Prony term alpha = 1, tau = 10 ms.
struct Block : test::ReleasedBlock {
  Block() : test::ReleasedBlock(0.35, PronySeries::from_long_term({1.0}, {0.01})) {}
};

TEST(OdeReferences, TensorMassJacobianActionMatchesDifferenceQuotient) {
  for (auto h : {ViscoelasticOptions::History::Pk2, ViscoelasticOptions::History::NodalForce}) {
    for (auto r : {ViscoelasticOptions::Relaxation::Full, ViscoelasticOptions::Relaxation::Deviatoric}) {
      if (h == ViscoelasticOptions::History::NodalForce && r == ViscoelasticOptions::Relaxation::Deviatoric)
        continue;
      const Block b;
      const ViscoelasticOptions opt{h, Integ::ExactLinear, r};
      ViscoelasticStVK model(b.mesh, b.mat, b.prony, opt);
      MechanicalSystem sys(model, lumped_dof_mass(b.node_mass), b.bc(), ExternalLoads(b.mesh, b.node_mass));
      TensorMassViscoelasticOde ode(b.mesh, b.mat, b.prony, opt, sys);
      VecX u(ode.num_dofs());
      for (Index i = 0; i < u.size(); ++i) u[i] = 1e-3 * std::sin(1.3 * i + 0.2);
      VecX y = ode.initial_state(0.0, u, b.v0);
      for (Index i = 2 * ode.num_dofs(); i < y.size(); ++i) y[i] *= 0.5 + 0.3 * std::cos(0.7 * i);
      VecX w(y.size());
      for (Index i = 0; i < w.size(); ++i) w[i] = std::cos(0.37 * i) * (i < 2 * ode.num_dofs() ? 1e-3 : 10.0);
      VecX Jw, fp, fm;
      ode.jacobian_times(0.0, y, w, Jw);
      const double eps = 1e-4;
      ode.rhs(0.0, y + eps * w, fp);
      ode.rhs(0.0, y - eps * w, fm);
      const VecX fd = (fp - fm) / (2 * eps);
      const double rel = (Jw - fd).norm() / fd.norm();
      std::printf("Jv vs central difference (%s/%s): %.2e\n", ViscoelasticOptions::to_string(h).c_str(),
                  ViscoelasticOptions::to_string(r).c_str(), rel);
      EXPECT_LT(rel, 1e-7);
    }
  }
}

/// u(t_end) by CVODE (or ARKStep) on the semi-discrete ODE, and the stats.
VecX reference_solution(const Block& b, const ViscoelasticOptions& opt, OdeMethod m, double rtol,
                        double t_end, IntegratorStats* stats) {
  ViscoelasticStVK model(b.mesh, b.mat, b.prony, opt);
  MechanicalSystem sys(model, lumped_dof_mass(b.node_mass), b.bc(), ExternalLoads(b.mesh, b.node_mass));
  TensorMassViscoelasticOde ode(b.mesh, b.mat, b.prony, opt, sys);
  OdeOptions o;
  o.rtol = rtol;
  o.linear = LinearSolverKind::Spgmr;
  o.atol_vector = ode.absolute_tolerances(1e-3 * rtol * 1e-3, 1e-3 * rtol * 0.05, 1e-3 * rtol * 100.0);
  OdeIntegrator integ(ode, m, o, 0.0, ode.initial_state(0.0, VecX::Zero(ode.num_dofs()), b.v0));
  VecX y;
  integ.advance(t_end, y);
  *stats = integ.stats();
  return ode.displacement(t_end, y);
}

TEST(OdeReferences, FixedStepTensorMassConvergesToCvodeReference) {
  const Block b;
  const double t_end = 0.02;
  const ViscoelasticOptions base{ViscoelasticOptions::History::Pk2, Integ::ExactLinear,
                                 ViscoelasticOptions::Relaxation::Full};
  IntegratorStats s10, s8, sa;
  const VecX ref = reference_solution(b, base, OdeMethod::CvodeBdf, 1e-10, t_end, &s10);
  const VecX ref8 = reference_solution(b, base, OdeMethod::CvodeBdf, 1e-8, t_end, &s8);
  const VecX ark = reference_solution(b, base, OdeMethod::ArkodeDirk, 1e-10, t_end, &sa);
  IntegratorStats si;
  const VecX imex = reference_solution(b, base, OdeMethod::ArkodeImex, 1e-10, t_end, &si);
  const double scale = ref.cwiseAbs().maxCoeff();
  std::printf("CVODE rtol 1e-10: steps %ld newton %ld linear %ld jtimes %ld; |u|max %.3e m\n", s10.steps,
              s10.nonlinear_iterations, s10.linear_iterations, s10.jtimes_evals, scale);
  std::printf("CVODE rtol 1e-8:  steps %ld newton %ld linear %ld; |u(1e-8) - u(1e-10)|/|u| = %.2e\n",
              s8.steps, s8.nonlinear_iterations, s8.linear_iterations,
              (ref8 - ref).cwiseAbs().maxCoeff() / scale);
  std::printf("ARKStep rtol 1e-10: steps %ld newton %ld linear %ld; |u_ark - u_cvode|/|u| = %.2e\n", sa.steps,
              sa.nonlinear_iterations, sa.linear_iterations, (ark - ref).cwiseAbs().maxCoeff() / scale);
  std::printf(
      "ARKStep ImEx rtol 1e-10: steps %ld f_E %ld f_I %ld newton %ld linear %ld; |u_imex - u_cvode|/|u| = "
      "%.2e\n",
      si.steps, si.explicit_rhs_evals, si.rhs_evals, si.nonlinear_iterations, si.linear_iterations,
      (imex - ref).cwiseAbs().maxCoeff() / scale);
  EXPECT_LT((ark - ref).cwiseAbs().maxCoeff() / scale, 1e-7);
  EXPECT_LT((imex - ref).cwiseAbs().maxCoeff() / scale, 1e-7);
  EXPECT_LT((ref8 - ref).cwiseAbs().maxCoeff() / scale, 1e-5);

  const struct {
    ImplicitScheme scheme;
    Integ integ;
    const char* name;
    double order;
  } cases[] = {{ImplicitScheme::Newmark, Integ::ExactLinear, "newmark + exact_linear", 2.0},
               {ImplicitScheme::Newmark, Integ::Midpoint, "newmark + midpoint", 2.0},
               {ImplicitScheme::BackwardEuler, Integ::BackwardEuler, "backward_euler + backward_euler", 1.0}};
  for (const auto& c : cases) {
    std::vector<double> errs;
    for (double dt : {4e-4, 2e-4, 1e-4, 5e-5}) {
      ViscoelasticOptions opt = base;
      opt.integration = c.integ;
      ViscoelasticStVK model(b.mesh, b.mat, b.prony, opt);
      MechanicalSystem sys(model, lumped_dof_mass(b.node_mass), b.bc(), ExternalLoads(b.mesh, b.node_mass));
      ImplicitDynamics im(sys, c.scheme, NewtonOptions{40, 1e-11, 1e-15});
      im.initialize(0.0, VecX::Zero(b.v0.size()), b.v0);
      const int n = static_cast<int>(std::lround(t_end / dt));
      for (int k = 0; k < n; ++k) ASSERT_TRUE(im.step(k * dt, dt).converged);
      errs.push_back((im.displacement() - ref).cwiseAbs().maxCoeff() / scale);
    }
    const double order = std::log2(errs[2] / errs[3]);
    std::printf("%-32s error vs CVODE dt=4e-4: %.3e, 2e-4: %.3e, 1e-4: %.3e, 5e-5: %.3e; order %.3f\n",
                c.name, errs[0], errs[1], errs[2], errs[3], order);
    EXPECT_NEAR(order, c.order, 0.15) << c.name;
  }
}

// ------------------------------------------------------------------ tensor-mass quasi-static creep (IDA)

/// The creep cube (ode_test_problems.hpp): one Prony term alpha = 1, tau = 0.5 s, the traction on a C1 ramp
/// over 1 s, held to 2 s.
using test::CreepCube;

TEST(OdeReferences, StaticSolverConvergesToIdaQuasiStaticReference) {
  const CreepCube c;
  const ViscoelasticOptions base{ViscoelasticOptions::History::Pk2, Integ::ExactLinear,
                                 ViscoelasticOptions::Relaxation::Full};
  // IDA reference at t = 0.1 k, k = 1..20
  std::vector<VecX> ref;
  IntegratorStats s;
  {
    ViscoelasticStVK model(c.mesh, c.mat, c.prony, base);
    MechanicalSystem sys(model, lumped_dof_mass(c.node_mass), DirichletSet(c.mesh.num_points(), c.bc),
                         c.loads);
    TensorMassQuasiStaticDae dae(c.mesh, c.mat, c.prony, base, sys);
    DaeOptions o;
    o.rtol = 1e-10;
    o.atol_vector = dae.absolute_tolerances(1e-3 * o.rtol * 1e-4, 1e-3 * o.rtol * 200.0);
    DaeIntegrator ida(dae, o, 0.0, dae.initial_state(0.0, VecX::Zero(dae.num_dofs())),
                      VecX::Zero(dae.size()));
    VecX y, yp;
    for (int k = 1; k <= 20; ++k) {
      ida.advance(0.1 * k, y, yp);
      ref.push_back(y.head(dae.num_dofs()));
    }
    s = ida.stats();
  }
  double scale = 0.0;
  for (const VecX& r : ref) scale = std::max(scale, r.cwiseAbs().maxCoeff());
  std::printf(
      "IDA quasi-static creep rtol 1e-10: steps %ld residuals %ld newton %ld jacobians %ld; max |u| %.3e m\n",
      s.steps, s.rhs_evals, s.nonlinear_iterations, s.jacobian_evals, scale);
  const struct {
    Integ integ;
    const char* name;
    double order;
  } cases[] = {{Integ::Midpoint, "static + midpoint", 2.0},
               {Integ::ExactLinear, "static + exact_linear", 2.0},
               {Integ::BackwardEuler, "static + backward_euler", 1.0}};
  for (const auto& cs : cases) {
    std::vector<double> errs;
    for (int level = 0; level < 4; ++level) {
      const int per = 1 << level;
      const double dt = 0.1 / per;
      ViscoelasticOptions opt = base;
      opt.integration = cs.integ;
      ViscoelasticStVK model(c.mesh, c.mat, c.prony, opt);
      MechanicalSystem sys(model, lumped_dof_mass(c.node_mass), DirichletSet(c.mesh.num_points(), c.bc),
                           c.loads);
      StaticSolver solver(sys, NewtonOptions{40, 1e-11, 1e-15});
      VecX u = VecX::Zero(sys.num_dofs());
      double e = 0.0;
      for (int k = 1; k <= 20 * per; ++k) {
        solver.advance((k - 1) * dt, k * dt, u);
        if (k % per == 0)
          e = std::max(e, (u - ref[static_cast<std::size_t>(k / per - 1)]).cwiseAbs().maxCoeff());
      }
      errs.push_back(e / scale);
    }
    const double order = std::log2(errs[2] / errs[3]);
    std::printf("%-24s error vs IDA dt=0.1: %.3e, 0.05: %.3e, 0.025: %.3e, 0.0125: %.3e; order %.3f\n",
                cs.name, errs[0], errs[1], errs[2], errs[3], order);
    EXPECT_NEAR(order, cs.order, 0.15) << cs.name;
  }
}

// ------------------------------------------------------------------ multirate (MRIStep)

TEST(OdeReferences, MriStepConvergesAtItsSlowOrder) {
  // SDOF: slow = the Maxwell branch h' = k v - h/tau, fast = the mass (adaptive inner steps, rtol 1e-12)
  {
    std::vector<double> errs;
    for (double hs : {0.04, 0.02, 0.01, 0.005}) {
      SlsOscillator sys(1.0, 4.0 * kPi * kPi, 1.0, 0.1, 0.0, 1.0);
      OdeOptions o;
      o.rtol = 1e-12;
      o.atol = 1e-15;
      o.slow_step = hs;
      OdeIntegrator mri(sys, OdeMethod::ArkodeMri, o, 0.0, sys.initial_state());
      VecX y;
      double e = 0.0, scale = 0.0;
      for (int i = 1; i <= 10; ++i) {
        mri.advance(0.2 * i, y);
        const Eigen::Vector3d ex = sys.exact(0.2 * i);
        e = std::max(e, (Eigen::Vector3d(y) - ex).cwiseAbs().maxCoeff());
        scale = std::max(scale, ex.cwiseAbs().maxCoeff());
      }
      const IntegratorStats st = mri.stats();
      std::printf("oscillator MRIStep slow step %.3f: error %.3e, slow steps %ld, fast steps %ld\n", hs,
                  e / scale, st.steps, st.fast_steps);
      errs.push_back(e / scale);
    }
    const double order = std::log2(errs[2] / errs[3]);
    std::printf("oscillator MRIStep observed slow order %.3f\n", order);
    EXPECT_NEAR(order, 3.0, 0.3);
  }
  // Tensor-mass block: slow = the Prony internal variables, fast = the mechanics (the seed's split of a
  // slow history update and a fast haptic-rate mechanics loop), against CVODE at rtol 1e-10.
  {
    const Block b;
    const ViscoelasticOptions opt{ViscoelasticOptions::History::Pk2, Integ::ExactLinear,
                                  ViscoelasticOptions::Relaxation::Full};
    const double t_end = 0.02;
    IntegratorStats sref;
    const VecX ref = reference_solution(b, opt, OdeMethod::CvodeBdf, 1e-10, t_end, &sref);
    const double scale = ref.cwiseAbs().maxCoeff();
    std::vector<double> errs;
    for (double hs : {2e-3, 1e-3, 5e-4}) {
      ViscoelasticStVK model(b.mesh, b.mat, b.prony, opt);
      MechanicalSystem sys(model, lumped_dof_mass(b.node_mass), b.bc(), ExternalLoads(b.mesh, b.node_mass));
      TensorMassViscoelasticOde ode(b.mesh, b.mat, b.prony, opt, sys);
      OdeOptions o;
      o.rtol = 1e-10;
      o.atol_vector = ode.absolute_tolerances(1e-16, 1e-13, 1e-9);
      o.slow_step = hs;
      OdeIntegrator mri(ode, OdeMethod::ArkodeMri, o, 0.0,
                        ode.initial_state(0.0, VecX::Zero(ode.num_dofs()), b.v0));
      VecX y;
      mri.advance(t_end, y);
      const IntegratorStats st = mri.stats();
      errs.push_back((ode.displacement(t_end, y) - ref).cwiseAbs().maxCoeff() / scale);
      std::printf(
          "tensor-mass MRIStep slow step %.0e: error vs CVODE %.3e, slow steps %ld (f_S %ld), fast steps %ld "
          "(f_F %ld)\n",
          hs, errs.back(), st.steps, st.rhs_evals, st.fast_steps, st.fast_rhs_evals);
    }
    const double order = std::log2(errs[1] / errs[2]);
    std::printf("tensor-mass MRIStep observed slow order %.3f\n", order);
    EXPECT_NEAR(order, 3.0, 0.4);
  }
}

}  // namespace
}  // namespace tmlab::tm
