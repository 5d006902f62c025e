// Tensor-mass St VK kernels on relative displacements; equations in tensor_mass.hpp and
// docs/theory/tensor-mass.md (corrected forms of docs/theory/seed-errata.md).
#include "tensormass/kernels/tensor_mass.hpp"

#include <cassert>

namespace tmlab::tm {

namespace {

// Pair P = (k,l) of the Gram vector G: (0,0),(1,1),(2,2),(0,1),(0,2),(1,2) (Voigt order).
constexpr int pair_k(int P) { return P < 3 ? P : (P == 5 ? 1 : 0); }
constexpr int pair_l(int P) { return P < 3 ? P : (P == 3 ? 1 : 2); }
constexpr double pair_mult(int P) { return P < 3 ? 1.0 : 2.0; }
// Row-major packed upper triangle of an n x n symmetric matrix, i <= j.
constexpr int packed(int n, int i, int j) { return i * n - i * (i - 1) / 2 + (j - i); }

/// Relative displacements e_j = U_{j+1} - U_0 (e[3j + c]), j = 0..2.
inline void relative(const VecX& u, const Tet& tet, double* e) {
  const double* U = u.data();
  const double* u0 = U + 3 * static_cast<std::ptrdiff_t>(tet[0]);
  for (int j = 0; j < 3; ++j) {
    const double* uj = U + 3 * static_cast<std::ptrdiff_t>(tet[j + 1]);
    for (int c = 0; c < 3; ++c) e[3 * j + c] = uj[c] - u0[c];
  }
}

/// y = S x for a packed symmetric n x n matrix.
template <int n>
inline void sym_matvec(const double* Sp, const double* x, double* y) {
  for (int i = 0; i < n; ++i) y[i] = 0.0;
  for (int i = 0; i < n; ++i) {
    y[i] += Sp[packed(n, i, i)] * x[i];
    for (int j = i + 1; j < n; ++j) {
      const double s = Sp[packed(n, i, j)];
      y[i] += s * x[j];
      y[j] += s * x[i];
    }
  }
}

/// G_P = e_k . e_l.
inline void gram(const double* e, double* G) {
  for (int P = 0; P < 6; ++P) {
    const double* ek = e + 3 * pair_k(P);
    const double* el = e + 3 * pair_l(P);
    G[P] = ek[0] * el[0] + ek[1] * el[1] + ek[2] * el[2];
  }
}

/// h = Chat e (h_P = sum_j e_j . m_P C_jkl).
inline void chat_apply(const double* C, const double* e, double* h) {
  for (int P = 0; P < 6; ++P) {
    double s = 0.0;
    for (int i = 0; i < 9; ++i) s += C[9 * P + i] * e[i];
    h[P] = s;
  }
}

/// g += Chat^T G (g_j += sum_kl C_jkl (e_k . e_l)).
inline void chat_transpose_add(const double* C, const double* G, double* g) {
  for (int P = 0; P < 6; ++P)
    for (int i = 0; i < 9; ++i) g[i] += C[9 * P + i] * G[P];
}

/// g += Gamma(e)^T s, Gamma = dG/de: P=(k,k) adds 2 s_P e_k to g_k; P=(k,l) adds s_P e_l to g_k
/// and s_P e_k to g_l.
inline void gamma_transpose_add(const double* e, const double* s, double* g) {
  for (int P = 0; P < 6; ++P) {
    const int k = pair_k(P), l = pair_l(P);
    if (k == l) {
      for (int c = 0; c < 3; ++c) g[3 * k + c] += 2.0 * s[P] * e[3 * k + c];
    } else {
      for (int c = 0; c < 3; ++c) {
        g[3 * k + c] += s[P] * e[3 * l + c];
        g[3 * l + c] += s[P] * e[3 * k + c];
      }
    }
  }
}

/// dG = Gamma(e) d: dG_P = e_k . d_l + e_l . d_k.
inline void gamma_apply(const double* e, const double* d, double* dG) {
  for (int P = 0; P < 6; ++P) {
    const int k = pair_k(P), l = pair_l(P);
    double s = 0.0;
    for (int c = 0; c < 3; ++c) s += e[3 * k + c] * d[3 * l + c] + e[3 * l + c] * d[3 * k + c];
    dG[P] = s;
  }
}

/// Relative-force kernel: returns the tet energy, writes g = dW_T/de (9).
inline double tet_energy_force(const TensorMassTet& T, const double* e, double* g) {
  double G[6], h[6], DG[6], sigma[6], Be[9];
  gram(e, G);                 // G_P = e_k . e_l
  chat_apply(T.C, e, h);      // h = Chat e
  sym_matvec<6>(T.D, G, DG);  // Dhat G
  sym_matvec<9>(T.B, e, Be);  // B e
  double w = 0.0;             // W_T = e^T B e + h . G + G^T Dhat G   (errata eq. 2)
  for (int i = 0; i < 9; ++i) w += e[i] * Be[i];
  for (int P = 0; P < 6; ++P) {
    w += (h[P] + DG[P]) * G[P];
    sigma[P] = h[P] + 2.0 * DG[P];  // dW/dG
  }
  // g = 2 B e + Chat^T G + Gamma^T sigma   (errata eq. 7, relative form)
  for (int i = 0; i < 9; ++i) g[i] = 2.0 * Be[i];
  chat_transpose_add(T.C, G, g);
  gamma_transpose_add(e, sigma, g);
  return w;
}

inline double tet_energy_only(const TensorMassTet& T, const double* e) {
  double G[6], h[6], DG[6], Be[9];
  gram(e, G);
  chat_apply(T.C, e, h);
  sym_matvec<6>(T.D, G, DG);
  sym_matvec<9>(T.B, e, Be);
  double w = 0.0;
  for (int i = 0; i < 9; ++i) w += e[i] * Be[i];
  for (int P = 0; P < 6; ++P) w += (h[P] + DG[P]) * G[P];
  return w;
}

/// dg = (d^2 W_T / de^2) d.
inline void tet_hessian_apply(const TensorMassTet& T, const double* e, const double* d, double* dg) {
  double G[6], h[6], DG[6], sigma[6];
  gram(e, G);
  chat_apply(T.C, e, h);
  sym_matvec<6>(T.D, G, DG);
  for (int P = 0; P < 6; ++P) sigma[P] = h[P] + 2.0 * DG[P];
  double dG[6], dh[6], DdG[6], dsigma[6];
  gamma_apply(e, d, dG);   // dG = Gamma d
  chat_apply(T.C, d, dh);  // dh = Chat d
  sym_matvec<6>(T.D, dG, DdG);
  for (int P = 0; P < 6; ++P) dsigma[P] = dh[P] + 2.0 * DdG[P];
  // dg = 2 B d + Chat^T dG + Gamma(e)^T dsigma + Gamma(d)^T sigma
  sym_matvec<9>(T.B, d, dg);
  for (int i = 0; i < 9; ++i) dg[i] *= 2.0;
  chat_transpose_add(T.C, dG, dg);
  gamma_transpose_add(e, dsigma, dg);
  gamma_transpose_add(d, sigma, dg);
}

/// The 9x9 relative Hessian
/// H = 2B + Sigma (x) I + Chat^T Gamma + Gamma^T Chat + 2 Gamma^T Dhat Gamma.
inline Eigen::Matrix<double, 9, 9> tet_hessian(const TensorMassTet& T, const double* e) {
  using M69 = Eigen::Matrix<double, 6, 9>;
  double G[6], h[6], DG[6], sigma[6];
  gram(e, G);
  chat_apply(T.C, e, h);
  sym_matvec<6>(T.D, G, DG);
  for (int P = 0; P < 6; ++P) sigma[P] = h[P] + 2.0 * DG[P];

  M69 Gam = M69::Zero();  // Gamma = dG/de
  for (int P = 0; P < 6; ++P) {
    const int k = pair_k(P), l = pair_l(P);
    for (int c = 0; c < 3; ++c) {
      Gam(P, 3 * k + c) += e[3 * l + c];
      Gam(P, 3 * l + c) += e[3 * k + c];
    }
  }
  const Eigen::Map<const Eigen::Matrix<double, 6, 9, Eigen::RowMajor>> Chat(T.C);
  Eigen::Matrix<double, 6, 6> Dhat;
  for (int P = 0; P < 6; ++P)
    for (int Q = P; Q < 6; ++Q) Dhat(P, Q) = Dhat(Q, P) = T.D[packed(6, P, Q)];

  Eigen::Matrix<double, 9, 9> H;
  for (int i = 0; i < 9; ++i)
    for (int j = i; j < 9; ++j) H(i, j) = H(j, i) = 2.0 * T.B[packed(9, i, j)];
  const M69 DGam = 2.0 * Dhat.lazyProduct(Gam);
  const M69 X = Chat + DGam;  // Chat^T Gam + Gam^T Chat + 2 Gam^T Dhat Gam = Gam^T X + Chat^T Gam
  H.noalias() += Gam.transpose().lazyProduct(X);
  H.noalias() += Chat.transpose().lazyProduct(Gam);
  for (int P = 0; P < 6; ++P) {  // Sigma (x) I
    const int k = pair_k(P), l = pair_l(P);
    const double s = (k == l) ? 2.0 * sigma[P] : sigma[P];
    for (int c = 0; c < 3; ++c) {
      H(3 * k + c, 3 * l + c) += s;
      if (k != l) H(3 * l + c, 3 * k + c) += s;
    }
  }
  return H;
}

/// 12x12 stiffness from the 9x9 relative Hessian: e = T U with e_j = U_{j+1} - U_0.
inline Eigen::Matrix<double, 12, 12> expand_hessian(const Eigen::Matrix<double, 9, 9>& H) {
  Eigen::Matrix<double, 12, 12> K;
  K.bottomRightCorner<9, 9>() = H;
  Eigen::Matrix<double, 9, 3> colsum = Eigen::Matrix<double, 9, 3>::Zero();  // sum_k H_jk
  for (int k = 0; k < 3; ++k) colsum += H.block<9, 3>(0, 3 * k);
  K.block<9, 3>(3, 0) = -colsum;
  K.block<3, 9>(0, 3) = -colsum.transpose();
  Eigen::Matrix3d all = Eigen::Matrix3d::Zero();
  for (int j = 0; j < 3; ++j) all += colsum.block<3, 3>(3 * j, 0);
  K.topLeftCorner<3, 3>() = all;
  return K;
}

}  // namespace

TensorMassTet make_tensor_mass_tet(const TetRest& rest, const StVenantKirchhoff& material) {
  const double V = rest.volume, lam = material.lambda, mu = material.mu;
  const Vec3* a = &rest.grad[1];  // a_1..a_3 (relative form never needs a_0)
  double d[3][3];                 // d_jk = a_j . a_k
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k) d[j][k] = a[j].dot(a[k]);
  TensorMassTet T{};
  // B_jk = V [ lambda/2 a_j (x) a_k + mu/2 ( a_k (x) a_j + (a_j . a_k) I ) ]   (errata eq. 3)
  for (int j = 0; j < 3; ++j)
    for (int al = 0; al < 3; ++al)
      for (int k = 0; k < 3; ++k)
        for (int be = 0; be < 3; ++be) {
          const int r = 3 * j + al, c = 3 * k + be;
          if (r > c) continue;
          T.B[packed(9, r, c)] = V * (0.5 * lam * a[j](al) * a[k](be) +
                                      0.5 * mu * (a[k](al) * a[j](be) + (al == be ? d[j][k] : 0.0)));
        }
  // Chat_jP = m_P C_jkl,  C_jkl = V [ lambda/2 a_j (a_k.a_l) + mu/2 ( a_l (a_j.a_k) + a_k (a_j.a_l) ) ]
  for (int P = 0; P < 6; ++P) {
    const int k = pair_k(P), l = pair_l(P);
    for (int j = 0; j < 3; ++j)
      for (int al = 0; al < 3; ++al)
        T.C[9 * P + 3 * j + al] =
            pair_mult(P) * V *
            (0.5 * lam * a[j](al) * d[k][l] + 0.5 * mu * (a[l](al) * d[j][k] + a[k](al) * d[j][l]));
  }
  // Dhat_PQ = m_P m_Q Dsym_jklm, D_jklm = V [ lambda/8 (a_j.a_k)(a_l.a_m) + mu/4 (a_j.a_m)(a_k.a_l) ]
  // symmetrised over j<->k: Dsym = V [ lambda/8 d_jk d_lm + mu/8 (d_jm d_kl + d_jl d_km) ].
  for (int P = 0; P < 6; ++P)
    for (int Q = P; Q < 6; ++Q) {
      const int j = pair_k(P), k = pair_l(P), l = pair_k(Q), m = pair_l(Q);
      T.D[packed(6, P, Q)] =
          pair_mult(P) * pair_mult(Q) * V *
          (lam / 8.0 * d[j][k] * d[l][m] + mu / 8.0 * (d[j][m] * d[k][l] + d[j][l] * d[k][m]));
    }
  return T;
}

