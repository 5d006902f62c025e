// Average-nodal-pressure (nodal-averaged F-bar) linear tet; equations in averaged_pressure_tet.hpp.
#include "tensormass/kernels/averaged_pressure_tet.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>

namespace tmlab::tm {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

inline std::size_t sz(Index i) { return static_cast<std::size_t>(i); }
inline Vec3 node_vec(const VecX& x, Index node) { return x.segment<3>(3 * static_cast<Eigen::Index>(node)); }
inline double ddot(const Mat3& A, const Mat3& B) { return A.cwiseProduct(B).sum(); }

/// cof(F) = det(F) F^-T, columns c1 x c2, c2 x c0, c0 x c1 of F's columns c0, c1, c2.
inline Mat3 cofactor(const Mat3& F) {
  Mat3 C;
  C.col(0) = F.col(1).cross(F.col(2));
  C.col(1) = F.col(2).cross(F.col(0));
  C.col(2) = F.col(0).cross(F.col(1));
  return C;
}

/// r^(1/3) for 1/2 <= r <= 2 (the volume ratios Jbar_e / J_e of any reasonable state): a degree-4
/// polynomial (relative error < 6e-4 on the interval) and two Halley steps y <- y (y^3 + 2r)/(2y^3 + r)
/// (cubic convergence: < 1e-9, then below round-off); within a few ulps of std::cbrt (tested). No
/// call and no branch, so a loop over the tets vectorises.
inline double cube_root_near_one(double r) {
  double y = 0.4568123070944322 +
             r * (0.8702924592016156 +
                  r * (-0.4679502874559885 + r * (0.16543434764067025 + r * -0.024331129719280378)));
  double y3 = y * y * y;
  y *= (y3 + 2.0 * r) / (2.0 * y3 + r);
  y3 = y * y * y;
  y *= (y3 + 2.0 * r) / (2.0 * y3 + r);
  return y;
}
inline bool near_one(double r) { return r >= 0.5 && r <= 2.0; }
/// The real cube root every path of the element uses.
inline double cube_root(double r) { return near_one(r) ? cube_root_near_one(r) : std::cbrt(r); }

/// The tet law of the elastic element: the Law at Ebar.
struct LawTet {
  const Law* law;
  void operator()(std::size_t, const Mat3& E, double* W, Mat3* S, Mat6* D) const {
    law->evaluate(E, W, S, D);
  }
};

/// The trial law of a viscoelastic step (AveragedPressureTet::TrialStress).
struct TrialTet {
  const Law* law;
  double g;
  const double* s_hist;
  void operator()(std::size_t t, const Mat3& E, double* W, Mat3* S, Mat6* D) const {
    const double* sh = s_hist + 6 * t;
    double We = 0.0;
    Mat3 Se;
    law->evaluate(E, W ? &We : nullptr, S ? &Se : nullptr, D);
    if (W) {
      double e6[6];
      to_voigt(E, e6);
      *W = (1.0 + g) * We + (sh[0] * e6[0] + sh[1] * e6[1] + sh[2] * e6[2] +
                             2.0 * (sh[3] * e6[3] + sh[4] * e6[4] + sh[5] * e6[5]));
    }
    if (S) *S = (1.0 + g) * Se + from_voigt(sh);
    if (D) *D *= (1.0 + g);
  }
};

/// psi(F, Jbar) = psi_e(Ebar), Ebar = (s^2 F^T F - I)/2, s = (Jbar / det F)^(1/3), with its gradient
/// (P_iso, q) and what its linearisation needs.
struct PsiState {
  bool ok = false;
  double J = 0.0, Jb = 0.0, s = 0.0, p = 0.0, q = 0.0, W = 0.0;
  Mat3 FinvT, Fbar, S, Pbar, Piso;
  Mat6 D;
};

template <class TL>
PsiState evaluate_psi(const TL& tl, bool stvk, std::size_t t, const Mat3& F, double Jb, bool want_W,
                      bool want_D) {
  PsiState st;
  st.J = F.determinant();
  st.Jb = Jb;
  st.ok = stvk ? (st.J != 0.0) : (st.J > 0.0 && Jb > 0.0);
  if (!st.ok) return st;
  st.s = cube_root(Jb / st.J);
  st.Fbar = st.s * F;
  const Mat3 Ebar = 0.5 * (st.Fbar.transpose() * st.Fbar - Mat3::Identity());
  tl(t, Ebar, want_W ? &st.W : nullptr, &st.S, want_D ? &st.D : nullptr);
  st.Pbar = st.Fbar * st.S;
  st.p = ddot(st.Pbar, st.Fbar) / 3.0;
  st.FinvT = F.inverse().transpose();
  st.Piso = st.s * st.Pbar - st.p * st.FinvT;
  st.q = st.p / Jb;
  return st;
}

/// The linearisation (dP_iso, dq) of the gradient of psi in the direction (dF, dJb) (needs want_D).
void linearize_psi(const PsiState& st, const Mat3& F, const Mat3& dF, double dJb, Mat3& dPiso, double& dq) {
  if (!st.ok) {
    dPiso.setConstant(kNaN);
    dq = kNaN;
    return;
  }
  const double ds = st.s / 3.0 * (dJb / st.Jb - ddot(st.FinvT, dF));
  const Mat3 dFbar = st.s * dF + ds * F;
  const Mat3 FtdF = st.Fbar.transpose() * dFbar;
  const Mat3 dS = apply_tangent(st.D, 0.5 * (FtdF + FtdF.transpose()));
  const Mat3 dPbar = dFbar * st.S + st.Fbar * dS;
  const double dp = (ddot(dPbar, st.Fbar) + ddot(st.Pbar, dFbar)) / 3.0;
  dPiso = ds * st.Pbar + st.s * dPbar - dp * st.FinvT + st.p * (st.FinvT * dF.transpose() * st.FinvT);
  dq = dp / st.Jb - st.p * dJb / (st.Jb * st.Jb);
}

AveragedPressureTet::Mat10 hessian_of(const PsiState& st, const Mat3& F) {
  AveragedPressureTet::Mat10 H;
  if (!st.ok) {
    H.setConstant(kNaN);
    return H;
  }
  for (int k = 0; k < 10; ++k) {
    Mat3 dF = Mat3::Zero();
    double dJb = 0.0;
    if (k < 9)
      dF(k / 3, k % 3) = 1.0;
    else
      dJb = 1.0;
    Mat3 dP;
    double dq = 0.0;
    linearize_psi(st, F, dF, dJb, dP, dq);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) H(3 * i + j, k) = dP(i, j);
    H(9, k) = dq;
  }
  return H;
}

}  // namespace

