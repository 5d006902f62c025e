// The quasi-static viscoelastic problem as a DAE integrated by IDA (deal.II 9.4 SUNDIALS::IDA).
// Equations: ida_dae.hpp and docs/reference-fem.md ("Time integration by IDA").
//
// deal.II 9.4's IDA wrapper lets a C++ exception from a callback unwind through SUNDIALS' C frames
// and checks IDA's return flags with Assert (a no-op in Release builds). So every callback here is
// wrapped: an exception is kept and the callback returns -1 (unrecoverable); the output callback,
// which deal.II calls from C++ after each IDASolve, rethrows it, and also detects a failed IDASolve
// by the time it stopped at (IDASolve returns at the last successful time instead of the output time).
#include "reference_fem/dealii/ida_dae.hpp"

#include "core/base/error.hpp"
#include "core/base/stopwatch.hpp"

#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/sundials/ida.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace tmlab::ref {

using namespace dealii;
using Clock = std::chrono::steady_clock;

namespace {

// Voigt order of the internal variables: xx, yy, zz, xy, xz, yz.
constexpr unsigned kVoigt[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};

SymTensor2 from_voigt(const Vector<double>& v, std::size_t offset) {
  SymTensor2 s;
  for (unsigned a = 0; a < 6; ++a) s[kVoigt[a][0]][kVoigt[a][1]] = v[offset + a];
  return s;
}

void add_voigt(const SymTensor2& s, double factor, Vector<double>& v, std::size_t offset) {
  for (unsigned a = 0; a < 6; ++a) v[offset + a] += factor * s[kVoigt[a][0]][kVoigt[a][1]];
}

/// Per cell: FEValues, its DoF indices, the component of each shape function and the displacement
/// gradient at each quadrature point from the U part of a state vector.
struct CellKinematics {
  CellKinematics(const Solid& solid)
      : fev(solid.mapping(), solid.fe(), solid.quadrature(), update_gradients | update_JxW_values),
        n(solid.fe().n_dofs_per_cell()),
        dofs(n),
        comp(n),
        grad_u(solid.quadrature().size()) {
    for (unsigned i = 0; i < n; ++i) comp[i] = solid.fe().system_to_component_index(i).first;
  }
  void reinit(const DoFHandler<3>::active_cell_iterator& cell, const Vector<double>& y) {
    fev.reinit(cell);
    cell->get_dof_indices(dofs);
    for (unsigned q = 0; q < grad_u.size(); ++q) {
      grad_u[q] = 0;
      for (unsigned i = 0; i < n; ++i) {
        const Tensor<1, 3> g = fev.shape_grad_component(i, q, comp[i]);
        for (unsigned k = 0; k < 3; ++k) grad_u[q][comp[i]][k] += y[dofs[i]] * g[k];
      }
    }
  }
  /// dE_i = sym(F^T Grad phi_i) = sym((F^T e_c) (x) grad N_i) for shape function i at point q.
  SymTensor2 strain_variation(const Tensor<2, 3>& F, unsigned i, unsigned q) const {
    Tensor<1, 3> Fc;
    for (unsigned k = 0; k < 3; ++k) Fc[k] = F[comp[i]][k];
    return symmetrize(outer_product(Fc, fev.shape_grad_component(i, q, comp[i])));
  }
  FEValues<3> fev;
  unsigned n;
  std::vector<types::global_dof_index> dofs;
  std::vector<unsigned> comp;
  std::vector<Tensor<2, 3>> grad_u;
};

Tensor<2, 3> deformation_gradient(const Tensor<2, 3>& grad_u) {
  return Tensor<2, 3>(unit_symmetric_tensor<3>()) + grad_u;
}

SymTensor2 green_lagrange(const Tensor<2, 3>& F) {
  return 0.5 * (symmetrize(transpose(F) * F) - unit_symmetric_tensor<3>());
}

}  // namespace

// =====================================================================================================
// Setup
// =====================================================================================================