TensorMassStVK::TensorMassStVK(const Mesh& mesh, const StVenantKirchhoff& material)
    : num_nodes_(mesh.num_points()), tets_(mesh.tets), material_(material) {
  const std::vector<TetRest> rest = compute_tet_rest(mesh);
  tensors_.resize(rest.size());
  for (std::size_t t = 0; t < rest.size(); ++t) tensors_[t] = make_tensor_mass_tet(rest[t], material_);
  pattern_ = TangentPattern(num_nodes_, tets_);
}

double TensorMassStVK::tet_energy(Index t, const VecX& u) const {
  double e[9];
  relative(u, tets_[static_cast<std::size_t>(t)], e);
  return tet_energy_only(tensors_[static_cast<std::size_t>(t)], e);
}

void TensorMassStVK::tet_gradient(Index t, const VecX& u, double* g) const {
  double e[9];
  relative(u, tets_[static_cast<std::size_t>(t)], e);
  tet_energy_force(tensors_[static_cast<std::size_t>(t)], e, g);
}

TensorMassStVK::Mat34 TensorMassStVK::tet_force(Index t, const VecX& u) const {
  double e[9], g[9];
  relative(u, tets_[static_cast<std::size_t>(t)], e);
  tet_energy_force(tensors_[static_cast<std::size_t>(t)], e, g);
  Mat34 f;
  for (int j = 0; j < 3; ++j) f.col(j + 1) = Vec3(g[3 * j], g[3 * j + 1], g[3 * j + 2]);
  f.col(0) = -(f.col(1) + f.col(2) + f.col(3));  // f_0 = -(g_1 + g_2 + g_3)
  return f;
}