AveragedPressureTet::AveragedPressureTet(const Mesh& mesh, Law law)
    : num_nodes_(mesh.num_points()), tets_(mesh.tets), rest_(compute_tet_rest(mesh)), law_(std::move(law)) {
  const std::size_t n = sz(num_nodes_);
  std::vector<double> vol(n, 0.0);
  node_tet_start_.assign(n + 1, 0);
  for (std::size_t t = 0; t < tets_.size(); ++t)
    for (Index a : tets_[t]) {
      vol[sz(a)] += rest_[t].volume;
      ++node_tet_start_[sz(a) + 1];
    }
  for (std::size_t a = 0; a < n; ++a) node_tet_start_[a + 1] += node_tet_start_[a];
  node_tets_.resize(sz(node_tet_start_[n]));
  std::vector<Index> fill(node_tet_start_.begin(), node_tet_start_.end() - 1);
  for (std::size_t t = 0; t < tets_.size(); ++t)
    for (Index a : tets_[t]) node_tets_[sz(fill[sz(a)]++)] = static_cast<Index>(t);
  inv_node_volume_.resize(n);
  for (std::size_t a = 0; a < n; ++a) inv_node_volume_[a] = vol[a] > 0.0 ? 1.0 / vol[a] : 0.0;
  geo_.resize(kGeo * tets_.size());
  for (std::size_t t = 0; t < tets_.size(); ++t) {
    geo_[kGeo * t] = rest_[t].volume;
    for (std::size_t j = 1; j < 4; ++j)
      for (std::size_t k = 0; k < 3; ++k)
        geo_[kGeo * t + 3 * (j - 1) + 1 + k] = rest_[t].grad[j][static_cast<Eigen::Index>(k)];
  }
  inv_six_volume_.resize(tets_.size());
  for (std::size_t t = 0; t < tets_.size(); ++t) inv_six_volume_[t] = 1.0 / (6.0 * rest_[t].volume);
  points_.resize(3 * n);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t k = 0; k < 3; ++k) points_[3 * a + k] = mesh.points[a][static_cast<Eigen::Index>(k)];
  node_tet_weight_.resize(node_tets_.size());
  for (std::size_t a = 0; a < n; ++a)
    for (Index k = node_tet_start_[a]; k < node_tet_start_[a + 1]; ++k)
      node_tet_weight_[sz(k)] = rest_[sz(node_tets_[sz(k)])].volume * inv_node_volume_[a];
  build_pattern();
}

