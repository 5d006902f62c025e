// Error-controlled reference problems of the viscoelastic tensor-mass model (issue 5), integrated by
// the SUNDIALS adapter (sundials_adapter.hpp). Theory and measured results:
// docs/theory/sundials-references.md.
//
// Internal-variable form of the Prony history. For one term (alpha_j, tau_j) the hereditary part
// h_j(t) = int_0^t exp(-(t-s)/tau_j) dX_e/ds ds solves h_j' = -h_j/tau_j + X_e'. With the
// "viscous" variable z_j = X_e - h_j (z_j = C : E_vj for pk2: the stress of the long-term spring at
// the viscous strain of branch j)
//
//   z_j' = (X_e(u) - z_j) / tau_j,          X_total = X_e + sum_j alpha_j h_j = (1 + A) X_e - sum_j alpha_j
//   z_j,
//
// A = sum_j alpha_j. This needs no time derivative of u (so prescribed displacements enter only
// through u(t)), and is the time-continuous limit of ViscoelasticStVK's recursions.
#pragma once

#include "reference_fem/sundials/sundials_adapter.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/system/mechanical_system.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace tmlab::tm {

/// The factorised Newton matrix of the tensor-mass ODE / DAE (src/ode_preconditioner.cpp).
struct TensorMassNewtonMatrix;
struct TensorMassNewtonMatrixDeleter {
  void operator()(TensorMassNewtonMatrix* p) const;
};

// ------------------------------------------------------------------ single-DOF verification problems

/// Mass on a standard linear solid (one Prony term), free vibration:
///   m x'' + k x + alpha h = 0,   h' = -h/tau + k x'      (X_e = k x, h in newtons)
/// y = (x, v, h), y' = A y with A = [[0, 1, 0], [-k/m, 0, -alpha/m], [0, k, -1/tau]].
/// Closed form: y(t) = V exp(Lambda t) V^{-1} y0 from the eigen-decomposition of A; the eigenvalues
/// are the roots of  s^3 + s^2/tau + s k (1 + alpha)/m + k/(m tau) = 0  (one real, decaying root and
/// a damped complex pair for the parameters used in the tests).
class SlsOscillator : public OdeSystem {
 public:
  SlsOscillator(double mass, double stiffness, double alpha, double tau, double x0, double v0);
  Index size() const override { return 3; }
  void rhs(double t, const VecX& y, VecX& ydot) override;
  bool has_jacobian_times() const override { return true; }
  void jacobian_times(double t, const VecX& y, const VecX& v, VecX& Jv) override;
  VecX initial_state() const;
  /// ImEx split: f_I = (0, 0, -h/tau) (the branch relaxation, stiff for small tau), f_E = the rest.
  bool has_split() const override { return true; }
  void rhs_explicit(double t, const VecX& y, VecX& ydot) override;
  void rhs_implicit(double t, const VecX& y, VecX& ydot) override;
  void jacobian_times_implicit(double t, const VecX& y, const VecX& v, VecX& Jv) override;
  /// Multirate split (MRIStep): slow f_S = (0, 0, k v - h/tau) (the branch), fast f_F = (v, -(k x + alpha
  /// h)/m, 0).
  bool has_multirate() const override { return true; }
  void rhs_slow(double t, const VecX& y, VecX& ydot) override;
  void rhs_fast(double t, const VecX& y, VecX& ydot) override;
  /// Closed-form (x, v, h) at time t >= 0.
  Eigen::Vector3d exact(double t) const;
  const Eigen::Matrix3d& matrix() const { return A_; }

 private:
  Eigen::Matrix3d A_;
  Eigen::Vector3d y0_;
  Eigen::Matrix3cd V_, Vinv_;
  Eigen::Vector3cd lambda_;
};

