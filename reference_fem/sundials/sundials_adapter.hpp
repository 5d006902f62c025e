// The one adapter between tmlab and SUNDIALS 6.4 (CVODE, ARKODE ARKStep, IDA). This header does not
// include any SUNDIALS header; src/sundials_adapter.cpp is the only translation unit that does.
//
//   OdeSystem      y' = f(t, y)                         (optionally with the Jacobian action J v = df/dy v)
//   OdeIntegrator  CVODE (variable-order BDF, Newton) or ARKODE ARKStep (diagonally implicit RK, or
//                  additive ImEx RK on a split f = f_E + f_I, orders 2..5), error-controlled:
//                  local error <= rtol |y_i| + atol_i; or ARKODE MRIStep (multirate: fixed slow step
//                  on f_S, inner explicit ARKStep on f_F)
//   DaeSystem      F(t, y, y') = 0 with differential / algebraic components (semi-explicit index 1)
//   DaeIntegrator  IDA (variable-order BDF), consistent initial y' of the algebraic part by IDACalcIC
//
// Linear solvers inside the Newton iterations: dense (SUNDenseMatrix + SUNLinSol_Dense, difference-
// quotient Jacobian, for small systems), matrix-free GMRES (SUNLinSol_SPGMR) without preconditioner,
// or GMRES left-preconditioned by the system's own approximate inverse of the Newton matrix
// (I - gamma J for CVODE / ARKStep, dF/dy + c_j dF/dy' for IDA; OdeSystem / DaeSystem
// preconditioner_setup / preconditioner_solve). GMRES uses the system's Jacobian action when it
// provides one, else SUNDIALS' difference quotient. A preconditioner that solves the Newton system
// exactly (a sparse direct factorisation, as the tensor-mass systems of ode_references.hpp do) makes
// GMRES converge in one iteration: the "sparse direct" option.
//
// Every failing SUNDIALS call throws tmlab::Error naming the SUNDIALS function, its return flag
// (name and value) and the last message SUNDIALS reported. An exception thrown by a user callback is
// caught at the C boundary (the callback returns an unrecoverable failure to SUNDIALS) and rethrown
// unchanged from advance(). SUNDIALS objects (SUNContext, N_Vector, SUNMatrix, SUNLinearSolver,
// integrator memory) are owned by RAII handles inside the implementation; integrators are move-only.
#pragma once

#include "tensormass/kernels/elastic_model.hpp"

#include <memory>
#include <string>

namespace tmlab::tm {

/// y' = f(t, y), y of fixed size.
class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  virtual Index size() const = 0;
  /// ydot = f(t, y) (ydot has size(), overwrite every entry).
  virtual void rhs(double t, const VecX& y, VecX& ydot) = 0;
  /// True when jacobian_times is implemented (used by the SPGMR linear solver).
  virtual bool has_jacobian_times() const { return false; }
  /// Jv = (df/dy)(t, y) v.
  virtual void jacobian_times(double /*t*/, const VecX& /*y*/, const VecX& /*v*/, VecX& /*Jv*/) {}

  // ---- additive split f = f_E + f_I for ImEx ARK (OdeMethod::ArkodeImex) ----
  /// True when rhs_explicit / rhs_implicit (and, with SPGMR, jacobian_times_implicit) are implemented.
  virtual bool has_split() const { return false; }
  /// f_E(t, y): the non-stiff part, integrated explicitly.
  virtual void rhs_explicit(double /*t*/, const VecX& /*y*/, VecX& /*ydot*/) {}
  /// f_I(t, y): the stiff part, integrated implicitly.
  virtual void rhs_implicit(double /*t*/, const VecX& /*y*/, VecX& /*ydot*/) {}
  /// Jv = (df_I/dy)(t, y) v.
  virtual void jacobian_times_implicit(double /*t*/, const VecX& /*y*/, const VecX& /*v*/, VecX& /*Jv*/) {}

  // ---- multirate split f = f_S + f_F for MRIStep (OdeMethod::ArkodeMri) ----
  /// True when rhs_slow / rhs_fast are implemented.
  virtual bool has_multirate() const { return false; }
  /// f_S(t, y): the slow part, explicit MRI-GARK with the fixed slow step.
  virtual void rhs_slow(double /*t*/, const VecX& /*y*/, VecX& /*ydot*/) {}
  /// f_F(t, y): the fast part, integrated by an inner explicit ARKStep (adaptive or fixed fast step).
  virtual void rhs_fast(double /*t*/, const VecX& /*y*/, VecX& /*ydot*/) {}