void AveragedPressureTet::build_pattern() {
  const std::size_t n = sz(num_nodes_);
  // Node graph (one edge = sharing a tet), sorted adjacency lists including the node itself.
  std::vector<std::uint64_t> pairs;
  pairs.reserve(16 * tets_.size());
  for (const Tet& tet : tets_)
    for (Index c : tet)
      for (Index r : tet)
        pairs.push_back((static_cast<std::uint64_t>(c) << 32) | static_cast<std::uint32_t>(r));
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  node_adj_start_.assign(n + 1, 0);
  for (std::uint64_t key : pairs) ++node_adj_start_[sz(static_cast<Index>(key >> 32)) + 1];
  for (std::size_t c = 0; c < n; ++c) node_adj_start_[c + 1] += node_adj_start_[c];
  node_adj_.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) node_adj_[i] = static_cast<Index>(pairs[i] & 0xffffffffu);

  // Column node c couples to the nodes at most three edges away (breadth-first, depth 3).
  std::vector<Index> mark(n, -1), ball, frontier, next;
  std::vector<std::size_t> col_start(n + 1, 0);
  std::vector<Index> rows;
  for (std::size_t c = 0; c < n; ++c) {
    ball.clear();
    if (node_adj_start_[c + 1] > node_adj_start_[c]) {
      frontier.assign(1, static_cast<Index>(c));
      mark[c] = static_cast<Index>(c);
      ball.push_back(static_cast<Index>(c));
      for (int depth = 0; depth < 3; ++depth) {
        next.clear();
        for (Index x : frontier)
          for (Index k = node_adj_start_[sz(x)]; k < node_adj_start_[sz(x) + 1]; ++k) {
            const Index y = node_adj_[sz(k)];
            if (mark[sz(y)] != static_cast<Index>(c)) {
              mark[sz(y)] = static_cast<Index>(c);
              next.push_back(y);
              ball.push_back(y);
            }
          }
        frontier.swap(next);
      }
      std::sort(ball.begin(), ball.end());
    }
    rows.insert(rows.end(), ball.begin(), ball.end());
    col_start[c + 1] = rows.size();
  }
  const std::size_t nnz = 9 * rows.size();
  if (nnz > static_cast<std::size_t>(std::numeric_limits<StorageIndex>::max()))
    throw Error("averaged-pressure tet: too many nonzeros in the widened tangent pattern for 32-bit indices");
  outer_.resize(3 * n + 1);
  inner_.resize(nnz);
  for (std::size_t c = 0; c < n; ++c) {
    const std::size_t deg = col_start[c + 1] - col_start[c];
    for (std::size_t b = 0; b < 3; ++b) {
      const std::size_t begin = 9 * col_start[c] + b * 3 * deg;
      outer_[3 * c + b] = static_cast<StorageIndex>(begin);
      for (std::size_t k = 0; k < deg; ++k)
        for (std::size_t a = 0; a < 3; ++a)
          inner_[begin + 3 * k + a] =
              static_cast<StorageIndex>(3 * rows[col_start[c] + k] + static_cast<Index>(a));
    }
  }
  outer_[3 * n] = static_cast<StorageIndex>(nnz);
}

Mat3 AveragedPressureTet::grad(Index t, const VecX& u) const {
  const Tet& tet = tets_[sz(t)];
  const TetRest& r = rest_[sz(t)];
  const Vec3 u0 = node_vec(u, tet[0]);
  Mat3 H = Mat3::Zero();
  for (int j = 1; j < 4; ++j) H.noalias() += (node_vec(u, tet[sz(j)]) - u0) * r.grad[sz(j)].transpose();
  return H;
}

void AveragedPressureTet::averaged_volumes(const VecX& u, std::vector<double>& j,
                                           std::vector<double>& jbar) const {
  const std::size_t nt = tets_.size(), n = sz(num_nodes_);
  j.resize(nt);
  jbar.resize(nt);
  for (std::size_t t = 0; t < nt; ++t)
    j[t] = (Mat3::Identity() + grad(static_cast<Index>(t), u)).determinant();
  // J_a = sum_{e ∋ a} (V_e / sum V) J_e, a gather over the node -> tet list (as internal_force)
  std::vector<double> node_j(n);
  for (std::size_t a = 0; a < n; ++a) {
    double s = 0.0;
    for (Index k = node_tet_start_[a]; k < node_tet_start_[a + 1]; ++k)
      s += node_tet_weight_[sz(k)] * j[sz(node_tets_[sz(k)])];
    node_j[a] = s;
  }
  for (std::size_t t = 0; t < nt; ++t) {
    const Tet& tet = tets_[t];
    jbar[t] = 0.25 * (node_j[sz(tet[0])] + node_j[sz(tet[1])] + node_j[sz(tet[2])] + node_j[sz(tet[3])]);
  }
}

double AveragedPressureTet::psi(const Mat3& F, double Jbar) const {
  const PsiState st = evaluate_psi(LawTet{&law_}, law_.is_stvk(), 0, F, Jbar, true, false);
  return st.ok ? st.W : kInf;
}