QuasiStaticDae::QuasiStaticDae(Solid& solid)
    : solid_(solid), prony_(solid.prony() ? *solid.prony() : PronySeries()), control_(1, 0.0) {
  if (!solid.prony())
    throw Error(
        "reference: IDA time integration needs a viscoelastic material (Prony terms): an elastic "
        "quasi-static problem has no differential variables; use time_integration = fixed_step");
  const unsigned ranks = Utilities::MPI::n_mpi_processes(solid.communicator());
  if (ranks != 1)
    throw Error("reference: IDA time integration runs on one MPI rank only (started on " +
                std::to_string(ranks) + "); run without mpirun, or with the serial option");
  n_dofs_ = static_cast<unsigned>(solid.n_dofs());
  n_q_ = solid.quadrature().size();
  n_terms_ = static_cast<unsigned>(prony_.size());
  n_cells_ = solid.triangulation().n_active_cells();
  n_z_ = static_cast<std::size_t>(n_cells_) * n_q_ * n_terms_ * 6;
  for (double a : prony_.alpha) alpha_sum_ += a;

  // The Newton matrix couples the displacement DoFs of a cell (the Z block is eliminated); the
  // constrained couplings are kept: prescribed rows are replaced by d I rows, their columns stay
  // (so a solve carries K_fc dU_c to the free rows).
  solid.finalize_setup();
  DynamicSparsityPattern dsp(n_dofs_);
  DoFTools::make_sparsity_pattern(solid.dof_handler(), dsp);
  for (NewtonMatrix* m : {&ida_matrix_, &projection_matrix_}) {
    m->K.reinit(solid.locally_owned_dofs(), solid.locally_owned_dofs(), dsp, solid.communicator());
    m->qp.resize(static_cast<std::size_t>(n_cells_) * n_q_);
    m->kappa.assign(n_terms_, 1.0);
  }
  f_ext_.reinit(solid.locally_owned_dofs(), solid.communicator());
  rhs_.reinit(solid.locally_owned_dofs(), solid.communicator());
  du_.reinit(solid.locally_owned_dofs(), solid.communicator());
}

QuasiStaticDae::~QuasiStaticDae() = default;

Vector<double> QuasiStaticDae::initial_state() const {
  Vector<double> y(size());
  const auto& u = solid_.solution();
  for (unsigned i = 0; i < n_dofs_; ++i) y[i] = u[i];
  CellKinematics ck(solid_);
  for (const auto& cell : solid_.dof_handler().active_cell_iterators()) {
    ck.reinit(cell, y);
    const unsigned c = cell->active_cell_index();
    for (unsigned q = 0; q < n_q_; ++q) {
      const SymTensor2 sr =
          prony_.relaxing_stress(solid_.material(), green_lagrange(deformation_gradient(ck.grad_u[q])));
      for (unsigned j = 0; j < n_terms_; ++j) add_voigt(sr, 1.0, y, z_offset(c, q, j));
    }
  }
  return y;
}

// =====================================================================================================
// Residual F(t, y, y')
// =====================================================================================================

