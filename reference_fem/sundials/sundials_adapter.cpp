// SUNDIALS 6.4 adapter: the only translation unit of tmlab that includes SUNDIALS headers.
// See sundials_adapter.hpp for the contract. Callback pattern: SUNDIALS passes the Impl object as
// user_data; each callback copies the N_Vector data into Eigen scratch vectors owned by the Impl,
// calls the tmlab system and copies the result back. C++ exceptions never cross the C boundary.
#include "reference_fem/sundials/sundials_adapter.hpp"

#include "core/base/error.hpp"

#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_mristep.h>
#include <cvode/cvode.h>
#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_version.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <cstdlib>
#include <cstring>
#include <exception>
#include <sstream>
#include <utility>

namespace tmlab::tm {
namespace {

// ---------------------------------------------------------------- RAII handles

struct ContextHandle {
  SUNContext ctx = nullptr;
  ContextHandle() {
    if (SUNContext_Create(nullptr, &ctx) != 0 || ctx == nullptr)
      throw Error("SUNDIALS SUNContext_Create failed");
  }
  ~ContextHandle() {
    if (ctx) SUNContext_Free(&ctx);
  }
  ContextHandle(const ContextHandle&) = delete;
  ContextHandle& operator=(const ContextHandle&) = delete;
};

struct VectorDeleter {
  void operator()(_generic_N_Vector* v) const { N_VDestroy(v); }
};
using VectorHandle = std::unique_ptr<_generic_N_Vector, VectorDeleter>;
struct MatrixDeleter {
  void operator()(_generic_SUNMatrix* m) const { SUNMatDestroy(m); }
};
using MatrixHandle = std::unique_ptr<_generic_SUNMatrix, MatrixDeleter>;
struct LinSolDeleter {
  void operator()(_generic_SUNLinearSolver* s) const { SUNLinSolFree(s); }
};
using LinSolHandle = std::unique_ptr<_generic_SUNLinearSolver, LinSolDeleter>;

VectorHandle new_vector(Index n, SUNContext ctx, const char* what) {
  N_Vector v = N_VNew_Serial(static_cast<sunindextype>(n), ctx);
  if (!v) throw Error(std::string("SUNDIALS N_VNew_Serial failed for ") + what);
  return VectorHandle(v);
}
void copy_in(const VecX& x, N_Vector v) {
  std::memcpy(N_VGetArrayPointer(v), x.data(), sizeof(double) * static_cast<std::size_t>(x.size()));
}
void copy_out(N_Vector v, VecX& x) {
  std::memcpy(x.data(), N_VGetArrayPointer(v), sizeof(double) * static_cast<std::size_t>(x.size()));
}

using FlagNameFn = char* (*)(long int);

/// Turns a negative SUNDIALS return flag into tmlab::Error("SUNDIALS <function> failed: <FLAG> (<value>):
/// <msg>").
void check(int flag, const char* function, FlagNameFn name_of, const std::string& last_message) {
  if (flag >= 0) return;
  std::ostringstream os;
  os << "SUNDIALS " << function << " failed: ";
  if (name_of) {
    char* name = name_of(flag);
    if (name) {
      os << name;
      free(name);  // the *GetReturnFlagName functions malloc their result
    }
  }
  os << " (" << flag << ")";
  if (!last_message.empty()) os << ": " << last_message;
  throw Error(os.str());
}
void check_ptr(const void* p, const char* function) {
  if (!p) throw Error(std::string("SUNDIALS ") + function + " failed: returned a null pointer");
}

/// State shared by the error handler and the callbacks of one integrator.
struct CallbackState {
  std::string last_message;
  std::exception_ptr pending;
  void rethrow_pending() {
    if (pending) {
      std::exception_ptr e = pending;
      pending = nullptr;
      std::rethrow_exception(e);
    }
  }
};

// Error handler (CVErrHandlerFn, ARKErrHandlerFn, IDAErrHandlerFn share the signature): keeps the
// message for the exception instead of printing it.
void error_handler(int error_code, const char* module, const char* function, char* msg, void* data) {
  auto* st = static_cast<CallbackState*>(data);
  std::ostringstream os;
  os << (module ? module : "") << "::" << (function ? function : "") << " [" << error_code << "] "
     << (msg ? msg : "");
  st->last_message = os.str();
}

}  // namespace

std::string to_string(OdeMethod m) {
  switch (m) {
    case OdeMethod::CvodeBdf:
      return "CVODE BDF";
    case OdeMethod::ArkodeDirk:
      return "ARKStep DIRK";
    case OdeMethod::ArkodeImex:
      return "ARKStep ImEx";
    case OdeMethod::ArkodeMri:
      return "MRIStep";
  }
  return "?";
}
std::string to_string(LinearSolverKind k) {
  switch (k) {
    case LinearSolverKind::Dense:
      return "dense";
    case LinearSolverKind::Spgmr:
      return "spgmr";
    case LinearSolverKind::SpgmrPreconditioned:
      return "spgmr+prec";
  }
  return "?";
}

std::string sundials_version() {
  char buf[64] = {0};
  SUNDIALSGetVersion(buf, sizeof(buf));
  return buf;
}

// ================================================================ ODE

struct OdeIntegrator::Impl {
  OdeSystem& system;
  OdeMethod method;
  OdeOptions options;
  ContextHandle ctx;
  VectorHandle y, atol;
  MatrixHandle A;
  LinSolHandle LS;
  void* mem = nullptr;
  double t = 0.0;
  CallbackState cb;
  VecX ys, ydot, vs, jv;  // scratch for callbacks