Eigen::Matrix<double, 10, 1> AveragedPressureTet::psi_gradient(const Mat3& F, double Jbar) const {
  const PsiState st = evaluate_psi(LawTet{&law_}, law_.is_stvk(), 0, F, Jbar, false, false);
  Eigen::Matrix<double, 10, 1> g;
  if (!st.ok) return g.setConstant(kNaN);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) g(3 * i + k) = st.Piso(i, k);
  g(9) = st.q;
  return g;
}

double AveragedPressureTet::volume_cube_root(double r) { return cube_root(r); }

AveragedPressureTet::Mat10 AveragedPressureTet::psi_hessian(const Mat3& F, double Jbar) const {
  return hessian_of(evaluate_psi(LawTet{&law_}, law_.is_stvk(), 0, F, Jbar, false, true), F);
}

std::vector<double> AveragedPressureTet::volume_ratios(const VecX& u) const {
  std::vector<double> j, jbar;
  averaged_volumes(u, j, jbar);
  for (std::size_t t = 0; t < j.size(); ++t) jbar[t] /= j[t];
  return jbar;
}

Mat3 AveragedPressureTet::averaged_deformation_gradient(Index t, const VecX& u) const {
  std::vector<double> j, jbar;
  averaged_volumes(u, j, jbar);
  return cube_root(jbar[sz(t)] / j[sz(t)]) * (Mat3::Identity() + grad(t, u));
}

std::vector<Mat3> AveragedPressureTet::averaged_deformation_gradients(const VecX& u) const {
  std::vector<double> j, jbar;
  averaged_volumes(u, j, jbar);
  std::vector<Mat3> out(j.size());
  for (std::size_t t = 0; t < j.size(); ++t)
    out[t] = cube_root(jbar[t] / j[t]) * (Mat3::Identity() + grad(static_cast<Index>(t), u));
  return out;
}

// ---------------------------------------------------------------- the public passes

double AveragedPressureTet::energy(const VecX& u) const { return energy_impl(u, LawTet{&law_}); }
void AveragedPressureTet::internal_force(const VecX& u, VecX& f) const { force_impl(u, f, LawTet{&law_}); }
void AveragedPressureTet::tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const {
  tangent_apply_impl(u, v, Kv, LawTet{&law_});
}
void AveragedPressureTet::tangent(const VecX& u, SpMat& K) const { tangent_impl(u, K, LawTet{&law_}); }

double AveragedPressureTet::energy_with(const VecX& u, const TrialStress& ts) const {
  if (!ts.s_hist) return energy(u);
  return energy_impl(u, TrialTet{&law_, ts.gain, ts.s_hist});
}
void AveragedPressureTet::internal_force_with(const VecX& u, VecX& f, const TrialStress& ts) const {
  if (!ts.s_hist) return internal_force(u, f);
  force_impl(u, f, TrialTet{&law_, ts.gain, ts.s_hist});
}
void AveragedPressureTet::tangent_apply_with(const VecX& u, const VecX& v, VecX& Kv,
                                             const TrialStress& ts) const {
  if (!ts.s_hist) return tangent_apply(u, v, Kv);
  tangent_apply_impl(u, v, Kv, TrialTet{&law_, ts.gain, ts.s_hist});
}
void AveragedPressureTet::tangent_with(const VecX& u, SpMat& K, const TrialStress& ts) const {
  if (!ts.s_hist) return tangent(u, K);
  tangent_impl(u, K, TrialTet{&law_, ts.gain, ts.s_hist});
}
void AveragedPressureTet::internal_force_reference(const VecX& u, VecX& f) const {
  force_reference_impl(u, f, LawTet{&law_});
}
void AveragedPressureTet::internal_force_reference(const VecX& u, VecX& f, const TrialStress& ts) const {
  if (!ts.s_hist) return force_reference_impl(u, f, LawTet{&law_});
  force_reference_impl(u, f, TrialTet{&law_, ts.gain, ts.s_hist});
}

// ---------------------------------------------------------------- energy and force

template <class TL>
double AveragedPressureTet::energy_impl(const VecX& u, const TL& tl) const {
  assert(u.size() == num_dofs());
  std::vector<double> j, jbar;
  averaged_volumes(u, j, jbar);
  const bool stvk = law_.is_stvk();
  double w = 0.0;
  for (std::size_t t = 0; t < tets_.size(); ++t) {
    const PsiState st =
        evaluate_psi(tl, stvk, t, Mat3::Identity() + grad(static_cast<Index>(t), u), jbar[t], true, false);
    if (!st.ok) return kInf;
    w += rest_[t].volume * st.W;
  }
  return w;
}