/// Quasi-static creep of a 3-parameter solid (spring k in parallel with a Maxwell branch alpha k,
/// relaxation time tau) under a force F(t) = F0 sin(omega t):
///   k x + alpha h = F(t),  h' = -h/tau + k x'.
/// With phi = F/k and H = h/k: (1 + alpha) H' = -H/tau + phi', so with tau_c = tau (1 + alpha)
///   H(t) = 1/(1+alpha) int_0^t exp(-(t-s)/tau_c) phi'(s) ds
///        = phi0 omega / (1+alpha) [cos(omega t)/tau_c + omega sin(omega t) - exp(-t/tau_c)/tau_c]
///                                 / (1/tau_c^2 + omega^2),
///   x(t) = phi(t) - alpha H(t).
/// DAE form (residual(), IDA): y = (x, z), z = x - H (viscous displacement):
///   0 = (1 + alpha) x - alpha z - phi(t)    (algebraic: equilibrium)
///   0 = z' - (x - z)/tau                    (differential: internal variable)
class SlsCreep : public DaeSystem {
 public:
  SlsCreep(double stiffness, double alpha, double tau, double force_amplitude, double omega);
  Index size() const override { return 2; }
  void residual(double t, const VecX& y, const VecX& yp, VecX& r) override;
  VecX differential() const override;
  double phi(double t) const;      ///< F(t)/k
  double exact_x(double t) const;  ///< closed form displacement
  double exact_H(double t) const;  ///< closed form history h/k
  /// The fixed-step recursion of ViscoelasticStVK on this problem: per step
  ///   H^{n+1} = a H^n + c (x^{n+1} - x^n),  x^{n+1} + alpha H^{n+1} = phi(t_{n+1})
  /// ((a, c) = recursion_factors(scheme, dt, tau)); returns x^n for n = 1..steps (t_n = n dt).
  std::vector<double> recursion(ViscoelasticOptions::Integration scheme, double dt, int steps) const;
  double alpha() const { return alpha_; }
  double tau() const { return tau_; }

 private:
  double k_, alpha_, tau_, f0_, omega_;
};

// ------------------------------------------------------------------ tensor-mass semi-discrete ODE

/// The semi-discrete viscoelastic tensor-mass dynamics as a first-order ODE
///   u' = v,   M v' = f_ext(u, t) - f_int(u, z) - C v,   z_j' = (X_e(u) - z_j) / tau_j   (per tet, per term)
/// y = [u (3N), v (3N), z (T x J x w)], w = 6 (pk2, Voigt xx,yy,zz,xy,xz,yz) or 12 (nodal_force).
/// f_int per tet: pk2  f_p = V F S_tot a_p,  S_tot = (1 + A) S_e - sum alpha_j z_j
///                      (deviatoric: S_tot = S_e + A S_dev - sum alpha_j z_j, X_e = S_dev)
///                nodal_force  f = (1 + A) f_e - sum alpha_j z_j  (f_e: TensorMassStVK::tet_force, global
///                axes)
/// Constrained DOFs: u is replaced by the prescribed g(t) before every evaluation and u', v' are 0
/// there (their state entries are unused). M, the constraints, loads and Rayleigh damping come from
/// `system` (C v = alpha M v + beta K_0 v with K_0 the system model's reference tangent; the tests
/// use no damping). The model itself is evaluated here from the long-term material (the system's model
/// is not called except by damping_force).
/// Jacobian action (SPGMR): exact for dead loads (follower-pressure load stiffness is left out,
/// which only slows the Newton iteration). The `integration` field of the options is ignored.
///
/// Preconditioner (LinearSolverKind::SpgmrPreconditioned, src/ode_preconditioner.cpp): the Newton
/// matrix I - gamma J reduced to the displacement block by eliminating v (u' = v) and z (z_j' is
/// diagonal in z_j):
///   (M + gamma C + gamma^2 K_eff) du = gamma M r_v + (M + gamma C) r_u + gamma^2 sum_j q_j alpha_j G r_zj,
///   dv = (du - r_u)/gamma,   dz_j = q_j (r_zj + (gamma/tau_j) D du),   q_j = 1/(1 + gamma/tau_j),
/// with G the map z_j -> f_int (V F Z a_p, or the nodal forces themselves), D = dX_e/du and
///   K_eff = K_u - sum_j alpha_j w_j G D,   w_j = gamma/(tau_j + gamma)
/// (K_u = df_int/du at fixed z: geometric stiffness of S_tot plus the material stiffness scaled by
/// 1 + A, or 1 + A on the deviatoric part). K_eff is assembled on the mesh graph (TangentPattern)
/// and factorised by sparse LDL^T (Eigen SimplicialLDLT); constrained DOFs are identity rows
/// (du_c = r_u_c, dv_c = r_v_c). For dead loads this is the exact inverse of I - gamma J, so GMRES
/// converges in one iteration (a sparse direct solver through the Krylov interface); with jacobian_ok
/// only gamma changes and the stored geometric and material parts are recombined and refactorised.
class TensorMassViscoelasticOde : public OdeSystem {
 public:
  TensorMassViscoelasticOde(const Mesh& mesh, const StVenantKirchhoff& long_term, PronySeries prony,
                            ViscoelasticOptions options, const MechanicalSystem& system);
  TensorMassViscoelasticOde(const TensorMassViscoelasticOde&) = delete;
  TensorMassViscoelasticOde& operator=(const TensorMassViscoelasticOde&) = delete;
  TensorMassViscoelasticOde& operator=(TensorMassViscoelasticOde&&) = delete;