  Impl(OdeSystem& s, OdeMethod m, const OdeOptions& o) : system(s), method(m), options(o) {}
  // (the destructor frees CVODE or ARKStep memory; both ARKStep variants use ARKStepFree)
  void* inner = nullptr;                  // MRIStep: the fast ARKStep
  MRIStepInnerStepper stepper = nullptr;  // MRIStep: its inner-stepper wrapper

  ~Impl() {
    if (mem) {
      if (method == OdeMethod::CvodeBdf)
        CVodeFree(&mem);
      else if (method == OdeMethod::ArkodeMri)
        MRIStepFree(&mem);
      else
        ARKStepFree(&mem);
    }
    if (stepper) MRIStepInnerStepper_Free(&stepper);
    if (inner) ARKStepFree(&inner);
  }
  FlagNameFn flag_name() const {
    if (method == OdeMethod::CvodeBdf) return CVodeGetReturnFlagName;
    return method == OdeMethod::ArkodeMri ? MRIStepGetReturnFlagName : ARKStepGetReturnFlagName;
  }
  // f_S, f_F (ARKRhsFn, MRIStep)
  static int rhs_slow(realtype t, N_Vector y, N_Vector ydot, void* data) {
    auto* self = static_cast<Impl*>(data);
    try {
      copy_out(y, self->ys);
      self->system.rhs_slow(t, self->ys, self->ydot);
      copy_in(self->ydot, ydot);
      return 0;
    } catch (...) {
      self->cb.pending = std::current_exception();
      return -1;
    }
  }
  static int rhs_fast(realtype t, N_Vector y, N_Vector ydot, void* data) {
    auto* self = static_cast<Impl*>(data);
    try {
      copy_out(y, self->ys);
      self->system.rhs_fast(t, self->ys, self->ydot);
      copy_in(self->ydot, ydot);
      return 0;
    } catch (...) {
      self->cb.pending = std::current_exception();
      return -1;
    }
  }
  void ck(int flag, const char* fn) {
    cb.rethrow_pending();
    check(flag, fn, flag_name(), cb.last_message);
  }