template <class TL>
void AveragedPressureTet::force_reference_impl(const VecX& u, VecX& f, const TL& tl) const {
  assert(u.size() == num_dofs());
  const std::size_t nt = tets_.size(), n = sz(num_nodes_);
  f.setZero(num_dofs());
  std::vector<double> j, jbar;
  averaged_volumes(u, j, jbar);
  const bool stvk = law_.is_stvk();
  std::vector<Mat3> piso(nt);
  std::vector<double> node_q(n, 0.0);
  for (std::size_t t = 0; t < nt; ++t) {
    const PsiState st =
        evaluate_psi(tl, stvk, t, Mat3::Identity() + grad(static_cast<Index>(t), u), jbar[t], false, false);
    if (st.ok)
      piso[t] = st.Piso;
    else
      piso[t].setConstant(kNaN);
    for (Index a : tets_[t]) node_q[sz(a)] += 0.25 * rest_[t].volume * (st.ok ? st.q : kNaN);  // Q_a
  }
  for (std::size_t a = 0; a < n; ++a) node_q[a] *= inv_node_volume_[a];
  for (std::size_t t = 0; t < nt; ++t) {
    const Tet& tet = tets_[t];
    const TetRest& r = rest_[t];
    double pi = 0.0;  // pi_e = V_e sum_{a ∈ e} Q_a / sum V
    for (Index a : tet) pi += node_q[sz(a)];
    pi *= r.volume;
    const Mat3 M = r.volume * piso[t] + pi * cofactor(Mat3::Identity() + grad(static_cast<Index>(t), u));
    for (int p = 0; p < 4; ++p) f.segment<3>(3 * static_cast<Eigen::Index>(tet[sz(p)])) += M * r.grad[sz(p)];
  }
}

namespace {

/// f_p += f_p of one tet's nodes, f_0 = -(f_1 + f_2 + f_3).
[[gnu::always_inline]] inline void add_tet_forces(double* fd, const Tet& tet, const Vec3& f1, const Vec3& f2,
                                                  const Vec3& f3) {
  const Vec3 f0 = -(f1 + f2 + f3);
  const Vec3* fp[4] = {&f0, &f1, &f2, &f3};
  for (std::size_t p = 0; p < 4; ++p) {
    double* dst = fd + 3 * tet[p];
    dst[0] += (*fp[p])[0];
    dst[1] += (*fp[p])[1];
    dst[2] += (*fp[p])[2];
  }
}

/// The deformed edges x_j - x_0 (j = 1..3) of a tet, x = X + u, as (X_j - X_0) + (u_j - u_0).
[[gnu::always_inline]] inline void deformed_edges(const double* X, const double* ud, const Tet& tet, Vec3& e1,
                                                  Vec3& e2, Vec3& e3) {
  const double *x0 = X + 3 * tet[0], *u0 = ud + 3 * tet[0];
  Vec3* e[3] = {&e1, &e2, &e3};
  for (std::size_t j = 0; j < 3; ++j) {
    const double *xj = X + 3 * tet[j + 1], *uj = ud + 3 * tet[j + 1];
    for (Eigen::Index i = 0; i < 3; ++i) (*e[j])[i] = (xj[i] - x0[i]) + (uj[i] - u0[i]);
  }
}

}  // namespace

