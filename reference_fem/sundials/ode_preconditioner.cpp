// The sparse Newton-matrix preconditioners of the tensor-mass ODE (CVODE / ARKStep: I - gamma J) and
// quasi-static DAE (IDA: dF/dy + c_j dF/dy'), see ode_references.hpp. Both eliminate the Prony
// variables z (their Jacobian block is diagonal) and, for the ODE, the velocities (u' = v), leaving
// one symmetric sparse system on the displacements, assembled on the mesh graph and factorised by
// Eigen's SimplicialLDLT. For dead loads the result is the exact inverse of the Newton matrix.
#include "reference_fem/sundials/ode_references.hpp"

#include "tensormass/kernels/tangent_pattern.hpp"

#include <Eigen/SparseCholesky>

#include <cmath>

namespace tmlab::tm {

/// Per-setup state: the u-dependent parts of K_eff on the mesh-graph pattern, F (pk2) or the tet
/// stiffness (nodal_force) at the setup point, and the factorisation.
struct TensorMassNewtonMatrix {
  TangentPattern pattern;
  SpMat Kg, Kl, Km;                       ///< geometric (S_tot), lambda-material, mu-material parts (pk2);
                                          ///< nodal_force: Km = K_e(u), the others zero
  std::vector<Mat3> F;                    ///< pk2: F per tet at the setup point
  std::vector<TensorMassStVK::Mat12> Ke;  ///< nodal_force: K_e(u) per tet
  SpMat K;                                ///< K_eff (full, before constraint elimination)
  SpMat A;                                ///< the matrix that is factorised (constraints eliminated)
  Eigen::SimplicialLDLT<SpMat> ldlt;
  bool analysed = false;
  bool have_parts = false;
  double gamma = 0.0;  ///< ODE: gamma of the last factorisation
  VecX work, rhs;
};

void TensorMassNewtonMatrixDeleter::operator()(TensorMassNewtonMatrix* p) const { delete p; }

namespace {

/// 2 mu (E - tr(E)/3 I)
Mat3 deviator_stress(double mu, const Mat3& E) {
  return 2.0 * mu * (E - (E.trace() / 3.0) * Mat3::Identity());
}

/// Factorises nm.A, analysing the (fixed) pattern once. False when the factorisation fails.
bool factorise(TensorMassNewtonMatrix& nm) {
  if (!nm.analysed) {
    nm.ldlt.analyzePattern(nm.A);
    nm.analysed = true;
  }
  nm.ldlt.factorize(nm.A);
  return nm.ldlt.info() == Eigen::Success;
}

/// Rows and columns of constrained DOFs become identity rows (the pattern is kept).
void eliminate_constraints(SpMat& A, const DirichletSet& bc) {
  const auto& mask = bc.mask();
  for (Eigen::Index col = 0; col < A.outerSize(); ++col)
    for (SpMat::InnerIterator it(A, col); it; ++it)
      if (mask[col] || mask[it.row()]) it.valueRef() = it.row() == col ? 1.0 : 0.0;
}

}  // namespace

// ------------------------------------------------------------------ shared building blocks

void TensorMassViscoelasticOde::assemble_newton_parts(const VecX& u, const double* z,
                                                      TensorMassNewtonMatrix& nm) const {
  if (nm.pattern.num_dofs() != ndof_) nm.pattern = TangentPattern(tl_.num_nodes(), tl_.tets());
  for (SpMat* M : {&nm.Kg, &nm.Kl, &nm.Km})
    if (!nm.pattern.matches(*M)) nm.pattern.reset(*M);
  for (SpMat* M : {&nm.Kg, &nm.Kl, &nm.Km}) std::fill(M->valuePtr(), M->valuePtr() + M->nonZeros(), 0.0);
  const std::size_t J = prony_.size();
  const int w = width_;
  if (pk2())
    nm.F.resize(static_cast<std::size_t>(ntets_));
  else
    nm.Ke.resize(static_cast<std::size_t>(ntets_));
  TensorMassStVK::Mat12 Kg, Kl, Km;
  for (Index e = 0; e < ntets_; ++e) {
    const Tet& tet = tl_.tets()[static_cast<std::size_t>(e)];
    if (!pk2()) {
      nm.Ke[static_cast<std::size_t>(e)] = tm_.tet_stiffness(e, u);
      nm.pattern.scatter(e, tet, nm.Ke[static_cast<std::size_t>(e)], nm.Km.valuePtr());
      continue;
    }
    // K_pq = V [ (a_p . S_tot a_q) I  +  lambda' b_p b_q^T  +  mu' (b_q b_p^T + (a_p . a_q) F F^T) ],  b = F
    // a
    const TetRest& r = tl_.rest(e);
    const Mat3 F = tl_.deformation_gradient(e, u);
    nm.F[static_cast<std::size_t>(e)] = F;
    const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
    const Mat3 Se = mat_.pk2_stress(E);
    Mat3 S =
        deviatoric() ? Mat3(Se + alpha_sum_ * deviator_stress(mat_.mu, E)) : Mat3((1.0 + alpha_sum_) * Se);
    const double* zt = z + static_cast<std::size_t>(e) * J * w;
    for (std::size_t j = 0; j < J; ++j) S -= prony_.alpha(j) * from_voigt(zt + j * w);
    const Mat3 FFt = F * F.transpose();
    std::array<Vec3, 4> b;
    for (int p = 0; p < 4; ++p) b[p] = F * r.grad[p];
    for (int p = 0; p < 4; ++p)
      for (int q = 0; q < 4; ++q) {
        const double geo = r.grad[p].dot(S * r.grad[q]);
        const double apaq = r.grad[p].dot(r.grad[q]);
        Kg.block<3, 3>(3 * p, 3 * q) = r.volume * geo * Mat3::Identity();
        Kl.block<3, 3>(3 * p, 3 * q) = r.volume * b[p] * b[q].transpose();
        Km.block<3, 3>(3 * p, 3 * q) = r.volume * (b[q] * b[p].transpose() + apaq * FFt);
      }
    nm.pattern.scatter(e, tet, Kg, nm.Kg.valuePtr());
    nm.pattern.scatter(e, tet, Kl, nm.Kl.valuePtr());
    nm.pattern.scatter(e, tet, Km, nm.Km.valuePtr());
  }
  nm.have_parts = true;
}

void TensorMassViscoelasticOde::combine_newton_parts(const std::vector<double>& w, TensorMassNewtonMatrix& nm,
                                                     SpMat& K) const {
  // K_eff = K_u - sum_j alpha_j w_j G D. G D is the material stiffness of the driver's elasticity, so
  // K_eff = geometric + material with the Lame pair
  //   full:        s (lambda, mu),                      s = 1 + A - sum_j alpha_j w_j
  //   deviatoric:  (lambda, mu) + s' (-2 mu / 3, mu),   s' = A - sum_j alpha_j w_j
  //   nodal_force: s K_e(u)
  double aw = 0.0;
  for (std::size_t j = 0; j < prony_.size(); ++j) aw += prony_.alpha(j) * w[j];
  double cg = 1.0, cl = 0.0, cm = 0.0;
  if (!pk2()) {
    cg = 0.0;
    cm = 1.0 + alpha_sum_ - aw;
  } else if (deviatoric()) {
    const double s = alpha_sum_ - aw;
    cl = mat_.lambda - s * 2.0 * mat_.mu / 3.0;
    cm = mat_.mu + s * mat_.mu;
  } else {
    const double s = 1.0 + alpha_sum_ - aw;
    cl = s * mat_.lambda;
    cm = s * mat_.mu;
  }
  if (!nm.pattern.matches(K)) nm.pattern.reset(K);
  const Eigen::Index nnz = K.nonZeros();
  double* k = K.valuePtr();
  const double *g = nm.Kg.valuePtr(), *l = nm.Kl.valuePtr(), *m = nm.Km.valuePtr();
  for (Eigen::Index i = 0; i < nnz; ++i) k[i] = cg * g[i] + cl * l[i] + cm * m[i];
}

void TensorMassViscoelasticOde::apply_history_map(const TensorMassNewtonMatrix& nm, const double* rz,
                                                  const std::vector<double>& q, VecX& out) const {
  out.setZero(ndof_);
  const std::size_t J = prony_.size();
  const int w = width_;
  for (Index e = 0; e < ntets_; ++e) {
    const Tet& tet = tl_.tets()[static_cast<std::size_t>(e)];
    const double* rt = rz + static_cast<std::size_t>(e) * J * w;
    double sum[12] = {0.0};
    for (std::size_t j = 0; j < J; ++j)
      for (int k = 0; k < w; ++k) sum[k] += q[j] * prony_.alpha(j) * rt[j * w + k];
    if (pk2()) {  // f_p = V F R a_p
      const Mat3 R = from_voigt(sum);
      const Mat34 f = tl_.tet_force_from_stress(e, nm.F[static_cast<std::size_t>(e)], R);
      for (int p = 0; p < 4; ++p) out.segment<3>(3 * tet[p]) += f.col(p);
    } else {
      for (int p = 0; p < 4; ++p)
        for (int c = 0; c < 3; ++c) out[3 * tet[p] + c] += sum[3 * p + c];
    }
  }
}

void TensorMassViscoelasticOde::apply_driver_derivative(const TensorMassNewtonMatrix& nm, const VecX& du,
                                                        VecX& dxv) const {
  const int w = width_;
  dxv.resize(ntets_ * w);
  for (Index e = 0; e < ntets_; ++e) {
    const Tet& tet = tl_.tets()[static_cast<std::size_t>(e)];
    double* dx = dxv.data() + e * w;
    if (pk2()) {
      const TetRest& r = tl_.rest(e);
      const Mat3& F = nm.F[static_cast<std::size_t>(e)];
      Mat3 dF = Mat3::Zero();
      for (int p = 0; p < 4; ++p) dF += du.segment<3>(3 * tet[p]) * r.grad[p].transpose();
      const Mat3 FtdF = F.transpose() * dF;
      const Mat3 dE = 0.5 * (FtdF + FtdF.transpose());
      to_voigt(deviatoric() ? deviator_stress(mat_.mu, dE) : mat_.pk2_stress(dE), dx);
    } else {
      Eigen::Matrix<double, 12, 1> dul;
      for (int p = 0; p < 4; ++p) dul.segment<3>(3 * p) = du.segment<3>(3 * tet[p]);
      const Eigen::Matrix<double, 12, 1> d = nm.Ke[static_cast<std::size_t>(e)] * dul;
      for (int k = 0; k < 12; ++k) dx[k] = d[k];
    }
  }
}

// ------------------------------------------------------------------ ODE: I - gamma J

bool TensorMassViscoelasticOde::preconditioner_setup(double t, const VecX& y, double gamma, bool jacobian_ok,
                                                     bool& jacobian_updated) {
  if (!newton_) newton_.reset(new TensorMassNewtonMatrix());
  TensorMassNewtonMatrix& nm = *newton_;
  jacobian_updated = false;
  if (!jacobian_ok || !nm.have_parts) {
    u_ = y.head(ndof_);
    system_.bc().apply(t, u_);
    assemble_newton_parts(u_, y.data() + 2 * ndof_, nm);
    jacobian_updated = true;
  }
  std::vector<double> w(prony_.size());
  for (std::size_t j = 0; j < w.size(); ++j) w[j] = gamma / (prony_.tau(j) + gamma);
  combine_newton_parts(w, nm, nm.K);
  // A = M + gamma C + gamma^2 K_eff, C = alpha M + beta K_0
  const RayleighDamping& d = system_.damping();
  nm.A = (gamma * gamma) * nm.K;
  for (Index i = 0; i < ndof_; ++i) nm.A.coeffRef(i, i) += (1.0 + gamma * d.alpha) * system_.mass()[i];
  if (d.beta != 0.0) {
    nm.A += (gamma * d.beta) * system_.reference_tangent();
    nm.A.makeCompressed();
    nm.analysed = false;  // the sum may have K_0's pattern: analyse again
  }
  eliminate_constraints(nm.A, system_.bc());
  nm.gamma = gamma;
  return factorise(nm);
}

bool TensorMassViscoelasticOde::preconditioner_solve(double /*t*/, const VecX& /*y*/, const VecX& r, VecX& z,
                                                     double /*gamma*/) {
  if (!newton_ || !newton_->have_parts) return false;
  TensorMassNewtonMatrix& nm = *newton_;
  // The gamma of the factorisation (SUNDIALS calls setup again when gamma has changed much; using the
  // setup gamma throughout keeps P one fixed matrix, the exact inverse of I - gamma_setup J).
  const double gamma = nm.gamma;
  const RayleighDamping& d = system_.damping();
  const bool damped = d.alpha != 0.0 || d.beta != 0.0;
  const std::size_t J = prony_.size();
  std::vector<double> q(J), wz(J);
  for (std::size_t j = 0; j < J; ++j) {
    q[j] = 1.0 / (1.0 + gamma / prony_.tau(j));
    wz[j] = q[j] * gamma / prony_.tau(j);
  }
  const VecX& M = system_.mass();
  // Right-hand side on the free rows:
  //   gamma M r_v + (M + gamma C) r_u0 - gamma^2 C r_vc + gamma^2 sum_j q_j alpha_j G r_zj
  // (r_u0: r_u without its constrained entries; r_vc: only the constrained entries of r_v, whose
  // dv_c = r_vc couples to the free rows through C).
  VecX ru0 = r.head(ndof_);
  system_.bc().zero_constrained(ru0);
  apply_history_map(nm, r.data() + 2 * ndof_, q, nm.rhs);
  nm.rhs *= gamma * gamma;
  nm.rhs += gamma * M.cwiseProduct(r.segment(ndof_, ndof_)) + M.cwiseProduct(ru0);
  if (damped) {
    system_.damping_force(ru0, nm.work);
    nm.rhs += gamma * nm.work;
    VecX rvc = VecX::Zero(ndof_);
    for (Index k : system_.bc().dofs()) rvc[k] = r[ndof_ + k];
    system_.damping_force(rvc, nm.work);
    nm.rhs -= gamma * gamma * nm.work;
  }
  for (Index k : system_.bc().dofs()) nm.rhs[k] = r[k];  // identity rows: du_c = r_u_c
  const VecX du = nm.ldlt.solve(nm.rhs);
  if (!du.allFinite()) return false;
  z.resize(size());
  z.head(ndof_) = du;
  z.segment(ndof_, ndof_) = (du - r.head(ndof_)) / gamma;
  for (Index k : system_.bc().dofs()) z[ndof_ + k] = r[ndof_ + k];
  // dz_j = q_j r_zj + q_j (gamma/tau_j) D du0   (du0: du without constrained entries, which the state does
  // not move)
  VecX du0 = du;
  system_.bc().zero_constrained(du0);
  apply_driver_derivative(nm, du0, nm.work);
  const int w = width_;
  for (Index e = 0; e < ntets_; ++e)
    for (std::size_t j = 0; j < J; ++j)
      for (int k = 0; k < w; ++k) {
        const Index i = 2 * ndof_ + static_cast<Index>((static_cast<std::size_t>(e) * J + j) * w) + k;
        z[i] = q[j] * r[i] + wz[j] * nm.work[e * w + k];
      }
  return true;
}

// ------------------------------------------------------------------ DAE: dF/dy + c_j dF/dy'

bool TensorMassQuasiStaticDae::preconditioner_setup(double /*t*/, const VecX& y, const VecX& /*yp*/,
                                                    double cj) {
  if (!newton_) newton_.reset(new TensorMassNewtonMatrix());
  TensorMassNewtonMatrix& nm = *newton_;
  const Index n = ode_.num_dofs();
  u_ = y.head(n);  // the DAE state holds u_c itself (an algebraic unknown), used as is
  ode_.assemble_newton_parts(u_, y.data() + n, nm);
  const PronySeries& p = ode_.prony();
  std::vector<double> w(p.size());
  for (std::size_t j = 0; j < w.size(); ++j) w[j] = 1.0 / (1.0 + cj * p.tau(j));
  ode_.combine_newton_parts(w, nm, nm.K);
  nm.A = nm.K;
  eliminate_constraints(nm.A, system_.bc());
  nm.gamma = cj;
  return factorise(nm);
}

bool TensorMassQuasiStaticDae::preconditioner_solve(double /*t*/, const VecX& /*y*/, const VecX& /*yp*/,
                                                    const VecX& r, VecX& z, double /*cj*/) {
  if (!newton_ || !newton_->have_parts) return false;
  TensorMassNewtonMatrix& nm = *newton_;
  const double cj = nm.gamma;  // the c_j of the factorisation (see the ODE solve)
  const Index n = ode_.num_dofs();
  const PronySeries& p = ode_.prony();
  const std::size_t J = p.size();
  std::vector<double> q(J);
  for (std::size_t j = 0; j < J; ++j) q[j] = 1.0 / (cj + 1.0 / p.tau(j));
  // du_c = r_u_c; free rows: K_eff_ff du_f = r_u_f + sum_j q_j alpha_j (G r_zj)_f - K_eff_fc du_c
  VecX duc = VecX::Zero(n);
  for (Index k : system_.bc().dofs()) duc[k] = r[k];
  ode_.apply_history_map(nm, r.data() + n, q, nm.rhs);
  nm.rhs += r.head(n);
  if (!system_.bc().dofs().empty()) nm.rhs -= nm.K * duc;
  for (Index k : system_.bc().dofs()) nm.rhs[k] = r[k];
  const VecX du = nm.ldlt.solve(nm.rhs);
  if (!du.allFinite()) return false;
  z.resize(size());
  z.head(n) = du;
  // dz_j = q_j (r_zj + D du / tau_j), du including the constrained entries
  ode_.apply_driver_derivative(nm, du, nm.work);
  const int w = ode_.width();
  const Index T = nm.work.size() / w;
  for (Index e = 0; e < T; ++e)
    for (std::size_t j = 0; j < J; ++j)
      for (int k = 0; k < w; ++k) {
        const Index i = n + static_cast<Index>((static_cast<std::size_t>(e) * J + j) * w) + k;
        z[i] = q[j] * (r[i] + nm.work[e * w + k] / p.tau(j));
      }
  return true;
}

}  // namespace tmlab::tm