  // f(t, y) (CVRhsFn / ARKRhsFn)
  static int rhs(realtype t, N_Vector y, N_Vector ydot, void* data) {
    auto* self = static_cast<Impl*>(data);
    try {
      copy_out(y, self->ys);
      self->system.rhs(t, self->ys, self->ydot);
      copy_in(self->ydot, ydot);
      return 0;
    } catch (...) {
      self->cb.pending = std::current_exception();
      return -1;  // unrecoverable
    }
  }
  // f_E(t, y), f_I(t, y) (ARKRhsFn, ImEx)
  static int rhs_explicit(realtype t, N_Vector y, N_Vector ydot, void* data) {
    auto* self = static_cast<Impl*>(data);
    try {
      copy_out(y, self->ys);
      self->system.rhs_explicit(t, self->ys, self->ydot);
      copy_in(self->ydot, ydot);
      return 0;
    } catch (...) {
      self->cb.pending = std::current_exception();
      return -1;
    }
  }
  static int rhs_implicit(realtype t, N_Vector y, N_Vector ydot, void* data) {
    auto* self = static_cast<Impl*>(data);
    try {
      copy_out(y, self->ys);
      self->system.rhs_implicit(t, self->ys, self->ydot);
      copy_in(self->ydot, ydot);
      return 0;
    } catch (...) {
      self->cb.pending = std::current_exception();
      return -1;
    }
  }
  // J v (CVLsJacTimesVecFn / ARKLsJacTimesVecFn); J = df_I/dy for ImEx
  static int jtimes_implicit(N_Vector v, N_Vector Jv, realtype t, N_Vector y, N_Vector /*fy*/, void* data,
                             N_Vector /*tmp*/) {
    auto* self = static_cast<Impl*>(data);
    try {
      copy_out(y, self->ys);
      copy_out(v, self->vs);
      self->system.jacobian_times_implicit(t, self->ys, self->vs, self->jv);
      copy_in(self->jv, Jv);
      return 0;
    } catch (...) {
      self->cb.pending = std::current_exception();
      return -1;
    }
  }
  // P ~ I - gamma J (CVLsPrecSetupFn / ARKLsPrecSetupFn share the signature)
  static int psetup(realtype t, N_Vector y, N_Vector /*fy*/, booleantype jok, booleantype* jcur,
                    realtype gamma, void* data) {
    auto* self = static_cast<Impl*>(data);
    try {
      copy_out(y, self->ys);
      bool updated = false;
      const bool ok = self->system.preconditioner_setup(t, self->ys, gamma, jok != SUNFALSE, updated);
      *jcur = updated ? SUNTRUE : SUNFALSE;
      return ok ? 0 : 1;  // 1: recoverable (the integrator retries)
    } catch (...) {
      self->cb.pending = std::current_exception();
      return -1;
    }
  }
  // z = P^{-1} r (CVLsPrecSolveFn / ARKLsPrecSolveFn)
  static int psolve(realtype t, N_Vector y, N_Vector /*fy*/, N_Vector r, N_Vector z, realtype gamma,
                    realtype /*delta*/, int /*lr*/, void* data) {
    auto* self = static_cast<Impl*>(data);
    try {
      copy_out(y, self->ys);
      copy_out(r, self->vs);
      const bool ok = self->system.preconditioner_solve(t, self->ys, self->vs, self->jv, gamma);
      copy_in(self->jv, z);
      return ok ? 0 : 1;
    } catch (...) {
      self->cb.pending = std::current_exception();
      return -1;
    }
  }
  // J v (CVLsJacTimesVecFn / ARKLsJacTimesVecFn)
  static int jtimes(N_Vector v, N_Vector Jv, realtype t, N_Vector y, N_Vector /*fy*/, void* data,
                    N_Vector /*tmp*/) {
    auto* self = static_cast<Impl*>(data);
    try {
      copy_out(y, self->ys);
      copy_out(v, self->vs);
      self->system.jacobian_times(t, self->ys, self->vs, self->jv);
      copy_in(self->jv, Jv);
      return 0;
    } catch (...) {
      self->cb.pending = std::current_exception();
      return -1;
    }
  }
};

OdeIntegrator::OdeIntegrator(OdeSystem& system, OdeMethod method, const OdeOptions& options, double t0,
                             const VecX& y0)
    : impl_(std::make_unique<Impl>(system, method, options)) {
  Impl& I = *impl_;
  const Index n = system.size();
  if (y0.size() != n)
    throw Error("OdeIntegrator: y0 has " + std::to_string(y0.size()) + " entries, the system " +
                std::to_string(n));
  if (options.atol_vector.size() != 0 && options.atol_vector.size() != n)
    throw Error("OdeIntegrator: atol_vector has " + std::to_string(options.atol_vector.size()) +
                " entries, the system " + std::to_string(n));
  I.ys.resize(n);
  I.ydot.resize(n);
  I.vs.resize(n);
  I.jv.resize(n);
  I.t = t0;
  SUNContext ctx = I.ctx.ctx;
  I.y = new_vector(n, ctx, "y");
  copy_in(y0, I.y.get());

  if (method == OdeMethod::ArkodeMri) {
    // y' = f_S(t, y) + f_F(t, y): inner explicit ARKStep on f_F, outer explicit MRI-GARK on f_S
    if (!system.has_multirate()) throw Error("OdeIntegrator: MRIStep needs a system with a slow/fast split");
    if (!(options.slow_step > 0.0)) throw Error("OdeIntegrator: MRIStep needs OdeOptions::slow_step > 0");
    I.inner = ARKStepCreate(&Impl::rhs_fast, nullptr, t0, I.y.get(), ctx);
    check_ptr(I.inner, "ARKStepCreate (fast)");
    I.ck(ARKStepSetErrHandlerFn(I.inner, error_handler, &I.cb), "ARKStepSetErrHandlerFn");
    I.ck(ARKStepSetUserData(I.inner, &I), "ARKStepSetUserData");
    I.ck(ARKStepSetMaxNumSteps(I.inner, options.max_steps), "ARKStepSetMaxNumSteps");
    if (options.fast_step > 0.0)
      I.ck(ARKStepSetFixedStep(I.inner, options.fast_step), "ARKStepSetFixedStep");
    else
      I.ck(ARKStepSStolerances(I.inner, options.rtol, options.atol), "ARKStepSStolerances");
    if (options.fast_step <= 0.0 && options.atol_vector.size() == n) {
      I.atol = new_vector(n, ctx, "atol");
      copy_in(options.atol_vector, I.atol.get());
      I.ck(ARKStepSVtolerances(I.inner, options.rtol, I.atol.get()), "ARKStepSVtolerances");
    }
    I.ck(ARKStepCreateMRIStepInnerStepper(I.inner, &I.stepper), "ARKStepCreateMRIStepInnerStepper");
    I.mem = MRIStepCreate(&Impl::rhs_slow, nullptr, t0, I.y.get(), I.stepper, ctx);
    check_ptr(I.mem, "MRIStepCreate");
    I.ck(MRIStepSetErrHandlerFn(I.mem, error_handler, &I.cb), "MRIStepSetErrHandlerFn");
    I.ck(MRIStepSetUserData(I.mem, &I), "MRIStepSetUserData");
    I.ck(MRIStepSetFixedStep(I.mem, options.slow_step), "MRIStepSetFixedStep");
    I.ck(MRIStepSetMaxNumSteps(I.mem, options.max_steps), "MRIStepSetMaxNumSteps");
    if (options.order > 0) I.ck(MRIStepSetOrder(I.mem, options.order), "MRIStepSetOrder");
    return;
  }
  if (method == OdeMethod::CvodeBdf) {
    I.mem = CVodeCreate(CV_BDF, ctx);
    check_ptr(I.mem, "CVodeCreate");
    I.ck(CVodeSetErrHandlerFn(I.mem, error_handler, &I.cb), "CVodeSetErrHandlerFn");
    I.ck(CVodeInit(I.mem, &Impl::rhs, t0, I.y.get()), "CVodeInit");
    I.ck(CVodeSetUserData(I.mem, &I), "CVodeSetUserData");
  } else if (method == OdeMethod::ArkodeImex) {
    if (!system.has_split())
      throw Error("OdeIntegrator: ARKStep ImEx needs a system with an explicit/implicit split");
    I.mem = ARKStepCreate(&Impl::rhs_explicit, &Impl::rhs_implicit, t0, I.y.get(), ctx);  // y' = f_E + f_I
    check_ptr(I.mem, "ARKStepCreate");
    I.ck(ARKStepSetErrHandlerFn(I.mem, error_handler, &I.cb), "ARKStepSetErrHandlerFn");
    I.ck(ARKStepSetUserData(I.mem, &I), "ARKStepSetUserData");
  } else {
    I.mem = ARKStepCreate(nullptr, &Impl::rhs, t0, I.y.get(), ctx);  // f_E = none, f_I = f
    check_ptr(I.mem, "ARKStepCreate");
    I.ck(ARKStepSetErrHandlerFn(I.mem, error_handler, &I.cb), "ARKStepSetErrHandlerFn");
    I.ck(ARKStepSetUserData(I.mem, &I), "ARKStepSetUserData");
  }
  const bool cv = method == OdeMethod::CvodeBdf;
  // Tolerances: local error test ||e_i / (rtol |y_i| + atol_i)||_WRMS <= 1.
  if (options.atol_vector.size() == n) {
    I.atol = new_vector(n, ctx, "atol");
    copy_in(options.atol_vector, I.atol.get());
    I.ck(cv ? CVodeSVtolerances(I.mem, options.rtol, I.atol.get())
            : ARKStepSVtolerances(I.mem, options.rtol, I.atol.get()),
         cv ? "CVodeSVtolerances" : "ARKStepSVtolerances");
  } else {
    I.ck(cv ? CVodeSStolerances(I.mem, options.rtol, options.atol)
            : ARKStepSStolerances(I.mem, options.rtol, options.atol),
         cv ? "CVodeSStolerances" : "ARKStepSStolerances");
  }
  I.ck(cv ? CVodeSetMaxNumSteps(I.mem, options.max_steps) : ARKStepSetMaxNumSteps(I.mem, options.max_steps),
       cv ? "CVodeSetMaxNumSteps" : "ARKStepSetMaxNumSteps");
  if (options.max_step > 0.0)
    I.ck(cv ? CVodeSetMaxStep(I.mem, options.max_step) : ARKStepSetMaxStep(I.mem, options.max_step),
         cv ? "CVodeSetMaxStep" : "ARKStepSetMaxStep");
  if (options.initial_step > 0.0)
    I.ck(cv ? CVodeSetInitStep(I.mem, options.initial_step) : ARKStepSetInitStep(I.mem, options.initial_step),
         cv ? "CVodeSetInitStep" : "ARKStepSetInitStep");
  if (options.order > 0)
    I.ck(cv ? CVodeSetMaxOrd(I.mem, options.order) : ARKStepSetOrder(I.mem, options.order),
         cv ? "CVodeSetMaxOrd" : "ARKStepSetOrder");

  // Linear solver of the Newton iteration: (I - gamma J) x = b.
  if (options.linear == LinearSolverKind::Dense) {
    I.A.reset(SUNDenseMatrix(static_cast<sunindextype>(n), static_cast<sunindextype>(n), ctx));
    check_ptr(I.A.get(), "SUNDenseMatrix");
    I.LS.reset(SUNLinSol_Dense(I.y.get(), I.A.get(), ctx));
    check_ptr(I.LS.get(), "SUNLinSol_Dense");
    // ARKStep with its default lagged linear-solver setup (I - gamma J rebuilt every 20 steps or on a
    // large gamma change) lost accuracy on the SLS oscillator with the dense solver (error 5e-6 at
    // rtol 1e-10, not decreasing with rtol; test_ode_references); a setup every step (the current
    // gamma; the DQ Jacobian itself is still reused) restores errors of ~0.04 rtol. Dense is for
    // small systems only, so the extra factorisations are cheap.
    if (!cv) I.ck(ARKStepSetLSetupFrequency(I.mem, 1), "ARKStepSetLSetupFrequency");
  } else {
    const bool prec = options.linear == LinearSolverKind::SpgmrPreconditioned;
    if (prec && method == OdeMethod::ArkodeImex)
      throw Error(
          "OdeIntegrator: preconditioned SPGMR is available for CVODE BDF and ARKStep DIRK, not for ImEx "
          "(its implicit part has its own, different Newton matrix)");
    if (prec && !system.has_preconditioner())
      throw Error(
          "OdeIntegrator: preconditioned SPGMR needs a system with a preconditioner (has_preconditioner())");
    I.LS.reset(SUNLinSol_SPGMR(I.y.get(), prec ? SUN_PREC_LEFT : SUN_PREC_NONE, options.krylov_dim, ctx));
    check_ptr(I.LS.get(), "SUNLinSol_SPGMR");
  }
  I.ck(cv ? CVodeSetLinearSolver(I.mem, I.LS.get(), I.A.get())
          : ARKStepSetLinearSolver(I.mem, I.LS.get(), I.A.get()),
       cv ? "CVodeSetLinearSolver" : "ARKStepSetLinearSolver");
  if (options.linear == LinearSolverKind::SpgmrPreconditioned)
    I.ck(cv ? CVodeSetPreconditioner(I.mem, &Impl::psetup, &Impl::psolve)
            : ARKStepSetPreconditioner(I.mem, &Impl::psetup, &Impl::psolve),
         cv ? "CVodeSetPreconditioner" : "ARKStepSetPreconditioner");
  if (options.linear != LinearSolverKind::Dense && system.has_jacobian_times()) {
    if (cv)
      I.ck(CVodeSetJacTimes(I.mem, nullptr, &Impl::jtimes), "CVodeSetJacTimes");
    else if (method == OdeMethod::ArkodeImex)
      I.ck(ARKStepSetJacTimes(I.mem, nullptr, &Impl::jtimes_implicit), "ARKStepSetJacTimes");
    else
      I.ck(ARKStepSetJacTimes(I.mem, nullptr, &Impl::jtimes), "ARKStepSetJacTimes");
  }
}

OdeIntegrator::~OdeIntegrator() = default;
OdeIntegrator::OdeIntegrator(OdeIntegrator&&) noexcept = default;
OdeIntegrator& OdeIntegrator::operator=(OdeIntegrator&&) noexcept = default;

void OdeIntegrator::advance(double t_out, VecX& y) {
  Impl& I = *impl_;
  realtype tret = I.t;
  if (I.method == OdeMethod::CvodeBdf)
    I.ck(CVode(I.mem, t_out, I.y.get(), &tret, CV_NORMAL), "CVode");
  else if (I.method == OdeMethod::ArkodeMri)
    I.ck(MRIStepEvolve(I.mem, t_out, I.y.get(), &tret, ARK_NORMAL), "MRIStepEvolve");
  else
    I.ck(ARKStepEvolve(I.mem, t_out, I.y.get(), &tret, ARK_NORMAL), "ARKStepEvolve");
  I.t = tret;
  y.resize(I.system.size());
  copy_out(I.y.get(), y);
}

double OdeIntegrator::time() const { return impl_->t; }
OdeMethod OdeIntegrator::method() const { return impl_->method; }
std::string OdeIntegrator::describe() const {
  if (impl_->method == OdeMethod::ArkodeMri) return "MRIStep (explicit slow, explicit ARKStep fast)";
  std::string d = to_string(impl_->method);
  if (impl_->options.order > 0)
    d += (impl_->method == OdeMethod::CvodeBdf ? " (max order " : " (order ") +
         std::to_string(impl_->options.order) + ")";
  return d + " + " + to_string(impl_->options.linear);
}

IntegratorStats OdeIntegrator::stats() const {
  Impl& I = *impl_;
  IntegratorStats s;
  if (I.method == OdeMethod::CvodeBdf) {
    CVodeGetNumSteps(I.mem, &s.steps);
    CVodeGetNumRhsEvals(I.mem, &s.rhs_evals);
    CVodeGetNumNonlinSolvIters(I.mem, &s.nonlinear_iterations);
    CVodeGetNumNonlinSolvConvFails(I.mem, &s.nonlinear_failures);
    CVodeGetNumLinIters(I.mem, &s.linear_iterations);
    CVodeGetNumErrTestFails(I.mem, &s.error_test_failures);
    CVodeGetNumJacEvals(I.mem, &s.jacobian_evals);
    CVodeGetNumJtimesEvals(I.mem, &s.jtimes_evals);
    CVodeGetLastStep(I.mem, &s.last_step);
    CVodeGetNumPrecEvals(I.mem, &s.preconditioner_setups);
    CVodeGetNumPrecSolves(I.mem, &s.preconditioner_solves);
  } else if (I.method == OdeMethod::ArkodeMri) {
    long fsi = 0, ffi = 0;
    MRIStepGetNumSteps(I.mem, &s.steps);
    MRIStepGetNumRhsEvals(I.mem, &s.rhs_evals, &fsi);
    MRIStepGetLastStep(I.mem, &s.last_step);
    ARKStepGetNumSteps(I.inner, &s.fast_steps);
    ARKStepGetNumRhsEvals(I.inner, &s.fast_rhs_evals, &ffi);
  } else {
    ARKStepGetNumSteps(I.mem, &s.steps);
    ARKStepGetNumRhsEvals(I.mem, &s.explicit_rhs_evals, &s.rhs_evals);
    ARKStepGetNumNonlinSolvIters(I.mem, &s.nonlinear_iterations);
    ARKStepGetNumNonlinSolvConvFails(I.mem, &s.nonlinear_failures);
    ARKStepGetNumLinIters(I.mem, &s.linear_iterations);
    ARKStepGetNumErrTestFails(I.mem, &s.error_test_failures);
    ARKStepGetNumJacEvals(I.mem, &s.jacobian_evals);
    ARKStepGetNumJtimesEvals(I.mem, &s.jtimes_evals);
    ARKStepGetLastStep(I.mem, &s.last_step);
    ARKStepGetNumPrecEvals(I.mem, &s.preconditioner_setups);
    ARKStepGetNumPrecSolves(I.mem, &s.preconditioner_solves);
  }
  return s;
}

// ================================================================ DAE (IDA)

struct DaeIntegrator::Impl {
  DaeSystem& system;
  DaeOptions options;
  ContextHandle ctx;
  VectorHandle y, yp, id, atol;
  MatrixHandle A;
  LinSolHandle LS;
  void* mem = nullptr;
  double t = 0.0;
  bool ic_done = false;
  CallbackState cb;
  VecX ys, yps, r, vs, out;

