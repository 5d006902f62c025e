// The SUNDIALS adapter (sundials_adapter.hpp): CVODE, ARKStep and IDA on y' = -lambda y (closed form
// exp(-lambda t)), stats, move semantics, and SUNDIALS failures / callback exceptions turned into
// tmlab::Error naming the SUNDIALS function and flag.
#include "core/base/error.hpp"
#include "reference_fem/sundials/sundials_adapter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace tmlab::tm {
namespace {

/// y_i' = -lambda_i y_i, y_i(0) = 1 (closed form exp(-lambda_i t)), optionally throwing at t > throw_after.
class Decay : public OdeSystem {
 public:
  explicit Decay(VecX lambda) : lambda_(std::move(lambda)) {}
  Index size() const override { return lambda_.size(); }
  void rhs(double t, const VecX& y, VecX& ydot) override {
    if (t > throw_after) throw std::runtime_error("decay rhs refused t = " + std::to_string(t));
    ydot = -lambda_.cwiseProduct(y);
  }
  bool has_jacobian_times() const override { return true; }
  void jacobian_times(double, const VecX&, const VecX& v, VecX& Jv) override {
    ++jtimes_calls;
    Jv = -lambda_.cwiseProduct(v);
  }
  double throw_after = 1e300;
  long jtimes_calls = 0;
  VecX lambda_;
};

/// 0 = y0 - sin(t) (algebraic), 0 = y1' - y0 (differential): y1 = 1 - cos(t).
class SineDae : public DaeSystem {
 public:
  Index size() const override { return 2; }
  void residual(double t, const VecX& y, const VecX& yp, VecX& r) override {
    r.resize(2);
    r[0] = y[0] - std::sin(t);
    r[1] = yp[1] - y[0];
  }
  VecX differential() const override { return (VecX(2) << 0.0, 1.0).finished(); }
};

TEST(SundialsAdapter, ReportsVersion) {
  const std::string v = sundials_version();
  std::printf("SUNDIALS %s\n", v.c_str());
  EXPECT_EQ(v.rfind("6.", 0), 0u) << v;
}

TEST(SundialsAdapter, EveryMethodAndLinearSolverSolvesDecay) {
  VecX lambda(3);
  lambda << 1.0, 10.0, 1000.0;  // stiff
  for (OdeMethod m : {OdeMethod::CvodeBdf, OdeMethod::ArkodeDirk}) {
    for (LinearSolverKind k : {LinearSolverKind::Dense, LinearSolverKind::Spgmr}) {
      Decay sys(lambda);
      OdeOptions o;
      o.rtol = 1e-8;
      o.atol = 1e-14;
      o.linear = k;
      OdeIntegrator ode(sys, m, o, 0.0, VecX::Ones(3));
      VecX y;
      double err = 0.0;
      for (int i = 1; i <= 10; ++i) {
        const double t = 0.1 * i;
        ode.advance(t, y);
        EXPECT_DOUBLE_EQ(ode.time(), t);
        for (int c = 0; c < 3; ++c) err = std::max(err, std::abs(y[c] - std::exp(-lambda[c] * t)));
      }
      const IntegratorStats s = ode.stats();
      std::printf("%-26s steps %5ld rhs %6ld newton %5ld lin %6ld jtimes %6ld jac %3ld: max error %.2e\n",
                  ode.describe().c_str(), s.steps, s.rhs_evals, s.nonlinear_iterations, s.linear_iterations,
                  s.jtimes_evals, s.jacobian_evals, err);
      EXPECT_LT(err, 1e-7) << ode.describe();
      EXPECT_GT(s.steps, 10);
      EXPECT_GT(s.nonlinear_iterations, 0);
      if (k == LinearSolverKind::Spgmr) {
        EXPECT_GT(s.linear_iterations, 0);
        EXPECT_GT(sys.jtimes_calls, 0);  // the system's Jacobian action is used
        EXPECT_EQ(s.jtimes_evals, sys.jtimes_calls);
      } else {
        EXPECT_GT(s.jacobian_evals, 0);
        EXPECT_EQ(sys.jtimes_calls, 0);
      }
    }
  }
}

TEST(SundialsAdapter, IntegratorsAreMovable) {
  Decay sys((VecX(1) << 2.0).finished());
  OdeOptions o;
  o.rtol = 1e-10;
  OdeIntegrator a(sys, OdeMethod::CvodeBdf, o, 0.0, VecX::Ones(1));
  VecX y;
  a.advance(0.5, y);
  OdeIntegrator b(std::move(a));
  b.advance(1.0, y);
  EXPECT_NEAR(y[0], std::exp(-2.0), 1e-8);
}

TEST(SundialsAdapter, SundialsFailuresBecomeErrorsNamingFunctionAndFlag) {
  Decay sys((VecX(1) << 1.0).finished());
  OdeOptions bad;
  bad.rtol = -1.0;
  try {
    OdeIntegrator ode(sys, OdeMethod::CvodeBdf, bad, 0.0, VecX::Ones(1));
    FAIL() << "negative rtol accepted";
  } catch (const Error& e) {
    const std::string w = e.what();
    std::printf("%s\n", w.c_str());
    EXPECT_NE(w.find("CVodeSStolerances"), std::string::npos) << w;
    EXPECT_NE(w.find("CV_ILL_INPUT"), std::string::npos) << w;
  }
  try {
    OdeIntegrator ode(sys, OdeMethod::ArkodeDirk, bad, 0.0, VecX::Ones(1));
    FAIL() << "negative rtol accepted";
  } catch (const Error& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("ARKStepSStolerances"), std::string::npos) << w;
    EXPECT_NE(w.find("ARK_ILL_INPUT"), std::string::npos) << w;
  }
  OdeOptions few;
  few.max_steps = 3;
  few.rtol = 1e-10;
  OdeIntegrator ode(sys, OdeMethod::CvodeBdf, few, 0.0, VecX::Ones(1));
  VecX y;
  try {
    ode.advance(10.0, y);
    FAIL() << "max_steps not enforced";
  } catch (const Error& e) {
    const std::string w = e.what();
    std::printf("%s\n", w.c_str());
    EXPECT_NE(w.find("CVode "), std::string::npos) << w;
    EXPECT_NE(w.find("CV_TOO_MUCH_WORK"), std::string::npos) << w;
  }
  EXPECT_THROW(OdeIntegrator(sys, OdeMethod::CvodeBdf, OdeOptions{}, 0.0, VecX::Ones(2)), Error);
  // ImEx and MRIStep need the corresponding split of the system
  EXPECT_THROW(OdeIntegrator(sys, OdeMethod::ArkodeImex, OdeOptions{}, 0.0, VecX::Ones(1)), Error);
  OdeOptions mri;
  mri.slow_step = 0.1;
  EXPECT_THROW(OdeIntegrator(sys, OdeMethod::ArkodeMri, mri, 0.0, VecX::Ones(1)), Error);
}