template <class TL>
void AveragedPressureTet::force_impl(const VecX& u, VecX& f, const TL& tl) const {
  assert(u.size() == num_dofs());
  const std::size_t nt = tets_.size(), n = sz(num_nodes_);
  f.setZero(num_dofs());
  // Workspace (sized once): per tet J_e, then Jbar_e (then p / J), then s_e (then q_e / 4); per
  // node J_a and the pressure sums Q_a / sum V. No per-tet matrix is stored. The sweeps (1) and (4)
  // work on the deformed edges (J_e = det[x_1 - x_0, x_2 - x_0, x_3 - x_0] / 6 V_e and
  // V_e cof F_e a_p = dV(x)/dx_p, a cross product of two deformed edges / 6), so only (3b) streams
  // the shape gradients.
  work_.resize(3 * nt + 2 * n);
  double* const tj = work_.data();
  double* const tjb = tj + nt;
  double* const ts = tjb + nt;
  double* const node_j = ts + nt;
  double* const node_q = node_j + n;
  const double* const ud = u.data();
  const double* const X = points_.data();
  double* const fd = f.data();
  const Tet* const tets = tets_.data();
  const double* const geo = geo_.data();
  const double* const inv6v = inv_six_volume_.data();
  // (1) J_e.
  for (std::size_t t = 0; t < nt; ++t) {
    Vec3 e1, e2, e3;
    deformed_edges(X, ud, tets[t], e1, e2, e3);
    tj[t] = e1.dot(e2.cross(e3)) * inv6v[t];
  }
  // (2) J_a: a gather with the weights V_e / sum V.
  const Index* const nstart = node_tet_start_.data();
  const Index* const ntets = node_tets_.data();
  const double* const nw = node_tet_weight_.data();
  for (std::size_t a = 0; a < n; ++a) {
    double s = 0.0;
    for (Index k = nstart[a]; k < nstart[a + 1]; ++k) s += nw[k] * tj[ntets[k]];
    node_j[a] = s;
  }
  // (3a) Jbar_e and s_e = (Jbar_e / J_e)^(1/3) (the near-one branch vectorises; the rest after).
  for (std::size_t t = 0; t < nt; ++t) {
    const Tet& tet = tets[t];
    const double jb =
        0.25 * (node_j[sz(tet[0])] + node_j[sz(tet[1])] + node_j[sz(tet[2])] + node_j[sz(tet[3])]);
    tjb[t] = jb;
    ts[t] = cube_root_near_one(jb / tj[t]);
  }
  for (std::size_t t = 0; t < nt; ++t)
    if (!near_one(tjb[t] / tj[t])) ts[t] = std::cbrt(tjb[t] / tj[t]);
  // (3b) the law at Ebar = (s^2 C - I)/2, C = F^T F; the isochoric force's first part
  // V s^2 F S a_p scattered now, its second part -(V p / J) cof F a_p with the pressure in (4):
  // V P_iso = V s^2 F S - (V p / J) cof F, p = (s^2 / 3) S : C, q / 4 = p / (4 Jbar).
  const bool stvk = law_.is_stvk();
  for (std::size_t t = 0; t < nt; ++t) {
    const double J = tj[t], Jb = tjb[t];
    const double* g = geo + kGeo * t;
    const Tet& tet = tets[t];
    const Eigen::Map<const Vec3> a1(g + 1), a2(g + 4), a3(g + 7);
    Mat3 F;  // I + sum_j (u_j - u_0) (x) a_j
    {
      const double *u0 = ud + 3 * tet[0], *u1 = ud + 3 * tet[1], *u2 = ud + 3 * tet[2], *u3 = ud + 3 * tet[3];
      for (Eigen::Index i = 0; i < 3; ++i) {
        const double d1 = u1[i] - u0[i], d2 = u2[i] - u0[i], d3 = u3[i] - u0[i];
        for (Eigen::Index k = 0; k < 3; ++k)
          F(i, k) = (i == k ? 1.0 : 0.0) + d1 * a1[k] + d2 * a2[k] + d3 * a3[k];
      }
    }
    if (stvk ? J != 0.0 : (J > 0.0 && Jb > 0.0)) {
      const double s2 = ts[t] * ts[t];
      const Mat3 C = F.transpose() * F;
      Mat3 S;
      tl(t, 0.5 * (s2 * C - Mat3::Identity()), nullptr, &S, nullptr);
      const double p = s2 * ddot(S, C) / 3.0;
      const Mat3 A = (g[0] * s2) * (F * S);
      add_tet_forces(fd, tet, A * a1, A * a2, A * a3);
      tjb[t] = p / J;
      ts[t] = 0.25 * p / Jb;  // q_e / 4: the gather's weights carry V_e
    } else {
      const Vec3 nan = Vec3::Constant(kNaN);
      add_tet_forces(fd, tet, nan, nan, nan);
      tjb[t] = kNaN;
      ts[t] = kNaN;
    }
  }
  // the nodal pressure sums Q_a / sum V = sum_{e ∋ a} (V_e / sum V) q_e / 4: the same gather
  for (std::size_t a = 0; a < n; ++a) {
    double s = 0.0;
    for (Index k = nstart[a]; k < nstart[a + 1]; ++k) s += nw[k] * ts[ntets[k]];
    node_q[a] = s;
  }
  // (4) (pi_e - V p / J) cof F_e a_p = (pi_e / V_e - p / J) dV(x)/dx_p into the nodes, with
  // pi_e / V_e = sum_{a ∈ e} Q_a / sum V and dV/dx_1 = (e_2 x e_3) / 6 (cyclic).
  for (std::size_t t = 0; t < nt; ++t) {
    const Tet& tet = tets[t];
    const double k =
        ((node_q[sz(tet[0])] + node_q[sz(tet[1])] + node_q[sz(tet[2])] + node_q[sz(tet[3])]) - tjb[t]) / 6.0;
    Vec3 e1, e2, e3;
    deformed_edges(X, ud, tet, e1, e2, e3);
    add_tet_forces(fd, tet, k * e2.cross(e3), k * e3.cross(e1), k * e1.cross(e2));
  }
}

// ---------------------------------------------------------------- tangent