int QuasiStaticDae::residual(double t, const Vector<double>& y, const Vector<double>& yp, Vector<double>& r) {
  const auto start = Clock::now();
  ++stats_.residual_evaluations;
  // Step bookkeeping (IdaStats): a new residual time after t0 is a new step attempt.
  if (t != t0_ && (!have_attempt_ || t != last_attempt_t_)) {
    if (have_attempt_ && t > last_attempt_t_) ++stats_.steps;
    ++stats_.step_attempts;
    last_attempt_t_ = t;
    have_attempt_ = true;
  }
  if (r.size() != size())
    r.reinit(size());
  else
    r = 0.0;
  const Material& m = solid_.material();
  CellKinematics ck(solid_);
  Vector<double> cell_r(ck.n);
  for (const auto& cell : solid_.dof_handler().active_cell_iterators()) {
    ck.reinit(cell, y);
    const unsigned c = cell->active_cell_index();
    cell_r = 0.0;
    for (unsigned q = 0; q < n_q_; ++q) {
      const Tensor<2, 3> F = deformation_gradient(ck.grad_u[q]);
      const double J = determinant(F);
      if (!(J > 0.0) || !std::isfinite(J)) {
        ++stats_.recoverable_failures;
        stats_.residual_seconds += seconds_since(start);
        return 1;  // IDA retries with a shorter step
      }
      const SymTensor2 E = green_lagrange(F);
      const SymTensor2 sr = prony_.relaxing_stress(m, E);
      // S_tot = S_e + sum_j alpha_j h_j with h_j = S_r - z_j, and the internal-variable rows.
      SymTensor2 S = m.stress(E) + alpha_sum_ * sr;
      for (unsigned j = 0; j < n_terms_; ++j) {
        const std::size_t o = z_offset(c, q, j);
        const SymTensor2 z = from_voigt(y, o);
        S -= prony_.alpha[j] * z;
        for (unsigned a = 0; a < 6; ++a) r[o + a] = yp[o + a];
        add_voigt(sr - z, -1.0 / prony_.tau[j], r, o);
      }
      const double JxW = ck.fev.JxW(q);
      for (unsigned i = 0; i < ck.n; ++i) cell_r(i) += (S * ck.strain_variation(F, i, q)) * JxW;
    }
    for (unsigned i = 0; i < ck.n; ++i) r[ck.dofs[i]] += cell_r(i);
  }
  solid_.external_force(t, f_ext_);
  for (unsigned i = 0; i < n_dofs_; ++i) r[i] -= f_ext_[i];
  // Prescribed DoFs: algebraic rows U_c - g_c(t).
  for (const auto& [dof, g] : solid_.prescribed_values(t)) r[dof] = y[dof] - g;
  stats_.residual_seconds += seconds_since(start);
  for (std::size_t i = 0; i < r.size(); ++i)
    if (!std::isfinite(r[i])) {
      ++stats_.recoverable_failures;
      return 1;
    }
  return 0;
}

// =====================================================================================================
// Newton matrix: Schur complement on U, factorised by the reference's direct solver
// =====================================================================================================

int QuasiStaticDae::setup_jacobian(double /*t*/, const Vector<double>& y, double alpha) {
  const auto start = Clock::now();
  ++stats_.jacobian_setups;
  assemble_newton_matrix(y, alpha, ida_matrix_);
  have_ida_matrix_ = true;
  stats_.jacobian_seconds += seconds_since(start);
  return 0;
}

