// HyperelasticP2: the F-based total-Lagrangian quadratic (10-node) tetrahedron for any hyperelastic
// Law, on a QuadraticMesh (core/mesh/quadratic_mesh.hpp; VTK node order). At each of the 14
// quadrature points q of the rule of p2_quadrature.hpp (deal.II's QGaussSimplex<3>(3), the rule of the
// deal.II P2 reference), with the rest shape-function gradients g_a = grad N_a(X_q) and weight
// w_q = (rule weight) |det dX/dxi| precomputed:
//
//   F_q = I + sum_{a=1..9} (U_a - U_0) (x) g_a      (relative form: exact, sum_a g_a = 0)
//   E_q = (F^T F - I)/2,  S_q, D_q from the law
//   W_T = sum_q w_q W(E_q),  f_a = sum_q w_q F_q S_q g_a
//   K_ab = sum_q w_q [ (g_a . S_q g_b) I + B_a^T D_q B_b ]   (B_a as in hyperelastic_tl.hpp)
//
// Volumetric option "mean_dilatation" (F-bar with one dilatation per element, for nu above ~0.49 where
// the displacement P2 element still locks): Jbar = sum_q w_q J_q / sum_q w_q, J_q = det F_q, and the law
// sees Fbar_q = (Jbar/J_q)^{1/3} F_q at every point: W_T = sum_q w_q W(Ebar_q). The force is its exact
// gradient and the tangent its exact Hessian (element-local: Jbar couples only the element's own
// nodes, so the pattern is that of plain P2); derivation in hyperelastic_p2.cpp. On an affine field
// J_q = Jbar and Fbar = F: the variants agree on homogeneous states.
//
// Outside the law's domain. Standard St VK is evaluated for every F (as HyperelasticTL). For every
// other law, and for St VK with mean dilatation (which needs J_q > 0 for (Jbar/J_q)^{1/3}), a tet
// with det F_q <= 0 at some point has energy +inf and NaN force and tangent entries.
//
// The per-point law is a template parameter of the element kernels (PointLaw: (t, q, E, W*, S*, D*)
// -> false outside its domain) so the viscoelastic model (viscoelastic_law_p2.hpp) runs the same
// element code with its trial stress at each point.
#pragma once

#include "core/mesh/quadratic_mesh.hpp"
#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/kernels/p2_quadrature.hpp"
#include "tensormass/kernels/tangent_pattern.hpp"
#include "tensormass/materials/law.hpp"

