// F-based total-Lagrangian P1 element for any hyperelastic law; equations in hyperelastic_tl.hpp.
#include "tensormass/kernels/hyperelastic_tl.hpp"

#include <cassert>
#include <limits>

namespace tmlab::tm {

namespace {

inline Vec3 node_vec(const VecX& x, Index node) { return x.segment<3>(3 * static_cast<Eigen::Index>(node)); }
inline Mat3 green(const Mat3& F) { return 0.5 * (F.transpose() * F - Mat3::Identity()); }
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

HyperelasticTL::HyperelasticTL(const Mesh& mesh, Law law)
    : num_nodes_(mesh.num_points()),
      tets_(mesh.tets),
      rest_(compute_tet_rest(mesh)),
      pattern_(num_nodes_, tets_),
      law_(std::move(law)) {}

Mat3 HyperelasticTL::displacement_gradient(Index t, const VecX& u) const {
  assert(u.size() == num_dofs());
  const Tet& tet = tets_[static_cast<std::size_t>(t)];
  const TetRest& r = rest_[static_cast<std::size_t>(t)];
  const Vec3 u0 = node_vec(u, tet[0]);
  Mat3 H = Mat3::Zero();
  for (int j = 1; j < 4; ++j) H.noalias() += (node_vec(u, tet[j]) - u0) * r.grad[j].transpose();
  return H;
}

double HyperelasticTL::tet_energy(Index t, const VecX& u) const {
  const Mat3 F = deformation_gradient(t, u);
  if (!in_domain(F)) return std::numeric_limits<double>::infinity();
  return rest_[static_cast<std::size_t>(t)].volume * law_.energy_density(green(F));
}

HyperelasticTL::Mat34 HyperelasticTL::tet_force_from_stress(Index t, const Mat3& F, const Mat3& S) const {
  const TetRest& r = rest_[static_cast<std::size_t>(t)];
  const Mat3 VP = r.volume * (F * S);  // V P, P = F S
  Mat34 f;
  for (int p = 0; p < 4; ++p) f.col(p) = VP * r.grad[p];
  return f;
}

HyperelasticTL::Mat34 HyperelasticTL::tet_force(Index t, const VecX& u) const {
  const Mat3 F = deformation_gradient(t, u);
  if (!in_domain(F)) return Mat34::Constant(kNaN);
  return tet_force_from_stress(t, F, law_.pk2_stress(green(F)));
}

HyperelasticTL::Mat12 HyperelasticTL::tet_stiffness_from(Index t, const Mat3& F, const Mat3& S,
                                                         const Mat6& D) const {
  const TetRest& r = rest_[static_cast<std::size_t>(t)];
  // B (6x12): column 3p+i = engineering(sym((F^T e_i) (x) a_p)), the strain of dU_p = e_i.
  Eigen::Matrix<double, 6, 12> B;
  for (int p = 0; p < 4; ++p) {
    const Vec3& a = r.grad[p];
    for (int i = 0; i < 3; ++i) {
      const Vec3 g = F.row(i).transpose();  // F^T e_i
      B(0, 3 * p + i) = g[0] * a[0];
      B(1, 3 * p + i) = g[1] * a[1];
      B(2, 3 * p + i) = g[2] * a[2];
      B(3, 3 * p + i) = g[0] * a[1] + g[1] * a[0];
      B(4, 3 * p + i) = g[0] * a[2] + g[2] * a[0];
      B(5, 3 * p + i) = g[1] * a[2] + g[2] * a[1];
    }
  }
  Mat12 K = B.transpose() * D * B;  // material stiffness
  for (int p = 0; p < 4; ++p) {
    const Vec3 Sap = S * r.grad[p];
    for (int q = 0; q < 4; ++q)
      K.block<3, 3>(3 * p, 3 * q).diagonal().array() += Sap.dot(r.grad[q]);  // geometric
  }
  return r.volume * K;
}

HyperelasticTL::Mat12 HyperelasticTL::tet_stiffness(Index t, const VecX& u) const {
  const Mat3 F = deformation_gradient(t, u);
  if (!in_domain(F)) return Mat12::Constant(kNaN);
  Mat3 S;
  Mat6 D;
  law_.evaluate(green(F), nullptr, &S, &D);
  return tet_stiffness_from(t, F, S, D);
}

double HyperelasticTL::energy(const VecX& u) const {
  assert(u.size() == num_dofs());
  double w = 0.0;
  for (Index t = 0; t < num_tets(); ++t) w += tet_energy(t, u);
  return w;
}

void HyperelasticTL::internal_force(const VecX& u, VecX& f) const {
  assert(u.size() == num_dofs());
  f.setZero(num_dofs());
  for (Index t = 0; t < num_tets(); ++t) {
    const Mat34 ft = tet_force(t, u);
    const Tet& tet = tets_[static_cast<std::size_t>(t)];
    for (int p = 0; p < 4; ++p) f.segment<3>(3 * static_cast<Eigen::Index>(tet[p])) += ft.col(p);
  }
}

void HyperelasticTL::tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const {
  assert(u.size() == num_dofs() && v.size() == num_dofs());
  Kv.setZero(num_dofs());
  for (Index t = 0; t < num_tets(); ++t) {
    const TetRest& r = rest_[static_cast<std::size_t>(t)];
    const Tet& tet = tets_[static_cast<std::size_t>(t)];
    const Mat3 F = deformation_gradient(t, u);
    Mat3 dP;
    if (in_domain(F)) {
      // dF = grad v, dE = sym(F^T dF), dS = D : dE, dP = dF S + F dS, d f_p = V dP a_p
      const Mat3 dF = displacement_gradient(t, v);
      Mat3 S;
      Mat6 D;
      law_.evaluate(green(F), nullptr, &S, &D);
      const Mat3 FtdF = F.transpose() * dF;
      dP = dF * S + F * apply_tangent(D, 0.5 * (FtdF + FtdF.transpose()));
    } else {
      dP.setConstant(kNaN);
    }
    for (int p = 0; p < 4; ++p)
      Kv.segment<3>(3 * static_cast<Eigen::Index>(tet[p])) += r.volume * (dP * r.grad[p]);
  }
}

void HyperelasticTL::tangent(const VecX& u, SpMat& K) const {
  assert(u.size() == num_dofs());
  if (!pattern_.matches(K))
    pattern_.reset(K);
  else
    std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
  double* values = K.valuePtr();
  for (Index t = 0; t < num_tets(); ++t)
    pattern_.scatter(t, tets_[static_cast<std::size_t>(t)], tet_stiffness(t, u), values);
}

}  // namespace tmlab::tm