void QuasiStaticDae::assemble_newton_matrix(const Vector<double>& y, double alpha, NewtonMatrix& nm) {
  const Material& m = solid_.material();
  // Z rows: (alpha + 1/tau_j) dz_j - (1/tau_j) D_r : dE(dU) = b_zj, so
  // dz_j = kappa_j (tau_j b_zj + D_r : dE(dU)), kappa_j = 1 / (1 + alpha tau_j); substituted into the
  // U rows (dF_i/dz_j = -alpha_j int dE_i dV) this leaves K_tot - sum_j alpha_j kappa_j D_r terms.
  double schur = alpha_sum_;  // d S_tot / d E = D_e + (A - sum_j alpha_j kappa_j) D_r
  for (unsigned j = 0; j < n_terms_; ++j) {
    nm.kappa[j] = 1.0 / (1.0 + alpha * prony_.tau[j]);  // alpha = inf (fixed Z): 0
    schur -= prony_.alpha[j] * nm.kappa[j];
  }
  CellKinematics ck(solid_);
  FullMatrix<double> cell_K(ck.n, ck.n);
  std::vector<SymTensor2> dE(ck.n), DdE(ck.n);
  std::vector<Tensor<1, 3>> gradN(ck.n), SgradN(ck.n);
  nm.K = 0.0;
  for (const auto& cell : solid_.dof_handler().active_cell_iterators()) {
    ck.reinit(cell, y);
    const unsigned c = cell->active_cell_index();
    cell_K = 0.0;
    for (unsigned q = 0; q < n_q_; ++q) {
      const Tensor<2, 3> F = deformation_gradient(ck.grad_u[q]);
      const SymTensor2 E = green_lagrange(F);
      QpJacobian& qj = nm.qp[static_cast<std::size_t>(c) * n_q_ + q];
      qj.F = F;
      qj.D_r = prony_.relaxing_tangent(m, E);
      SymTensor2 S = m.stress(E) + alpha_sum_ * prony_.relaxing_stress(m, E);
      for (unsigned j = 0; j < n_terms_; ++j) S -= prony_.alpha[j] * from_voigt(y, z_offset(c, q, j));
      const SymTensor4 D = m.tangent(E) + schur * qj.D_r;
      const double JxW = ck.fev.JxW(q);
      for (unsigned i = 0; i < ck.n; ++i) {
        gradN[i] = ck.fev.shape_grad_component(i, q, ck.comp[i]);
        dE[i] = ck.strain_variation(F, i, q);
        DdE[i] = D * dE[i];
        SgradN[i] = S * gradN[i];
      }
      // Material and geometric stiffness, as Solid::assemble.
      for (unsigned i = 0; i < ck.n; ++i)
        for (unsigned j = 0; j < ck.n; ++j) {
          double k = DdE[i] * dE[j];
          if (ck.comp[i] == ck.comp[j]) k += SgradN[i] * gradN[j];
          cell_K(i, j) += k * JxW;
        }
    }
    nm.K.add(ck.dofs, cell_K);
  }
  nm.K.compress(VectorOperation::add);
  // Prescribed rows: d * dU_c = d * b_c, with d the mean free diagonal (keeps the pivots balanced).
  const auto prescribed = solid_.prescribed_values(0.0);
  std::vector<types::global_dof_index> rows;
  std::vector<char> is_prescribed(n_dofs_, 0);
  for (const auto& p : prescribed) {
    rows.push_back(p.first);
    is_prescribed[p.first] = 1;
  }
  double diag = 0.0;
  unsigned n_free = 0;
  for (unsigned i = 0; i < n_dofs_; ++i)
    if (!is_prescribed[i]) {
      diag += std::abs(nm.K.diag_element(i));
      ++n_free;
    }
  nm.constrained_diagonal = n_free > 0 && diag > 0.0 ? diag / n_free : 1.0;
  nm.K.clear_rows(rows, nm.constrained_diagonal);
  TrilinosWrappers::SolverDirect::AdditionalData data(
      false, linear_solver_ == LinearSolver::DirectKlu ? "Amesos_Klu" : "Amesos_Mumps");
  nm.direct = std::make_unique<TrilinosWrappers::SolverDirect>(control_, data);
  nm.direct->initialize(nm.K);
}

int QuasiStaticDae::solve_with_jacobian(const Vector<double>& b, Vector<double>& x) {
  const auto start = Clock::now();
  ++stats_.newton_iterations;
  if (!have_ida_matrix_) throw Error("reference: IDA asked for a solve before any Jacobian setup");
  solve_newton(ida_matrix_, b, x);
  stats_.solve_seconds += seconds_since(start);
  return 0;
}