#include <Eigen/LU>

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace tmlab::tm {

struct P2Options {
  enum class Volumetric { Standard, MeanDilatation };
  Volumetric volumetric = Volumetric::Standard;

  /// "standard" | "mean_dilatation"; throws tmlab::Error naming the accepted values.
  static Volumetric parse_volumetric(const std::string& s);
  static std::string to_string(Volumetric v);
};

class HyperelasticP2 : public ElasticModel {
 public:
  static constexpr int kNodes = 10;
  static constexpr int kPoints = P2Quadrature::kPoints;
  using Mat3x10 = Eigen::Matrix<double, 3, kNodes>;
  using Mat30 = Eigen::Matrix<double, 3 * kNodes, 3 * kNodes>;
  using Vec30 = Eigen::Matrix<double, 3 * kNodes, 1>;
  /// Rest data of one quadrature point of one tet.
  struct PointRest {
    double weight = 0.0;          ///< w_q = rule weight times |det dX/dxi|, m^3
    std::array<Vec3, 10> grad{};  ///< g_a = grad N_a at the point, rest configuration, 1/m
  };
  /// The law's view of a tet: the deformation gradient each point's law sees (F_q, or Fbar_q with
  /// mean dilatation) and the kinematic quantities the mean-dilatation derivatives need.
  struct TetKinematics {
    std::array<Mat3, kPoints> F{};   ///< F_q
    std::array<Mat3, kPoints> Fe{};  ///< the law's F: F_q or Fbar_q
    std::array<double, kPoints> J{};
    double Jbar = 1.0;
    bool in_domain = true;
  };

  /// Copies the connectivity, computes the rest data per point and the P2 tangent pattern; throws
  /// tmlab::Error naming a tet with a non-positive Jacobian at a point or a missing node.
  HyperelasticP2(const QuadraticMesh& mesh, Law law, P2Options options = {});

  Index num_nodes() const override { return num_nodes_; }
  Index num_tets() const { return static_cast<Index>(tets_.size()); }
  int num_points_per_tet() const { return kPoints; }
  const P2Quadrature& quadrature() const { return rule_; }
  const Law& law() const { return law_; }
  const P2Options& options() const { return options_; }
  bool mean_dilatation() const { return options_.volumetric == P2Options::Volumetric::MeanDilatation; }
  const std::vector<Tet10>& tets() const { return tets_; }
  const PointRest& point(Index t, int q) const { return rest_[kPoints * static_cast<std::size_t>(t) + q]; }
  /// Rest volume sum_q w_q of tet t.
  double tet_volume(Index t) const { return volume_[static_cast<std::size_t>(t)]; }
  const TangentPattern& pattern() const { return pattern_; }

  double energy(const VecX& u) const override;
  void internal_force(const VecX& u, VecX& f) const override;
  /// Matrix-free: pointwise dP for the standard element, the element matrix times v_e with mean dilatation.
  void tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const override;
  void tangent(const VecX& u, SpMat& K) const override;

  // ---- per tet and point ----
  /// grad u = sum_a (U_a - U_0) (x) g_a at point q of tet t.
  Mat3 displacement_gradient(Index t, int q, const VecX& u) const;
  /// F_q of point q alone, accumulated from I as kinematics() does (the same value as its F[q], bit
  /// for bit, at a fourteenth of the cost).
  Mat3 point_deformation_gradient(Index t, int q, const VecX& u) const;
  /// F = I + grad u at point q of tet t (the displacement's own F, not Fbar).
  Mat3 deformation_gradient(Index t, int q, const VecX& u) const {
    return Mat3::Identity() + displacement_gradient(t, q, u);
  }
  /// F_q, J_q and (with mean dilatation) Jbar and Fbar_q of tet t; in_domain false when the law
  /// cannot be evaluated (see the header comment).
  TetKinematics kinematics(Index t, const VecX& u) const;
  double tet_energy(Index t, const VecX& u) const;
  /// Column a = f_a of local node a.
  Mat3x10 tet_force(Index t, const VecX& u) const;
  /// d^2 W_T / dU^2, local node-major (row 3a + c).
  Mat30 tet_stiffness(Index t, const VecX& u) const;
  /// sum_q w_q S_q / V of tet t (S of the law's F at each point): the element's mean PK2 stress.
  Mat3 mean_pk2_stress(Index t, const VecX& u) const;
  /// sum_q w_q sigma_q / V, sigma = Fe S Fe^T / det Fe: the element's mean Cauchy stress (NaN outside the
  /// domain).
  Mat3 mean_cauchy_stress(Index t, const VecX& u) const;

  // ---- the element kernels for a general per-point law ----
  // PointLaw: bool operator()(Index t, int q, const Mat3& E, double* W, Mat3* S, Mat6* D) const
  // (pointers may be null; false: outside its domain).
  template <class PointLaw>
  double tet_energy_with(Index t, const VecX& u, const PointLaw& pl) const;
  template <class PointLaw>
  Mat3x10 tet_force_with(Index t, const VecX& u, const PointLaw& pl) const;
  template <class PointLaw>
  Mat30 tet_stiffness_with(Index t, const VecX& u, const PointLaw& pl) const;
  template <class PointLaw>
  Mat3x10 tet_tangent_apply_with(Index t, const VecX& u, const VecX& v, const PointLaw& pl) const;
  template <class PointLaw>
  double energy_with(const VecX& u, const PointLaw& pl) const;
  template <class PointLaw>
  void internal_force_with(const VecX& u, VecX& f, const PointLaw& pl) const;
  template <class PointLaw>
  void tangent_apply_with(const VecX& u, const VecX& v, VecX& Kv, const PointLaw& pl) const;
  template <class PointLaw>
  void tangent_with(const VecX& u, SpMat& K, const PointLaw& pl) const;

  /// The point law of the long-term Law (what the elastic model uses).
  struct LawPoint {
    const Law* law;
    bool operator()(Index, int, const Mat3& E, double* W, Mat3* S, Mat6* D) const {
      law->evaluate(E, W, S, D);
      return true;
    }
  };
  LawPoint law_point() const { return LawPoint{&law_}; }

 private:
  /// U_a - U_0 (a = 1..9) of tet t as columns 1..9 (column 0 zero).
  Mat3x10 relative_displacements(Index t, const VecX& u) const;
  void add_to(Index t, const Mat3x10& fe, VecX& f) const;
  /// The mean-dilatation element force and stiffness (K may be null) for a point law.
  template <class PointLaw>
  bool fbar_element(Index t, const TetKinematics& k, const PointLaw& pl, Vec30* f, Mat30* K) const;

  Index num_nodes_ = 0;
  std::vector<Tet10> tets_;
  P2Quadrature rule_;
  std::vector<PointRest> rest_;  ///< [t][q]
  std::vector<double> volume_;
  TangentPattern pattern_;
  Law law_;
  P2Options options_;
};

// ---------------------------------------------------------------------------------------------------
// Template definitions.

namespace p2_detail {

inline Mat3 green(const Mat3& F) { return 0.5 * (F.transpose() * F - Mat3::Identity()); }
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// The 6x30 map dU -> engineering dE at a point (column 3a+i = engineering(sym((F^T e_i) (x) g_a))).
inline Eigen::Matrix<double, 6, 30> strain_matrix(const Mat3& F, const std::array<Vec3, 10>& g) {
  Eigen::Matrix<double, 6, 30> B;
  for (int a = 0; a < 10; ++a) {
    const Vec3& ga = g[static_cast<std::size_t>(a)];
    for (int i = 0; i < 3; ++i) {
      const Vec3 h = F.row(i).transpose();
      B(0, 3 * a + i) = h[0] * ga[0];
      B(1, 3 * a + i) = h[1] * ga[1];
      B(2, 3 * a + i) = h[2] * ga[2];
      B(3, 3 * a + i) = h[0] * ga[1] + h[1] * ga[0];
      B(4, 3 * a + i) = h[0] * ga[2] + h[2] * ga[0];
      B(5, 3 * a + i) = h[1] * ga[2] + h[2] * ga[1];
    }
  }
  return B;
}

/// dP/dF as a 9x9 matrix on row-major vec (index 3i+J): A = delta_ik S_JL + F_iM F_kN D_MJNL.
Eigen::Matrix<double, 9, 9> first_elasticity(const Mat3& F, const Mat3& S, const Mat6& D);

}  // namespace p2_detail

template <class PointLaw>
double HyperelasticP2::tet_energy_with(Index t, const VecX& u, const PointLaw& pl) const {
  const TetKinematics k = kinematics(t, u);
  if (!k.in_domain) return p2_detail::kInf;
  double w = 0.0;
  for (int q = 0; q < kPoints; ++q) {
    double Wq = 0.0;
    if (!pl(t, q, p2_detail::green(k.Fe[static_cast<std::size_t>(q)]), &Wq, nullptr, nullptr))
      return p2_detail::kInf;
    w += point(t, q).weight * Wq;
  }
  return w;
}

template <class PointLaw>
HyperelasticP2::Mat3x10 HyperelasticP2::tet_force_with(Index t, const VecX& u, const PointLaw& pl) const {
  const TetKinematics k = kinematics(t, u);
  Mat3x10 fe = Mat3x10::Zero();
  if (!k.in_domain) return Mat3x10::Constant(p2_detail::kNaN);
  if (mean_dilatation()) {
    Vec30 f;
    if (!fbar_element(t, k, pl, &f, nullptr)) return Mat3x10::Constant(p2_detail::kNaN);
    for (int a = 0; a < kNodes; ++a) fe.col(a) = f.segment<3>(3 * a);
    return fe;
  }
  for (int q = 0; q < kPoints; ++q) {
    const PointRest& r = point(t, q);
    const Mat3& F = k.F[static_cast<std::size_t>(q)];
    Mat3 S;
    if (!pl(t, q, p2_detail::green(F), nullptr, &S, nullptr)) return Mat3x10::Constant(p2_detail::kNaN);
    const Mat3 wP = r.weight * (F * S);
    for (int a = 0; a < kNodes; ++a) fe.col(a).noalias() += wP * r.grad[static_cast<std::size_t>(a)];
  }
  return fe;
}

template <class PointLaw>
HyperelasticP2::Mat30 HyperelasticP2::tet_stiffness_with(Index t, const VecX& u, const PointLaw& pl) const {
  const TetKinematics k = kinematics(t, u);
  if (!k.in_domain) return Mat30::Constant(p2_detail::kNaN);
  Mat30 K = Mat30::Zero();
  if (mean_dilatation()) {
    if (!fbar_element(t, k, pl, nullptr, &K)) return Mat30::Constant(p2_detail::kNaN);
    return K;
  }
  for (int q = 0; q < kPoints; ++q) {
    const PointRest& r = point(t, q);
    const Mat3& F = k.F[static_cast<std::size_t>(q)];
    Mat3 S;
    Mat6 D;
    if (!pl(t, q, p2_detail::green(F), nullptr, &S, &D)) return Mat30::Constant(p2_detail::kNaN);
    const Eigen::Matrix<double, 6, 30> B = p2_detail::strain_matrix(F, r.grad);
    K.noalias() += r.weight * (B.transpose() * D * B);
    for (int a = 0; a < kNodes; ++a) {
      const Vec3 Sga = r.weight * (S * r.grad[static_cast<std::size_t>(a)]);
      for (int b = 0; b < kNodes; ++b)
        K.block<3, 3>(3 * a, 3 * b).diagonal().array() += Sga.dot(r.grad[static_cast<std::size_t>(b)]);
    }
  }
  return K;
}

template <class PointLaw>
HyperelasticP2::Mat3x10 HyperelasticP2::tet_tangent_apply_with(Index t, const VecX& u, const VecX& v,
                                                               const PointLaw& pl) const {
  if (mean_dilatation()) {
    const Mat30 K = tet_stiffness_with(t, u, pl);
    Vec30 ve;
    const Tet10& tet = tets_[static_cast<std::size_t>(t)];
    for (int a = 0; a < kNodes; ++a)
      ve.segment<3>(3 * a) = v.segment<3>(3 * static_cast<Eigen::Index>(tet[static_cast<std::size_t>(a)]));
    const Vec30 kv = K.lazyProduct(ve);
    Mat3x10 out;
    for (int a = 0; a < kNodes; ++a) out.col(a) = kv.segment<3>(3 * a);
    return out;
  }
  const TetKinematics k = kinematics(t, u);
  if (!k.in_domain) return Mat3x10::Constant(p2_detail::kNaN);
  const Mat3x10 dU = relative_displacements(t, v);
  Mat3x10 out = Mat3x10::Zero();
  for (int q = 0; q < kPoints; ++q) {
    const PointRest& r = point(t, q);
    const Mat3& F = k.F[static_cast<std::size_t>(q)];
    Mat3 S;
    Mat6 D;
    if (!pl(t, q, p2_detail::green(F), nullptr, &S, &D)) return Mat3x10::Constant(p2_detail::kNaN);
    Mat3 dF = Mat3::Zero();
    for (int a = 1; a < kNodes; ++a)
      dF.noalias() += dU.col(a) * r.grad[static_cast<std::size_t>(a)].transpose();
    const Mat3 FtdF = F.transpose() * dF;
    const Mat3 dP = r.weight * (dF * S + F * apply_tangent(D, 0.5 * (FtdF + FtdF.transpose())));
    for (int a = 0; a < kNodes; ++a) out.col(a).noalias() += dP * r.grad[static_cast<std::size_t>(a)];
  }
  return out;
}

template <class PointLaw>
double HyperelasticP2::energy_with(const VecX& u, const PointLaw& pl) const {
  double w = 0.0;
  for (Index t = 0; t < num_tets(); ++t) w += tet_energy_with(t, u, pl);
  return w;
}

template <class PointLaw>
void HyperelasticP2::internal_force_with(const VecX& u, VecX& f, const PointLaw& pl) const {
  f.setZero(num_dofs());
  for (Index t = 0; t < num_tets(); ++t) add_to(t, tet_force_with(t, u, pl), f);
}

template <class PointLaw>
void HyperelasticP2::tangent_apply_with(const VecX& u, const VecX& v, VecX& Kv, const PointLaw& pl) const {
  Kv.setZero(num_dofs());
  for (Index t = 0; t < num_tets(); ++t) add_to(t, tet_tangent_apply_with(t, u, v, pl), Kv);
}

template <class PointLaw>
void HyperelasticP2::tangent_with(const VecX& u, SpMat& K, const PointLaw& pl) const {
  if (!pattern_.matches(K))
    pattern_.reset(K);
  else
    std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
  double* values = K.valuePtr();
  for (Index t = 0; t < num_tets(); ++t)
    pattern_.scatter(t, tets_[static_cast<std::size_t>(t)], tet_stiffness_with(t, u, pl), values);
}

// Mean dilatation (F-bar, one Jbar per element). With b_q = d(ln J_q)/dU (b_q[3a+i] = (F_q^{-T} g_a)_i),
// jb = d(ln Jbar)/dU = sum_q w_q J_q b_q / (V Jbar), l_q = d(ln alpha_q)/dU = (jb - b_q)/3,
// alpha_q = (Jbar/J_q)^{1/3}, G_q = dFbar_q/dU = alpha_q (B_q + vec(F_q) l_q^T) (B_q: dU -> vec dF_q):
//   f = sum_q w_q G_q^T vec(Pbar_q),   Pbar = Fbar S(Ebar)
//   K = sum_q w_q [ G_q^T A_q G_q + alpha_q (m_q l_q^T + l_q m_q^T) + alpha_q (Pbar_q : F_q)(l_q l_q^T + H_q)
//   ]
// with A_q = dPbar/dFbar, m_q = B_q^T vec(Pbar_q) and H_q = d^2(ln alpha_q)/dU^2 = (Hbar - HJ_q)/3,
// HJ_q = B_q^T L_q B_q (L_q: d^2 ln J = -tr(F^-1 dF F^-1 dF)),
// Hbar = sum_q w_q J_q (b_q b_q^T + HJ_q) / (V Jbar) - jb jb^T.
template <class PointLaw>
bool HyperelasticP2::fbar_element(Index t, const TetKinematics& k, const PointLaw& pl, Vec30* f,
                                  Mat30* K) const {
  using Mat9x30 = Eigen::Matrix<double, 9, 30>;
  using Mat9 = Eigen::Matrix<double, 9, 9>;
  using Vec9 = Eigen::Matrix<double, 9, 1>;
  const double V = tet_volume(t);
  std::array<Mat9x30, kPoints> Bq;
  std::array<Vec30, kPoints> b;
  std::array<Mat3, kPoints> Finv;
  Vec30 jb = Vec30::Zero();
  for (int q = 0; q < kPoints; ++q) {
    const auto qs = static_cast<std::size_t>(q);
    const PointRest& r = point(t, q);
    Finv[qs] = k.F[qs].inverse();
    Mat9x30& B = Bq[qs];
    B.setZero();
    for (int a = 0; a < kNodes; ++a)
      for (int i = 0; i < 3; ++i)
        for (int J = 0; J < 3; ++J) B(3 * i + J, 3 * a + i) = r.grad[static_cast<std::size_t>(a)][J];
    for (int a = 0; a < kNodes; ++a)
      b[qs].segment<3>(3 * a) = Finv[qs].transpose() * r.grad[static_cast<std::size_t>(a)];
    jb.noalias() += (r.weight * k.J[qs]) * b[qs];
  }
  jb /= V * k.Jbar;
  if (f) f->setZero();
  if (K) K->setZero();
  Mat30 Hbar = Mat30::Zero();
  std::array<Mat30, kPoints> HJ;
  if (K) {
    for (int q = 0; q < kPoints; ++q) {
      const auto qs = static_cast<std::size_t>(q);
      Mat9 L;
      for (int i = 0; i < 3; ++i)
        for (int J = 0; J < 3; ++J)
          for (int kk = 0; kk < 3; ++kk)
            for (int l = 0; l < 3; ++l) L(3 * i + J, 3 * kk + l) = -Finv[qs](J, kk) * Finv[qs](l, i);
      HJ[qs].noalias() = Bq[qs].transpose() * L * Bq[qs];
      Hbar.noalias() += (point(t, q).weight * k.J[qs]) * (b[qs] * b[qs].transpose() + HJ[qs]);
    }
    Hbar /= V * k.Jbar;
    Hbar.noalias() -= jb * jb.transpose();
  }
  for (int q = 0; q < kPoints; ++q) {
    const auto qs = static_cast<std::size_t>(q);
    const double w = point(t, q).weight;
    const Mat3& Fe = k.Fe[qs];
    const double alpha = std::cbrt(k.Jbar / k.J[qs]);
    Mat3 S;
    Mat6 D;
    if (!pl(t, q, p2_detail::green(Fe), nullptr, &S, K ? &D : nullptr)) return false;
    const Mat3 P = Fe * S;
    Vec9 vecP, vecF;
    for (int i = 0; i < 3; ++i)
      for (int J = 0; J < 3; ++J) {
        vecP[3 * i + J] = P(i, J);
        vecF[3 * i + J] = k.F[qs](i, J);
      }
    const Vec30 l = (jb - b[qs]) / 3.0;
    const Mat9x30 G = alpha * (Bq[qs] + vecF * l.transpose());
    if (f) f->noalias() += w * G.transpose().lazyProduct(vecP);
    if (K) {
      const Mat9 A = p2_detail::first_elasticity(Fe, S, D);
      const Vec30 m = Bq[qs].transpose().lazyProduct(vecP);
      const double PF = vecP.dot(vecF);
      K->noalias() += w * (G.transpose() * A * G);
      K->noalias() += (w * alpha) * (m * l.transpose() + l * m.transpose());
      K->noalias() += (w * alpha * PF) * (l * l.transpose() + (Hbar - HJ[qs]) / 3.0);
    }
  }
  return true;
}

}  // namespace tmlab::tm