TensorMassStVK::Mat12 TensorMassStVK::tet_stiffness(Index t, const VecX& u) const {
  double e[9];
  relative(u, tets_[static_cast<std::size_t>(t)], e);
  return expand_hessian(tet_hessian(tensors_[static_cast<std::size_t>(t)], e));
}

double TensorMassStVK::energy(const VecX& u) const {
  assert(u.size() == num_dofs());
  double w = 0.0;
  double e[9];
  for (std::size_t t = 0; t < tets_.size(); ++t) {
    relative(u, tets_[t], e);
    w += tet_energy_only(tensors_[t], e);
  }
  return w;
}

void TensorMassStVK::internal_force(const VecX& u, VecX& f) const {
  assert(u.size() == num_dofs());
  f.setZero(num_dofs());
  double* F = f.data();
  double e[9], g[9];
  for (std::size_t t = 0; t < tets_.size(); ++t) {
    const Tet& tet = tets_[t];
    relative(u, tet, e);
    tet_energy_force(tensors_[t], e, g);
    double* f0 = F + 3 * static_cast<std::ptrdiff_t>(tet[0]);
    for (int j = 0; j < 3; ++j) {
      double* fj = F + 3 * static_cast<std::ptrdiff_t>(tet[j + 1]);
      for (int c = 0; c < 3; ++c) {
        fj[c] += g[3 * j + c];
        f0[c] -= g[3 * j + c];
      }
    }
  }
}