void QuasiStaticDae::solve_newton(const NewtonMatrix& nm, const Vector<double>& b, Vector<double>& x) {
  // Right-hand side of the Schur system: b_U + sum_j alpha_j kappa_j tau_j int dE_i : b_zj dV.
  CellKinematics ck(solid_);
  rhs_ = 0.0;
  Vector<double> cell_rhs(ck.n);
  for (const auto& cell : solid_.dof_handler().active_cell_iterators()) {
    ck.fev.reinit(cell);
    cell->get_dof_indices(ck.dofs);
    const unsigned c = cell->active_cell_index();
    cell_rhs = 0.0;
    for (unsigned q = 0; q < n_q_; ++q) {
      const QpJacobian& qj = nm.qp[static_cast<std::size_t>(c) * n_q_ + q];
      SymTensor2 w;
      for (unsigned j = 0; j < n_terms_; ++j)
        w += (prony_.alpha[j] * nm.kappa[j] * prony_.tau[j]) * from_voigt(b, z_offset(c, q, j));
      const double JxW = ck.fev.JxW(q);
      for (unsigned i = 0; i < ck.n; ++i) cell_rhs(i) += (w * ck.strain_variation(qj.F, i, q)) * JxW;
    }
    rhs_.add(ck.dofs, cell_rhs);
  }
  rhs_.compress(VectorOperation::add);
  Vector<double> rhs(n_dofs_);
  for (unsigned i = 0; i < n_dofs_; ++i) rhs[i] = rhs_[i] + b[i];
  for (const auto& p : solid_.prescribed_values(0.0)) rhs[p.first] = nm.constrained_diagonal * b[p.first];
  for (unsigned i = 0; i < n_dofs_; ++i) rhs_[i] = rhs[i];
  rhs_.compress(VectorOperation::insert);
  nm.direct->solve(du_, rhs_);
  if (x.size() != size()) x.reinit(size());
  for (unsigned i = 0; i < n_dofs_; ++i) x[i] = du_[i];
  for (std::size_t i = n_dofs_; i < size(); ++i) x[i] = 0.0;
  // Back-substitution: dz_j = kappa_j (tau_j b_zj + D_r : sym(F^T Grad dU)).
  for (const auto& cell : solid_.dof_handler().active_cell_iterators()) {
    ck.reinit(cell, x);
    const unsigned c = cell->active_cell_index();
    for (unsigned q = 0; q < n_q_; ++q) {
      const QpJacobian& qj = nm.qp[static_cast<std::size_t>(c) * n_q_ + q];
      const SymTensor2 dE = symmetrize(transpose(qj.F) * ck.grad_u[q]);
      const SymTensor2 DdE = qj.D_r * dE;
      for (unsigned j = 0; j < n_terms_; ++j) {
        const std::size_t o = z_offset(c, q, j);
        const SymTensor2 dz = nm.kappa[j] * (prony_.tau[j] * from_voigt(b, o) + DdE);
        add_voigt(dz, 1.0, x, o);
      }
    }
  }
}

void QuasiStaticDae::project_to_equilibrium(double t, Vector<double>& y) {
  const auto start = Clock::now();
  // Modified Newton with the fixed-Z tangent (alpha = inf: kappa_j = 0, dS_tot/dE = D_e + A D_r)
  // of the interpolated state; the Z part of every correction is zero.
  assemble_newton_matrix(y, std::numeric_limits<double>::infinity(), projection_matrix_);
  Vector<double> r(size()), dy(size()), yp(size());
  const long evaluations = stats_.residual_evaluations, attempts = stats_.step_attempts, steps = stats_.steps;
  const double last = last_attempt_t_;
  const bool had = have_attempt_;
  bool converged = false;
  for (int it = 0; it < 20 && !converged; ++it) {
    if (residual(t, y, yp, r) != 0)
      throw Error("reference: IDA output state at t = " + std::to_string(t) + " has det F <= 0");
    for (std::size_t i = n_dofs_; i < size(); ++i) r[i] = 0.0;  // Z is kept
    r *= -1.0;
    solve_newton(projection_matrix_, r, dy);
    double worst = 0.0;
    for (unsigned i = 0; i < n_dofs_; ++i) {
      y[i] += dy[i];
      worst =
          std::max(worst, std::abs(dy[i]) / (projection_tolerance_u_ + projection_rtol_ * std::abs(y[i])));
    }
    ++stats_.projection_iterations;
    converged = worst <= 1e-3;
  }
  // The projection's residuals are not IDA's: restore the bookkeeping.
  stats_.residual_evaluations = evaluations;
  stats_.step_attempts = attempts;
  stats_.steps = steps;
  last_attempt_t_ = last;
  have_attempt_ = had;
  if (!converged)
    throw Error("reference: the equilibrium projection of IDA's output at t = " + std::to_string(t) +
                " did not converge in 20 iterations");
  stats_.projection_seconds += seconds_since(start);
}