  // ---- preconditioner of the Newton matrix I - gamma J (LinearSolverKind::SpgmrPreconditioned;
  //      CVODE BDF and ARKStep DIRK) ----
  /// True when preconditioner_setup / preconditioner_solve are implemented.
  virtual bool has_preconditioner() const { return false; }
  /// Prepares P ~ I - gamma (df/dy)(t, y). `jacobian_ok`: the integrator allows reusing the Jacobian
  /// data of the previous setup (only gamma changed). Sets `jacobian_updated` to true when the
  /// Jacobian data was recomputed. Returns false on a recoverable failure (e.g. a singular
  /// factorisation: the integrator retries with a smaller step).
  virtual bool preconditioner_setup(double /*t*/, const VecX& /*y*/, double /*gamma*/, bool /*jacobian_ok*/,
                                    bool& jacobian_updated) {
    jacobian_updated = false;
    return true;
  }
  /// z = P^{-1} r, P ~ I - gamma J (the last setup). Returns false on a recoverable failure.
  virtual bool preconditioner_solve(double /*t*/, const VecX& /*y*/, const VecX& r, VecX& z,
                                    double /*gamma*/) {
    z = r;
    return true;
  }
};

/// F(t, y, y') = 0; differential()[i] != 0 when y'_i appears (the others are algebraic).
class DaeSystem {
 public:
  virtual ~DaeSystem() = default;
  virtual Index size() const = 0;
  virtual void residual(double t, const VecX& y, const VecX& yp, VecX& r) = 0;
  /// 1.0 for differential components, 0.0 for algebraic ones (IDASetId).
  virtual VecX differential() const = 0;

  // ---- iterative linear solver (DaeOptions::linear = Spgmr / SpgmrPreconditioned) ----
  /// True when jacobian_times is implemented (else SUNDIALS' difference quotient is used).
  virtual bool has_jacobian_times() const { return false; }
  /// Jv = (dF/dy + cj dF/dy')(t, y, yp) v.
  virtual void jacobian_times(double /*t*/, const VecX& /*y*/, const VecX& /*yp*/, const VecX& /*v*/,
                              double /*cj*/, VecX& /*Jv*/) {}
  /// True when preconditioner_setup / preconditioner_solve are implemented.
  virtual bool has_preconditioner() const { return false; }
  /// Prepares P ~ dF/dy + cj dF/dy' at (t, y, yp). Returns false on a recoverable failure.
  virtual bool preconditioner_setup(double /*t*/, const VecX& /*y*/, const VecX& /*yp*/, double /*cj*/) {
    return true;
  }
  /// z = P^{-1} r (the last setup). Returns false on a recoverable failure.
  virtual bool preconditioner_solve(double /*t*/, const VecX& /*y*/, const VecX& /*yp*/, const VecX& r,
                                    VecX& z, double /*cj*/) {
    z = r;
    return true;
  }
};

enum class OdeMethod {
  CvodeBdf,    ///< CVODE, BDF orders 1..5, Newton iteration
  ArkodeDirk,  ///< ARKODE ARKStep, fully implicit (f = f_I), default ESDIRK of the chosen order
  ArkodeImex,  ///< ARKODE ARKStep, additive ImEx RK on f = f_E + f_I (needs OdeSystem::has_split())
  ArkodeMri,   ///< ARKODE MRIStep: explicit slow f_S with a FIXED slow step (OdeOptions::slow_step; no
               ///< slow error control in SUNDIALS 6.4), inner explicit ARKStep on f_F (needs has_multirate())
};
enum class LinearSolverKind {
  Dense,  ///< dense LU with a difference-quotient Jacobian (small systems)
  Spgmr,  ///< matrix-free GMRES with the system's Jacobian action (or a difference quotient)
  /// GMRES left-preconditioned by the system's preconditioner_setup/solve (needs has_preconditioner();
  /// CVODE BDF, ARKStep DIRK, IDA; not ImEx or MRIStep)
  SpgmrPreconditioned,
};
std::string to_string(OdeMethod m);
std::string to_string(LinearSolverKind k);