void TensorMassStVK::tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const {
  assert(u.size() == num_dofs() && v.size() == num_dofs());
  Kv.setZero(num_dofs());
  double* out = Kv.data();
  double e[9], d[9], dg[9];
  for (std::size_t t = 0; t < tets_.size(); ++t) {
    const Tet& tet = tets_[t];
    relative(u, tet, e);
    relative(v, tet, d);
    tet_hessian_apply(tensors_[t], e, d, dg);
    double* o0 = out + 3 * static_cast<std::ptrdiff_t>(tet[0]);
    for (int j = 0; j < 3; ++j) {
      double* oj = out + 3 * static_cast<std::ptrdiff_t>(tet[j + 1]);
      for (int c = 0; c < 3; ++c) {
        oj[c] += dg[3 * j + c];
        o0[c] -= dg[3 * j + c];
      }
    }
  }
}

void TensorMassStVK::tangent(const VecX& u, SpMat& K) const {
  assert(u.size() == num_dofs());
  if (!pattern_.matches(K))
    pattern_.reset(K);
  else
    std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
  double* values = K.valuePtr();
  double e[9];
  for (std::size_t t = 0; t < tets_.size(); ++t) {
    relative(u, tets_[t], e);
    const Mat12 Kt = expand_hessian(tet_hessian(tensors_[t], e));
    pattern_.scatter(static_cast<Index>(t), tets_[t], Kt, values);
  }
}

}  // namespace tmlab::tm