template <class TL>
void AveragedPressureTet::tangent_apply_impl(const VecX& u, const VecX& v, VecX& Kv, const TL& tl) const {
  assert(u.size() == num_dofs() && v.size() == num_dofs());
  const std::size_t nt = tets_.size(), n = sz(num_nodes_);
  const bool stvk = law_.is_stvk();
  Kv.setZero(num_dofs());
  std::vector<double> tet_j(nt), tet_dj(nt), node_j(n, 0.0), node_dj(n, 0.0), node_q(n, 0.0), node_dq(n, 0.0);
  for (std::size_t t = 0; t < nt; ++t) {
    const Mat3 F = Mat3::Identity() + grad(static_cast<Index>(t), u);
    const Mat3 dF = grad(static_cast<Index>(t), v);
    tet_j[t] = F.determinant();
    tet_dj[t] = ddot(cofactor(F), dF);
  }
  for (std::size_t a = 0; a < n; ++a)
    for (Index k = node_tet_start_[a]; k < node_tet_start_[a + 1]; ++k) {
      const double w = node_tet_weight_[sz(k)];
      node_j[a] += w * tet_j[sz(node_tets_[sz(k)])];
      node_dj[a] += w * tet_dj[sz(node_tets_[sz(k)])];
    }
  for (std::size_t t = 0; t < nt; ++t) {
    const Tet& tet = tets_[t];
    const TetRest& r = rest_[t];
    const Mat3 F = Mat3::Identity() + grad(static_cast<Index>(t), u);
    const Mat3 dF = grad(static_cast<Index>(t), v);
    const double Jb =
        0.25 * (node_j[sz(tet[0])] + node_j[sz(tet[1])] + node_j[sz(tet[2])] + node_j[sz(tet[3])]);
    double dJb = 0.0;
    for (Index a : tet) dJb += 0.25 * node_dj[sz(a)];
    const PsiState st = evaluate_psi(tl, stvk, t, F, Jb, false, true);
    Mat3 dP;
    double dq = 0.0;
    linearize_psi(st, F, dF, dJb, dP, dq);
    const double q = st.ok ? st.q : kNaN;
    for (int p = 0; p < 4; ++p)
      Kv.segment<3>(3 * static_cast<Eigen::Index>(tet[sz(p)])) += r.volume * (dP * r.grad[sz(p)]);
    for (Index a : tet) {
      node_q[sz(a)] += 0.25 * r.volume * q;
      node_dq[sz(a)] += 0.25 * r.volume * dq;
    }
  }
  for (std::size_t a = 0; a < n; ++a) {
    node_q[a] *= inv_node_volume_[a];
    node_dq[a] *= inv_node_volume_[a];
  }
  for (std::size_t t = 0; t < nt; ++t) {
    const Tet& tet = tets_[t];
    const TetRest& r = rest_[t];
    double pi = 0.0, dpi = 0.0;
    for (Index a : tet) {
      pi += r.volume * node_q[sz(a)];
      dpi += r.volume * node_dq[sz(a)];
    }
    const Mat3 F = Mat3::Identity() + grad(static_cast<Index>(t), u);
    const Mat3 dF = grad(static_cast<Index>(t), v);
    const Mat3 C = cofactor(F);
    const Mat3 FinvT = C / tet_j[t];
    // d cof(F) = J (tr(F^-1 dF) F^-T - F^-T dF^T F^-T)
    const Mat3 dC = ddot(C, dF) * FinvT - tet_j[t] * (FinvT * dF.transpose() * FinvT);
    const Mat3 M = dpi * C + pi * dC;
    for (int p = 0; p < 4; ++p) Kv.segment<3>(3 * static_cast<Eigen::Index>(tet[sz(p)])) += M * r.grad[sz(p)];
  }
}

void AveragedPressureTet::scatter(const std::vector<Index>& nodes, const Eigen::MatrixXd& Kloc,
                                  double* values) const {
  const std::size_t m = nodes.size();
  for (std::size_t j = 0; j < m; ++j) {
    const std::size_t y = sz(nodes[j]);
    const StorageIndex base = outer_[3 * y];
    const StorageIndex stride = outer_[3 * y + 1] - base;  // 3 deg(y)
    const StorageIndex deg = stride / 3;
    StorageIndex k = 0;
    for (std::size_t i = 0; i < m; ++i) {
      const StorageIndex row = 3 * nodes[i];
      while (k < deg && inner_[sz(base + 3 * k)] < row) ++k;
      assert(k < deg && inner_[sz(base + 3 * k)] == row);
      double* dst = values + base + 3 * k;
      for (Eigen::Index b = 0; b < 3; ++b)
        for (Eigen::Index a = 0; a < 3; ++a)
          dst[b * stride + a] +=
              Kloc(3 * static_cast<Eigen::Index>(i) + a, 3 * static_cast<Eigen::Index>(j) + b);
    }
  }
}

