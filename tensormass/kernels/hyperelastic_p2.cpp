// The F-based total-Lagrangian 10-node tet for any hyperelastic law; equations in hyperelastic_p2.hpp.
#include "tensormass/kernels/hyperelastic_p2.hpp"

#include "core/base/error.hpp"
#include "tensormass/kernels/tet_geometry.hpp"

#include <cassert>

namespace tmlab::tm {

P2Options::Volumetric P2Options::parse_volumetric(const std::string& s) {
  if (s == "standard") return Volumetric::Standard;
  if (s == "mean_dilatation") return Volumetric::MeanDilatation;
  throw Error("P2 volumetric option '" + s + "' is not one of \"standard\", \"mean_dilatation\"");
}

std::string P2Options::to_string(Volumetric v) {
  return v == Volumetric::Standard ? "standard" : "mean_dilatation";
}

namespace p2_detail {

Eigen::Matrix<double, 9, 9> first_elasticity(const Mat3& F, const Mat3& S, const Mat6& D) {
  // Voigt position of the index pair (M, J)
  constexpr int v[3][3] = {{0, 3, 4}, {3, 1, 5}, {4, 5, 2}};
  // FD(i, J, N, L) = sum_M F_iM D_MJNL, then A(iJ, kL) = delta_ik S_JL + sum_N F_kN FD(i, J, N, L)
  double FD[3][3][3][3];
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int N = 0; N < 3; ++N)
        for (int L = 0; L < 3; ++L) {
          double s = 0.0;
          for (int M = 0; M < 3; ++M) s += F(i, M) * D(v[M][J], v[N][L]);
          FD[i][J][N][L] = s;
        }
  Eigen::Matrix<double, 9, 9> A;
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          double s = (i == k) ? S(J, L) : 0.0;
          for (int N = 0; N < 3; ++N) s += F(k, N) * FD[i][J][N][L];
          A(3 * i + J, 3 * k + L) = s;
        }
  return A;
}

}  // namespace p2_detail

HyperelasticP2::HyperelasticP2(const QuadraticMesh& mesh, Law law, P2Options options)
    : num_nodes_(mesh.num_points()),
      tets_(mesh.tets),
      rule_(p2_quadrature()),
      law_(std::move(law)),
      options_(options) {
  const std::size_t nt = tets_.size();
  rest_.resize(kPoints * nt);
  volume_.assign(nt, 0.0);
  std::array<std::array<Vec3, 10>, kPoints> ref_grad;
  for (int q = 0; q < kPoints; ++q)
    ref_grad[static_cast<std::size_t>(q)] = p2_shape_gradients(rule_.points[static_cast<std::size_t>(q)]);
  for (std::size_t t = 0; t < nt; ++t) {
    const Tet10& tet = tets_[t];
    const std::string name = "quadratic tet " + std::to_string(t);
    for (Index n : tet)
      if (n < 0 || n >= num_nodes_)
        throw Error(name + " references node " + std::to_string(n) + " outside the mesh's " +
                    std::to_string(num_nodes_) + " points");
    // the vertex tet first: inverted, flat or degenerate tets named as for P1
    (void)tet_rest(
        mesh.points[static_cast<std::size_t>(tet[0])], mesh.points[static_cast<std::size_t>(tet[1])],
        mesh.points[static_cast<std::size_t>(tet[2])], mesh.points[static_cast<std::size_t>(tet[3])], name);
    for (int q = 0; q < kPoints; ++q) {
      const auto& G = ref_grad[static_cast<std::size_t>(q)];
      Mat3 Jac = Mat3::Zero();  // dX/dxi
      for (int a = 0; a < kNodes; ++a)
        Jac.noalias() += mesh.points[static_cast<std::size_t>(tet[static_cast<std::size_t>(a)])] *
                         G[static_cast<std::size_t>(a)].transpose();
      const double det = Jac.determinant();
      if (!(det > 0.0))
        throw Error(name + ": non-positive Jacobian " + std::to_string(det) + " at quadrature point " +
                    std::to_string(q) + " (misplaced midside node?)");
      const Mat3 JinvT = Jac.inverse().transpose();
      PointRest& r = rest_[kPoints * t + static_cast<std::size_t>(q)];
      r.weight = rule_.weights[static_cast<std::size_t>(q)] * det;
      for (int a = 0; a < kNodes; ++a)
        r.grad[static_cast<std::size_t>(a)] = JinvT * G[static_cast<std::size_t>(a)];
      volume_[t] += r.weight;
    }
  }
  pattern_ = TangentPattern(num_nodes_, tets_);
}

HyperelasticP2::Mat3x10 HyperelasticP2::relative_displacements(Index t, const VecX& u) const {
  assert(u.size() == num_dofs());
  const Tet10& tet = tets_[static_cast<std::size_t>(t)];
  const Vec3 u0 = u.segment<3>(3 * static_cast<Eigen::Index>(tet[0]));
  Mat3x10 U;
  U.col(0).setZero();
  for (int a = 1; a < kNodes; ++a)
    U.col(a) = u.segment<3>(3 * static_cast<Eigen::Index>(tet[static_cast<std::size_t>(a)])) - u0;
  return U;
}