TEST(SundialsAdapter, CallbackExceptionsPropagateUnchanged) {
  for (OdeMethod m : {OdeMethod::CvodeBdf, OdeMethod::ArkodeDirk}) {
    Decay sys((VecX(1) << 1.0).finished());
    sys.throw_after = 0.5;
    OdeIntegrator ode(sys, m, OdeOptions{}, 0.0, VecX::Ones(1));
    VecX y;
    try {
      ode.advance(1.0, y);
      FAIL() << "exception swallowed";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("decay rhs refused"), std::string::npos) << e.what();
    }
  }
}

TEST(SundialsAdapter, IdaSolvesSemiExplicitIndexOneDae) {
  SineDae dae;
  DaeOptions o;
  o.rtol = 1e-9;
  o.atol = 1e-12;
  // inconsistent y0[0] = 0.3: IDACalcIC corrects the algebraic component (and y1')
  DaeIntegrator ida(dae, o, 0.0, (VecX(2) << 0.3, 0.0).finished(), VecX::Zero(2));
  VecX y, yp;
  double err = 0.0;
  for (int i = 1; i <= 20; ++i) {
    const double t = 0.25 * i;
    ida.advance(t, y, yp);
    err = std::max({err, std::abs(y[0] - std::sin(t)), std::abs(y[1] - (1.0 - std::cos(t)))});
  }
  const IntegratorStats s = ida.stats();
  std::printf("IDA: steps %ld residuals %ld newton %ld: max error %.2e\n", s.steps, s.rhs_evals,
              s.nonlinear_iterations, err);
  EXPECT_LT(err, 1e-7);
}

}  // namespace
}  // namespace tmlab::tm