template <class TL>
void AveragedPressureTet::tangent_impl(const VecX& u, SpMat& K, const TL& tl) const {
  assert(u.size() == num_dofs());
  const std::size_t nt = tets_.size(), n = sz(num_nodes_);
  const Eigen::Index ndof = num_dofs();
  const bool same = K.rows() == ndof && K.cols() == ndof && K.isCompressed() &&
                    static_cast<std::size_t>(K.nonZeros()) == inner_.size() &&
                    std::equal(outer_.begin(), outer_.end(), K.outerIndexPtr());
  if (!same) {
    std::vector<double> zeros(inner_.size(), 0.0);
    const Eigen::Map<const SpMat> view(ndof, ndof, static_cast<Eigen::Index>(inner_.size()), outer_.data(),
                                       inner_.data(), zeros.data());
    K = view;
    K.makeCompressed();
  } else {
    std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
  }
  double* values = K.valuePtr();

  // Per tet J_e, cof(F_e), Jbar_e; the law's state; the nodal pressure sums and pi_e.
  std::vector<double> tet_j, tet_jb;
  averaged_volumes(u, tet_j, tet_jb);
  std::vector<Mat3> cof(nt);
  std::vector<PsiState> states(nt);
  std::vector<double> node_q(n, 0.0);
  const bool stvk = law_.is_stvk();
  for (std::size_t t = 0; t < nt; ++t) {
    const Mat3 F = Mat3::Identity() + grad(static_cast<Index>(t), u);
    cof[t] = cofactor(F);
    states[t] = evaluate_psi(tl, stvk, t, F, tet_jb[t], false, true);
    const double q = states[t].ok ? states[t].q : kNaN;
    for (Index a : tets_[t]) node_q[sz(a)] += 0.25 * rest_[t].volume * q;
  }
  for (std::size_t a = 0; a < n; ++a) node_q[a] *= inv_node_volume_[a];

  std::vector<Index> pos(n, -1), nodes;
  Eigen::MatrixXd T, HT, Kloc;
  for (std::size_t t = 0; t < nt; ++t) {
    const Tet& tet = tets_[t];
    const TetRest& r = rest_[t];
    // The patch: every node of every tet sharing a node with t, sorted.
    nodes.clear();
    for (Index a : tet)
      for (Index k = node_adj_start_[sz(a)]; k < node_adj_start_[sz(a) + 1]; ++k)
        nodes.push_back(node_adj_[sz(k)]);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    for (std::size_t i = 0; i < nodes.size(); ++i) pos[sz(nodes[i])] = static_cast<Index>(i);
    const Eigen::Index m3 = 3 * static_cast<Eigen::Index>(nodes.size());

    // T: rows 0..8 d(vec F_e)/dU (row-major vec), row 9 dJbar_e/dU.
    T.setZero(10, m3);
    for (int p = 0; p < 4; ++p) {
      const Eigen::Index c = 3 * pos[sz(tet[sz(p)])];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) T(3 * i + j, c + i) = r.grad[sz(p)][j];
    }
    for (Index a : tet) {
      const double wa = 0.25 * inv_node_volume_[sz(a)];
      for (Index k = node_tet_start_[sz(a)]; k < node_tet_start_[sz(a) + 1]; ++k) {
        const std::size_t e = sz(node_tets_[sz(k)]);
        const double w = wa * rest_[e].volume;
        for (int p = 0; p < 4; ++p)
          T.block<1, 3>(9, 3 * pos[sz(tets_[e][sz(p)])]) += w * (cof[e] * rest_[e].grad[sz(p)]).transpose();
      }
    }
    const Mat3 F = Mat3::Identity() + grad(static_cast<Index>(t), u);
    HT.noalias() = (r.volume * hessian_of(states[t], F)) * T;
    Kloc.noalias() = T.transpose() * HT;
    // pi_e d^2 J_e: entry (p i, q j) = pi J (h_p[i] h_q[j] - h_p[j] h_q[i]), h_p = F^-T a_p.
    const double pi =
        r.volume * (node_q[sz(tet[0])] + node_q[sz(tet[1])] + node_q[sz(tet[2])] + node_q[sz(tet[3])]);
    const double piJ = pi * tet_j[t];
    const Mat3 FinvT = cof[t] / tet_j[t];
    for (int p = 0; p < 4; ++p) {
      const Vec3 hp = FinvT * r.grad[sz(p)];
      const Eigen::Index cp = 3 * pos[sz(tet[sz(p)])];
      for (int qn = 0; qn < 4; ++qn) {
        const Vec3 hq = FinvT * r.grad[sz(qn)];
        const Eigen::Index cq = 3 * pos[sz(tet[sz(qn)])];
        Kloc.block<3, 3>(cp, cq) += piJ * (hp * hq.transpose() - hq * hp.transpose());
      }
    }
    scatter(nodes, Kloc, values);
    for (Index x : nodes) pos[sz(x)] = -1;
  }
}

}  // namespace tmlab::tm