// =====================================================================================================
// Output state and the IDA driver
// =====================================================================================================

void QuasiStaticDae::apply_state(const Vector<double>& y) {
  TrilinosWrappers::MPI::Vector u(solid_.locally_owned_dofs(), solid_.communicator());
  for (unsigned i = 0; i < n_dofs_; ++i) u[i] = y[i];
  u.compress(VectorOperation::insert);
  solid_.set_solution(u);
  CellKinematics ck(solid_);
  const Material& m = solid_.material();
  // The solid's quadrature-point data are keyed by triangulation cells; its DoFHandler cell of the
  // same active index gives the displacement gradient.
  std::vector<std::vector<SymTensor2>> sr(n_cells_, std::vector<SymTensor2>(n_q_));
  for (const auto& cell : solid_.dof_handler().active_cell_iterators()) {
    ck.reinit(cell, y);
    for (unsigned q = 0; q < n_q_; ++q)
      sr[cell->active_cell_index()][q] =
          prony_.relaxing_stress(m, green_lagrange(deformation_gradient(ck.grad_u[q])));
  }
  solid_.set_history([&](const Triangulation<3>::active_cell_iterator& cell, unsigned q, PronyState& st) {
    const unsigned c = cell->active_cell_index();
    st.resize(n_terms_);
    st.s_r = st.s_r_trial = sr[c][q];
    for (unsigned j = 0; j < n_terms_; ++j)
      st.h[j] = st.h_trial[j] = sr[c][q] - from_voigt(y, z_offset(c, q, j));
  });
}

template <class Body>
int QuasiStaticDae::guarded(Body&& body) {
  try {
    return body();
  } catch (...) {
    if (!pending_) pending_ = std::current_exception();
    return -1;
  }
}