struct OdeOptions {
  double rtol = 1e-8;
  double atol = 1e-12;  ///< scalar absolute tolerance, used when atol_vector is empty
  VecX atol_vector;     ///< per-component absolute tolerances (size() of the system), optional
  LinearSolverKind linear = LinearSolverKind::Dense;
  long max_steps = 1000000;   ///< per advance() call
  double max_step = 0.0;      ///< 0: no limit
  double initial_step = 0.0;  ///< 0: the integrator's estimate
  int order = 0;              ///< 0: default (CVODE: max order 5; ARKStep: order 4)
  int krylov_dim = 0;         ///< SPGMR restart dimension, 0: SUNDIALS default (5)
  double slow_step = 0.0;     ///< ArkodeMri: the fixed slow step (required > 0)
  double fast_step = 0.0;     ///< ArkodeMri: fixed fast step; 0: adaptive inner steps with rtol/atol
};

/// Integrator counters since construction.
struct IntegratorStats {
  long steps = 0;
  long rhs_evals = 0;           ///< f (ODE; f_I for ImEx) or F (DAE) evaluations, excluding Jacobian DQ ones
  long explicit_rhs_evals = 0;  ///< f_E evaluations (ImEx only)
  long fast_steps = 0;          ///< inner (fast) steps (MRIStep only; steps counts the slow ones)
  long fast_rhs_evals = 0;      ///< f_F evaluations (MRIStep only; rhs_evals counts f_S)
  long nonlinear_iterations = 0;  ///< Newton iterations
  long nonlinear_failures = 0;    ///< Newton convergence failures
  long linear_iterations = 0;     ///< Krylov iterations (0 for dense)
  long error_test_failures = 0;
  long jacobian_evals = 0;         ///< dense Jacobian evaluations
  long jtimes_evals = 0;           ///< Jacobian-vector products (SPGMR)
  long preconditioner_setups = 0;  ///< preconditioner_setup calls (SpgmrPreconditioned)
  long preconditioner_solves = 0;  ///< preconditioner_solve calls (SpgmrPreconditioned)
  double last_step = 0.0;
};

class OdeIntegrator {
 public:
  /// Sets up the integrator at (t0, y0). The system must outlive the integrator.
  OdeIntegrator(OdeSystem& system, OdeMethod method, const OdeOptions& options, double t0, const VecX& y0);
  ~OdeIntegrator();
  OdeIntegrator(OdeIntegrator&&) noexcept;
  OdeIntegrator& operator=(OdeIntegrator&&) noexcept;
  OdeIntegrator(const OdeIntegrator&) = delete;
  OdeIntegrator& operator=(const OdeIntegrator&) = delete;

  /// Integrates to t_out > time() (interpolated output, the integrator may step past t_out) and
  /// writes y(t_out) into y. Throws tmlab::Error on any SUNDIALS failure.
  void advance(double t_out, VecX& y);
  double time() const;
  IntegratorStats stats() const;
  OdeMethod method() const;
  /// "CVODE BDF + dense", "ARKStep DIRK + spgmr", ...
  std::string describe() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct DaeOptions {
  double rtol = 1e-8;
  double atol = 1e-12;
  VecX atol_vector;
  long max_steps = 1000000;
  double max_step = 0.0;
  /// Dense (DQ Jacobian, small systems), Spgmr (matrix-free, the system's jacobian_times when it has
  /// one) or SpgmrPreconditioned (the system's preconditioner).
  LinearSolverKind linear = LinearSolverKind::Dense;
  int krylov_dim = 0;  ///< SPGMR restart dimension, 0: SUNDIALS default (5)
  /// Compute consistent y' of the differential and y of the algebraic components from y0 (IDACalcIC,
  /// IDA_YA_YDP_INIT) before the first step.
  bool consistent_initial_conditions = true;
  /// Leave the algebraic components out of the local error test (IDASetSuppressAlg): their y' is not
  /// made consistent by IDACalcIC, and an inconsistent y' of an algebraic component otherwise makes
  /// the first error tests fail.
  bool suppress_algebraic_error = true;
};

class DaeIntegrator {
 public:
  /// IDA with the linear solver of options.linear. The system must outlive the integrator.
  DaeIntegrator(DaeSystem& system, const DaeOptions& options, double t0, const VecX& y0, const VecX& yp0);
  ~DaeIntegrator();
  DaeIntegrator(DaeIntegrator&&) noexcept;
  DaeIntegrator& operator=(DaeIntegrator&&) noexcept;
  DaeIntegrator(const DaeIntegrator&) = delete;
  DaeIntegrator& operator=(const DaeIntegrator&) = delete;

  void advance(double t_out, VecX& y, VecX& yp);
  double time() const;
  IntegratorStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// "6.4.1" (the SUNDIALS library the adapter was built against).
std::string sundials_version();

}  // namespace tmlab::tm