void HyperelasticP2::add_to(Index t, const Mat3x10& fe, VecX& f) const {
  const Tet10& tet = tets_[static_cast<std::size_t>(t)];
  for (int a = 0; a < kNodes; ++a)
    f.segment<3>(3 * static_cast<Eigen::Index>(tet[static_cast<std::size_t>(a)])) += fe.col(a);
}

Mat3 HyperelasticP2::displacement_gradient(Index t, int q, const VecX& u) const {
  const Mat3x10 U = relative_displacements(t, u);
  const PointRest& r = point(t, q);
  Mat3 H = Mat3::Zero();
  for (int a = 1; a < kNodes; ++a) H.noalias() += U.col(a) * r.grad[static_cast<std::size_t>(a)].transpose();
  return H;
}

Mat3 HyperelasticP2::point_deformation_gradient(Index t, int q, const VecX& u) const {
  const Mat3x10 U = relative_displacements(t, u);
  const PointRest& r = point(t, q);
  Mat3 F = Mat3::Identity();
  for (int a = 1; a < kNodes; ++a) F.noalias() += U.col(a) * r.grad[static_cast<std::size_t>(a)].transpose();
  return F;
}

HyperelasticP2::TetKinematics HyperelasticP2::kinematics(Index t, const VecX& u) const {
  TetKinematics k;
  const Mat3x10 U = relative_displacements(t, u);
  const bool fbar = mean_dilatation();
  const bool need_positive = fbar || !law_.is_stvk();
  double wJ = 0.0;
  for (int q = 0; q < kPoints; ++q) {
    const auto qs = static_cast<std::size_t>(q);
    const PointRest& r = point(t, q);
    Mat3 F = Mat3::Identity();
    for (int a = 1; a < kNodes; ++a)
      F.noalias() += U.col(a) * r.grad[static_cast<std::size_t>(a)].transpose();
    k.F[qs] = F;
    k.J[qs] = F.determinant();
    if (need_positive && !(k.J[qs] > 0.0)) k.in_domain = false;
    wJ += r.weight * k.J[qs];
  }
  if (!fbar) {
    k.Fe = k.F;
    return k;
  }
  k.Jbar = wJ / tet_volume(t);
  if (!k.in_domain) {
    k.Fe.fill(Mat3::Constant(p2_detail::kNaN));
    return k;
  }
  for (std::size_t q = 0; q < static_cast<std::size_t>(kPoints); ++q)
    k.Fe[q] = std::cbrt(k.Jbar / k.J[q]) * k.F[q];
  return k;
}

double HyperelasticP2::tet_energy(Index t, const VecX& u) const { return tet_energy_with(t, u, law_point()); }
HyperelasticP2::Mat3x10 HyperelasticP2::tet_force(Index t, const VecX& u) const {
  return tet_force_with(t, u, law_point());
}
HyperelasticP2::Mat30 HyperelasticP2::tet_stiffness(Index t, const VecX& u) const {
  return tet_stiffness_with(t, u, law_point());
}

double HyperelasticP2::energy(const VecX& u) const {
  assert(u.size() == num_dofs());
  return energy_with(u, law_point());
}

void HyperelasticP2::internal_force(const VecX& u, VecX& f) const {
  assert(u.size() == num_dofs());
  internal_force_with(u, f, law_point());
}

void HyperelasticP2::tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const {
  assert(u.size() == num_dofs() && v.size() == num_dofs());
  tangent_apply_with(u, v, Kv, law_point());
}

void HyperelasticP2::tangent(const VecX& u, SpMat& K) const {
  assert(u.size() == num_dofs());
  tangent_with(u, K, law_point());
}

Mat3 HyperelasticP2::mean_pk2_stress(Index t, const VecX& u) const {
  const TetKinematics k = kinematics(t, u);
  if (!k.in_domain) return Mat3::Constant(p2_detail::kNaN);
  Mat3 s = Mat3::Zero();
  for (int q = 0; q < kPoints; ++q)
    s += point(t, q).weight * law_.pk2_stress(p2_detail::green(k.Fe[static_cast<std::size_t>(q)]));
  return s / tet_volume(t);
}

Mat3 HyperelasticP2::mean_cauchy_stress(Index t, const VecX& u) const {
  const TetKinematics k = kinematics(t, u);
  if (!k.in_domain) return Mat3::Constant(p2_detail::kNaN);
  Mat3 s = Mat3::Zero();
  for (int q = 0; q < kPoints; ++q) {
    const Mat3& Fe = k.Fe[static_cast<std::size_t>(q)];
    const double J = Fe.determinant();
    if (!(J > 0.0)) return Mat3::Constant(p2_detail::kNaN);
    s += (point(t, q).weight / J) * (Fe * law_.pk2_stress(p2_detail::green(Fe)) * Fe.transpose());
  }
  return s / tet_volume(t);
}

}  // namespace tmlab::tm