IdaStats QuasiStaticDae::integrate(double t0, double t_end, int n_outputs, const IdaParameters& p,
                                   const std::function<void(int, double, const Vector<double>&)>& output) {
  if (!(t_end > t0) || n_outputs < 1)
    throw Error("reference: IDA needs t_end > t0 and at least one output step");
  if (!(p.rtol > 0.0) || !(p.atol_u > 0.0) || !(p.atol_z > 0.0))
    throw Error("reference: IDA tolerances must be > 0 (rtol " + std::to_string(p.rtol) + ", atol " +
                std::to_string(p.atol_u) + " m, " + std::to_string(p.atol_z) + " Pa)");
  if (p.linear_solver == LinearSolver::CgAmg)
    throw Error(
        "reference: IDA time integration uses a direct solver: linear_solver must be 'direct' or "
        "'direct_klu' (got '" +
        to_string(p.linear_solver) + "')");
  linear_solver_ = p.linear_solver;
  projection_tolerance_u_ = p.atol_u;
  projection_rtol_ = p.rtol;
  stats_ = IdaStats();
  have_attempt_ = false;
  pending_ = nullptr;
  t0_ = t0;
  const double dt_out = (t_end - t0) / n_outputs;

  using Ida = SUNDIALS::IDA<Vector<double>>;
  Ida::AdditionalData data(t0, t_end, p.initial_step > 0.0 ? p.initial_step : dt_out / 100.0, dt_out,
                           /*minimum_step_size (unused by 9.4)*/ 0.0, p.max_order, p.max_newton,
                           /*ls_norm_factor: SUNDIALS default*/ 0.0, p.atol_u, p.rtol,
                           /*ignore_algebraic_terms_for_errors*/ true, Ida::AdditionalData::use_y_diff,
                           Ida::AdditionalData::use_y_diff, /*maximum_non_linear_iterations_ic*/ 10);
  Ida ida(data, solid_.communicator());
  Vector<double> atol(size());
  for (std::size_t i = 0; i < size(); ++i) atol[i] = i < n_dofs_ ? p.atol_u : p.atol_z;
  ida.reinit_vector = [this](Vector<double>& v) { v.reinit(size()); };
  ida.residual = [this](double t, const Vector<double>& y, const Vector<double>& yp, Vector<double>& r) {
    return guarded([&] { return residual(t, y, yp, r); });
  };
  ida.setup_jacobian = [this](double t, const Vector<double>& y, const Vector<double>&, double alpha) {
    return guarded([&] { return setup_jacobian(t, y, alpha); });
  };
  ida.solve_with_jacobian = [this](const Vector<double>& b, Vector<double>& x, double) {
    return guarded([&] { return solve_with_jacobian(b, x); });
  };
  ida.differential_components = [this]() {
    IndexSet s(size());
    s.add_range(n_dofs_, size());
    return s;
  };
  ida.get_local_tolerances = [&atol]() -> Vector<double>& { return atol; };
  int last_k = -1;
  ida.output_step = [&](double t, const Vector<double>& y, const Vector<double>& yp, unsigned step) {
    if (pending_) {
      auto e = pending_;
      pending_ = nullptr;
      std::rethrow_exception(e);
    }
    if (step == 0) {
      // IDACalcIC's result (its flag is not checked by deal.II 9.4 in Release): equilibrium at t0.
      Vector<double> r;
      const int flag = residual(t0, y, yp, r);
      --stats_.residual_evaluations;  // a check, not IDA's
      if (flag != 0) throw Error("reference: IDA initial state is not admissible (det F <= 0)");
      solid_.external_force(t0, f_ext_);
      double rn = 0.0, fn = 0.0;
      for (unsigned i = 0; i < n_dofs_; ++i) rn += r[i] * r[i], fn += f_ext_[i] * f_ext_[i];
      if (std::sqrt(rn) > 1e-6 * std::sqrt(fn) + 1e-300)
        throw Error("reference: IDA could not compute consistent initial values at t = " +
                    std::to_string(t0) + " (|F_U| = " + std::to_string(std::sqrt(rn)) + " N)");
      last_k = 0;
      output(0, t0, y);
      return;
    }
    const double kf = (t - t0) / dt_out;
    const long k = std::lround(kf);
    if (std::abs(kf - static_cast<double>(k)) > 1e-6 || k < 1 || k > n_outputs) {
      std::ostringstream msg;
      msg << "reference: IDA failed: it stopped at t = " << t << " before the output time "
          << t0 + (last_k + 1) * dt_out
          << " (error test or Newton failures at the minimum step; try a looser ida_rtol, or check the "
             "loads)";
      throw Error(msg.str());
    }
    if (k == last_k) return;  // the final time again (deal.II's output clock accumulates round-off)
    last_k = static_cast<int>(k);
    const double tk = t0 + (t_end - t0) * static_cast<double>(k) / n_outputs;  // the fixed-step times
    Vector<double> yk(y);
    project_to_equilibrium(tk, yk);
    output(last_k, tk, yk);
  };
  Vector<double> y = initial_state(), yp(size());
  ida.solve_dae(y, yp);
  if (pending_) {
    auto e = pending_;
    pending_ = nullptr;
    std::rethrow_exception(e);
  }
  if (last_k != n_outputs)
    throw Error("reference: IDA stopped after output " + std::to_string(last_k) + " of " +
                std::to_string(n_outputs));
  if (have_attempt_) ++stats_.steps;  // the last attempt was accepted: the run reached t_end
  return stats_;
}

}  // namespace tmlab::ref