  Impl(DaeSystem& s, const DaeOptions& o) : system(s), options(o) {}
  ~Impl() {
    if (mem) IDAFree(&mem);
  }
  void ck(int flag, const char* fn) {
    cb.rethrow_pending();
    check(flag, fn, IDAGetReturnFlagName, cb.last_message);
  }
  // F(t, y, y') (IDAResFn)
  static int residual(realtype t, N_Vector y, N_Vector yp, N_Vector r, void* data) {
    auto* self = static_cast<Impl*>(data);
    try {
      copy_out(y, self->ys);
      copy_out(yp, self->yps);
      self->system.residual(t, self->ys, self->yps, self->r);
      copy_in(self->r, r);
      return 0;
    } catch (...) {
      self->cb.pending = std::current_exception();
      return -1;
    }
  }
  // (dF/dy + cj dF/dy') v (IDALsJacTimesVecFn)
  static int jtimes(realtype t, N_Vector y, N_Vector yp, N_Vector /*rr*/, N_Vector v, N_Vector Jv,
                    realtype cj, void* data, N_Vector /*tmp1*/, N_Vector /*tmp2*/) {
    auto* self = static_cast<Impl*>(data);
    try {
      copy_out(y, self->ys);
      copy_out(yp, self->yps);
      copy_out(v, self->vs);
      self->system.jacobian_times(t, self->ys, self->yps, self->vs, cj, self->out);
      copy_in(self->out, Jv);
      return 0;
    } catch (...) {
      self->cb.pending = std::current_exception();
      return -1;
    }
  }
  // P ~ dF/dy + cj dF/dy' (IDALsPrecSetupFn)
  static int psetup(realtype t, N_Vector y, N_Vector yp, N_Vector /*rr*/, realtype cj, void* data) {
    auto* self = static_cast<Impl*>(data);
    try {
      copy_out(y, self->ys);
      copy_out(yp, self->yps);
      return self->system.preconditioner_setup(t, self->ys, self->yps, cj) ? 0 : 1;
    } catch (...) {
      self->cb.pending = std::current_exception();
      return -1;
    }
  }
  // z = P^{-1} r (IDALsPrecSolveFn)
  static int psolve(realtype t, N_Vector y, N_Vector yp, N_Vector /*rr*/, N_Vector r, N_Vector z, realtype cj,
                    realtype /*delta*/, void* data) {
    auto* self = static_cast<Impl*>(data);
    try {
      copy_out(y, self->ys);
      copy_out(yp, self->yps);
      copy_out(r, self->vs);
      const bool ok = self->system.preconditioner_solve(t, self->ys, self->yps, self->vs, self->out, cj);
      copy_in(self->out, z);
      return ok ? 0 : 1;
    } catch (...) {
      self->cb.pending = std::current_exception();
      return -1;
    }
  }
};

DaeIntegrator::DaeIntegrator(DaeSystem& system, const DaeOptions& options, double t0, const VecX& y0,
                             const VecX& yp0)
    : impl_(std::make_unique<Impl>(system, options)) {
  Impl& I = *impl_;
  const Index n = system.size();
  if (y0.size() != n || yp0.size() != n)
    throw Error("DaeIntegrator: y0/yp0 size differs from the system size " + std::to_string(n));
  I.ys.resize(n);
  I.yps.resize(n);
  I.r.resize(n);
  I.vs.resize(n);
  I.out.resize(n);
  I.t = t0;
  SUNContext ctx = I.ctx.ctx;
  I.y = new_vector(n, ctx, "y");
  I.yp = new_vector(n, ctx, "yp");
  I.id = new_vector(n, ctx, "id");
  copy_in(y0, I.y.get());
  copy_in(yp0, I.yp.get());
  copy_in(system.differential(), I.id.get());
  I.mem = IDACreate(ctx);
  check_ptr(I.mem, "IDACreate");
  I.ck(IDASetErrHandlerFn(I.mem, error_handler, &I.cb), "IDASetErrHandlerFn");
  I.ck(IDAInit(I.mem, &Impl::residual, t0, I.y.get(), I.yp.get()), "IDAInit");
  I.ck(IDASetUserData(I.mem, &I), "IDASetUserData");
  if (options.atol_vector.size() == n) {
    I.atol = new_vector(n, ctx, "atol");
    copy_in(options.atol_vector, I.atol.get());
    I.ck(IDASVtolerances(I.mem, options.rtol, I.atol.get()), "IDASVtolerances");
  } else {
    I.ck(IDASStolerances(I.mem, options.rtol, options.atol), "IDASStolerances");
  }
  I.ck(IDASetId(I.mem, I.id.get()), "IDASetId");
  if (options.suppress_algebraic_error) I.ck(IDASetSuppressAlg(I.mem, SUNTRUE), "IDASetSuppressAlg");
  I.ck(IDASetMaxNumSteps(I.mem, options.max_steps), "IDASetMaxNumSteps");
  if (options.max_step > 0.0) I.ck(IDASetMaxStep(I.mem, options.max_step), "IDASetMaxStep");
  if (options.linear == LinearSolverKind::Dense) {
    I.A.reset(SUNDenseMatrix(static_cast<sunindextype>(n), static_cast<sunindextype>(n), ctx));
    check_ptr(I.A.get(), "SUNDenseMatrix");
    I.LS.reset(SUNLinSol_Dense(I.y.get(), I.A.get(), ctx));
    check_ptr(I.LS.get(), "SUNLinSol_Dense");
    I.ck(IDASetLinearSolver(I.mem, I.LS.get(), I.A.get()), "IDASetLinearSolver");
    return;
  }
  const bool prec = options.linear == LinearSolverKind::SpgmrPreconditioned;
  if (prec && !system.has_preconditioner())
    throw Error(
        "DaeIntegrator: preconditioned SPGMR needs a system with a preconditioner (has_preconditioner())");
  I.LS.reset(SUNLinSol_SPGMR(I.y.get(), prec ? SUN_PREC_LEFT : SUN_PREC_NONE, options.krylov_dim, ctx));
  check_ptr(I.LS.get(), "SUNLinSol_SPGMR");
  I.ck(IDASetLinearSolver(I.mem, I.LS.get(), nullptr), "IDASetLinearSolver");
  if (system.has_jacobian_times()) I.ck(IDASetJacTimes(I.mem, nullptr, &Impl::jtimes), "IDASetJacTimes");
  if (prec) I.ck(IDASetPreconditioner(I.mem, &Impl::psetup, &Impl::psolve), "IDASetPreconditioner");
}

DaeIntegrator::~DaeIntegrator() = default;
DaeIntegrator::DaeIntegrator(DaeIntegrator&&) noexcept = default;
DaeIntegrator& DaeIntegrator::operator=(DaeIntegrator&&) noexcept = default;

void DaeIntegrator::advance(double t_out, VecX& y, VecX& yp) {
  Impl& I = *impl_;
  if (!I.ic_done && I.options.consistent_initial_conditions) {
    I.ck(IDACalcIC(I.mem, IDA_YA_YDP_INIT, t_out), "IDACalcIC");
  }
  I.ic_done = true;
  realtype tret = I.t;
  I.ck(IDASolve(I.mem, t_out, &tret, I.y.get(), I.yp.get(), IDA_NORMAL), "IDASolve");
  I.t = tret;
  y.resize(I.system.size());
  yp.resize(I.system.size());
  copy_out(I.y.get(), y);
  copy_out(I.yp.get(), yp);
}

double DaeIntegrator::time() const { return impl_->t; }

IntegratorStats DaeIntegrator::stats() const {
  Impl& I = *impl_;
  IntegratorStats s;
  IDAGetNumSteps(I.mem, &s.steps);
  IDAGetNumResEvals(I.mem, &s.rhs_evals);
  IDAGetNumNonlinSolvIters(I.mem, &s.nonlinear_iterations);
  IDAGetNumNonlinSolvConvFails(I.mem, &s.nonlinear_failures);
  IDAGetNumLinIters(I.mem, &s.linear_iterations);
  IDAGetNumErrTestFails(I.mem, &s.error_test_failures);
  IDAGetNumJacEvals(I.mem, &s.jacobian_evals);
  IDAGetLastStep(I.mem, &s.last_step);
  IDAGetNumJtimesEvals(I.mem, &s.jtimes_evals);
  IDAGetNumPrecEvals(I.mem, &s.preconditioner_setups);
  IDAGetNumPrecSolves(I.mem, &s.preconditioner_solves);
  return s;
}

}  // namespace tmlab::tm