  Index size() const override { return 2 * ndof_ + nz_; }
  void rhs(double t, const VecX& y, VecX& ydot) override;
  bool has_jacobian_times() const override { return true; }
  void jacobian_times(double t, const VecX& y, const VecX& v, VecX& Jv) override;
  /// ImEx split (ARKStep): f_E = the mechanics (u' = v, v' = M^{-1}(f_ext - f_int - C v), 0 on z),
  /// f_I = the branch relaxation (0 on u, v; z_j' = (X_e(u) - z_j)/tau_j), stiff for small tau_j.
  /// The explicit part keeps the elastic wave speed limit of explicit dynamics on the step.
  bool has_split() const override { return true; }
  void rhs_explicit(double t, const VecX& y, VecX& ydot) override;
  void rhs_implicit(double t, const VecX& y, VecX& ydot) override;
  void jacobian_times_implicit(double t, const VecX& y, const VecX& v, VecX& Jv) override;
  /// Multirate split (MRIStep), a model of the seed's haptic / simulation split: fast f_F = the
  /// mechanics (= f_E above), slow f_S = the branch relaxation (= f_I above), explicit at the slow step.
  bool has_multirate() const override { return true; }
  void rhs_slow(double t, const VecX& y, VecX& ydot) override { rhs_implicit(t, y, ydot); }
  void rhs_fast(double t, const VecX& y, VecX& ydot) override { rhs_explicit(t, y, ydot); }
  /// The sparse Newton-matrix preconditioner (see the class comment). Setup returns false when the
  /// factorisation fails (CVODE / ARKStep then retry with a smaller step).
  bool has_preconditioner() const override { return true; }
  bool preconditioner_setup(double t, const VecX& y, double gamma, bool jacobian_ok,
                            bool& jacobian_updated) override;
  bool preconditioner_solve(double t, const VecX& y, const VecX& r, VecX& z, double gamma) override;

  /// y0 with u0 (constrained entries set from g(t0)), v0 and z = X_e(u0) (h = 0: no history,
  /// as ViscoelasticStVK after initialize()).
  VecX initial_state(double t0, const VecX& u0, const VecX& v0) const;
  /// Per-component absolute tolerances: u_scale (m) for u, v_scale (m/s) for v, x_scale (Pa for pk2,
  /// N for nodal_force) for z.
  VecX absolute_tolerances(double u_scale, double v_scale, double x_scale) const;

  Index num_dofs() const { return ndof_; }
  Index num_history() const { return nz_; }
  int width() const { return width_; }
  /// u(t) from the state (constrained entries prescribed).
  VecX displacement(double t, const VecX& y) const;
  VecX velocity(const VecX& y) const { return y.segment(ndof_, ndof_); }
  /// X_total per tet (T x w): (1 + A) X_e - sum alpha_j z_j (deviatoric: S_e + A S_dev - sum alpha z).
  VecX total_driver(double t, const VecX& y) const;
  /// The hereditary part per tet (T x w): sum_j alpha_j h_j = sum_j alpha_j (X_e(u) - z_j)
  /// (ViscoelasticStVK's committed sum_j alpha_j h_j^c in the time-continuous limit).
  VecX history_sum(double t, const VecX& y) const;
  /// X_e per tet (T x w) at displacement u (the driver of the history: S_e, S_dev or f_e).
  VecX elastic_driver(const VecX& u) const;
  /// Assembled f_int(u, z) at time t.
  void internal_force(double t, const VecX& y, VecX& f) const;
  /// Assembled f_int at displacement u (used as is) and histories z (num_history() values).
  void internal_force_at(const VecX& u, const double* z, VecX& f) const { force(u, z, f); }
  const PronySeries& prony() const { return prony_; }
  /// Linearisation at displacement u (used as is) and histories z in the direction (du, dz):
  /// df = d f_int (assembled, num_dofs()) and dx = d X_e per tet (T x w).
  void linearise(const VecX& u, const double* z, const VecX& du, const double* dz, VecX& df, VecX& dx) const;

  // ---- Newton-matrix building blocks shared with TensorMassQuasiStaticDae (src/ode_preconditioner.cpp) ----
  /// Assembles the u-dependent parts of K_eff at (u, z) into nm (geometric, lambda- and mu-material parts).
  void assemble_newton_parts(const VecX& u, const double* z, TensorMassNewtonMatrix& nm) const;
  /// K_eff = K_u - sum_j alpha_j w_j G D of the parts, for the weights w_j (one per Prony term).
  void combine_newton_parts(const std::vector<double>& w, TensorMassNewtonMatrix& nm, SpMat& K) const;
  /// out = sum_j q_j alpha_j G r_zj (assembled; r_z: num_history() values).
  void apply_history_map(const TensorMassNewtonMatrix& nm, const double* rz, const std::vector<double>& q,
                         VecX& out) const;
  /// dx = D du per tet (T x w) at the setup point of nm.
  void apply_driver_derivative(const TensorMassNewtonMatrix& nm, const VecX& du, VecX& dx) const;

 private:
  bool pk2() const { return options_.history == ViscoelasticOptions::History::Pk2; }
  bool deviatoric() const { return options_.relaxation == ViscoelasticOptions::Relaxation::Deviatoric; }
  /// Per-tet driver X_e (width_ values) at u.
  void tet_driver(Index t, const VecX& u, double* x) const;
  /// f_int at u with histories z (full vectors).
  void force(const VecX& u, const double* z, VecX& f) const;

  TotalLagrangianStVK tl_;
  TensorMassStVK tm_;
  StVenantKirchhoff mat_;
  PronySeries prony_;
  ViscoelasticOptions options_;
  const MechanicalSystem& system_;
  Index ndof_ = 0, nz_ = 0, ntets_ = 0;
  int width_ = 6;
  double alpha_sum_ = 0.0;
  mutable VecX u_, f_, fext_, cv_, du_;  // scratch
  std::unique_ptr<TensorMassNewtonMatrix, TensorMassNewtonMatrixDeleter>
      newton_;  ///< preconditioner state (created on first setup)
};

/// The quasi-static viscoelastic tensor-mass problem as a semi-explicit index-1 DAE (IDA):
///   y = [u (3N), z (T x J x w)],
///   0 = f_int(u, z) - f_ext(u, t)        free DOFs       (algebraic: equilibrium)
///   0 = u_c - g_c(t)                     constrained DOFs (algebraic: prescribed displacement)
///   0 = z_j' - (X_e(u) - z_j) / tau_j                      (differential: internal variables)
/// with f_int, X_e and z as in TensorMassViscoelasticOde (whose force evaluation it reuses). The
/// time-continuous limit of StaticSolver + ViscoelasticStVK (t is real time).
///
/// Iterative linear solver (DaeOptions::linear = Spgmr / SpgmrPreconditioned): exact Jacobian action
/// (dF/dy + c_j dF/dy') v for dead loads, and the preconditioner (src/ode_preconditioner.cpp): z
/// eliminated (dz_j = q_j (r_zj + D du / tau_j), q_j = 1/(c_j + 1/tau_j)), leaving
///   K_eff du = r_u + sum_j q_j alpha_j G r_zj,   K_eff = K_u - sum_j alpha_j w_j G D,  w_j = 1/(1 + c_j
///   tau_j)
/// on the free DOFs (du_c = r_u_c, the coupling K_eff_fc du_c moved to the right-hand side), factorised
/// by sparse LDL^T: the exact inverse of the IDA Newton matrix for dead loads.
class TensorMassQuasiStaticDae : public DaeSystem {
 public:
  TensorMassQuasiStaticDae(const Mesh& mesh, const StVenantKirchhoff& long_term, PronySeries prony,
                           ViscoelasticOptions options, const MechanicalSystem& system);
  TensorMassQuasiStaticDae(const TensorMassQuasiStaticDae&) = delete;
  TensorMassQuasiStaticDae& operator=(const TensorMassQuasiStaticDae&) = delete;
  Index size() const override { return ode_.num_dofs() + ode_.num_history(); }
  void residual(double t, const VecX& y, const VecX& yp, VecX& r) override;
  VecX differential() const override;
  bool has_jacobian_times() const override { return true; }
  void jacobian_times(double t, const VecX& y, const VecX& yp, const VecX& v, double cj, VecX& Jv) override;
  bool has_preconditioner() const override { return true; }
  bool preconditioner_setup(double t, const VecX& y, const VecX& yp, double cj) override;
  bool preconditioner_solve(double t, const VecX& y, const VecX& yp, const VecX& r, VecX& z,
                            double cj) override;
  /// y0 = [u0 (constrained entries from g(t0)), z = X_e(u0)] (no history); u0 must be in equilibrium.
  VecX initial_state(double t0, const VecX& u0) const;
  /// Absolute tolerances: u_scale (m) on u, x_scale on z.
  VecX absolute_tolerances(double u_scale, double x_scale) const;
  Index num_dofs() const { return ode_.num_dofs(); }

 private:
  TensorMassViscoelasticOde ode_;
  const MechanicalSystem& system_;
  VecX u_, f_, fext_, g_;
  std::unique_ptr<TensorMassNewtonMatrix, TensorMassNewtonMatrixDeleter>
      newton_;  ///< preconditioner state (created on first setup)
};

}  // namespace tmlab::tm
