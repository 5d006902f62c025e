#include "tensormass/kernels/tl_oracle.hpp"

#include <cassert>

namespace tmlab::tm {

namespace {

inline Vec3 node_vec(const VecX& x, Index node) { return x.segment<3>(3 * static_cast<Eigen::Index>(node)); }

}  // namespace

TotalLagrangianStVK::TotalLagrangianStVK(const Mesh& mesh, const StVenantKirchhoff& material)
    : num_nodes_(mesh.num_points()), tets_(mesh.tets), rest_(compute_tet_rest(mesh)), material_(material) {}

Mat3 TotalLagrangianStVK::deformation_gradient(Index t, const VecX& u) const {
  assert(u.size() == num_dofs());
  const Tet& tet = tets_[static_cast<std::size_t>(t)];
  const TetRest& r = rest_[static_cast<std::size_t>(t)];
  // F = I + grad u, grad u = sum_j U_j (x) a_j
  Mat3 F = Mat3::Identity();
  for (int j = 0; j < 4; ++j) F.noalias() += node_vec(u, tet[j]) * r.grad[j].transpose();
  return F;
}

Mat3 TotalLagrangianStVK::green_strain(Index t, const VecX& u) const {
  const Mat3 F = deformation_gradient(t, u);
  return 0.5 * (F.transpose() * F - Mat3::Identity());  // seed eq. 1
}

double TotalLagrangianStVK::tet_energy(Index t, const VecX& u) const {
  return rest_[static_cast<std::size_t>(t)].volume * material_.energy_density(green_strain(t, u));
}

Mat34 TotalLagrangianStVK::tet_force_from_stress(Index t, const Mat3& F, const Mat3& S) const {
  const TetRest& r = rest_[static_cast<std::size_t>(t)];
  const Mat3 VP = r.volume * (F * S);  // V P, P = F S
  Mat34 f;
  for (int p = 0; p < 4; ++p) f.col(p) = VP * r.grad[p];  // f_p = V P a_p
  return f;
}

Mat34 TotalLagrangianStVK::tet_force(Index t, const VecX& u) const {
  const Mat3 F = deformation_gradient(t, u);
  const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
  return tet_force_from_stress(t, F, material_.pk2_stress(E));
}

Mat12 TotalLagrangianStVK::tet_stiffness(Index t, const VecX& u) const {
  const TetRest& r = rest_[static_cast<std::size_t>(t)];
  const Mat3 F = deformation_gradient(t, u);
  const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
  const Mat3 S = material_.pk2_stress(E);
  const Mat3 FFt = F * F.transpose();
  std::array<Vec3, 4> b;
  for (int p = 0; p < 4; ++p) b[p] = F * r.grad[p];
  const double lam = material_.lambda, mu = material_.mu;
  Mat12 K;
  for (int p = 0; p < 4; ++p) {
    for (int q = 0; q < 4; ++q) {
      // K_pq = V [ (a_p . S a_q) I + lambda b_p b_q^T + mu b_q b_p^T + mu (a_p . a_q) F F^T ]
      const double geo = r.grad[p].dot(S * r.grad[q]);
      const double apaq = r.grad[p].dot(r.grad[q]);
      K.block<3, 3>(3 * p, 3 * q) = r.volume * (geo * Mat3::Identity() + lam * b[p] * b[q].transpose() +
                                                mu * b[q] * b[p].transpose() + mu * apaq * FFt);
    }
  }
  return K;
}

double TotalLagrangianStVK::energy(const VecX& u) const {
  assert(u.size() == num_dofs());
  double w = 0.0;
  for (Index t = 0; t < num_tets(); ++t) w += tet_energy(t, u);
  return w;
}

void TotalLagrangianStVK::internal_force(const VecX& u, VecX& f) const {
  assert(u.size() == num_dofs());
  f.setZero(num_dofs());
  for (Index t = 0; t < num_tets(); ++t) {
    const Mat34 ft = tet_force(t, u);
    const Tet& tet = tets_[static_cast<std::size_t>(t)];
    for (int p = 0; p < 4; ++p) f.segment<3>(3 * static_cast<Eigen::Index>(tet[p])) += ft.col(p);
  }
}

void TotalLagrangianStVK::tangent_apply(const VecX& u, const VecX& v, VecX& Kv) const {
  assert(u.size() == num_dofs() && v.size() == num_dofs());
  Kv.setZero(num_dofs());
  for (Index t = 0; t < num_tets(); ++t) {
    const TetRest& r = rest_[static_cast<std::size_t>(t)];
    const Tet& tet = tets_[static_cast<std::size_t>(t)];
    const Mat3 F = deformation_gradient(t, u);
    const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
    const Mat3 S = material_.pk2_stress(E);
    // directional derivative: dF = sum_j V_j (x) a_j, dE = sym(F^T dF), dS = C : dE,
    // dP = dF S + F dS, d f_p = V dP a_p
    Mat3 dF = Mat3::Zero();
    for (int j = 0; j < 4; ++j) dF.noalias() += node_vec(v, tet[j]) * r.grad[j].transpose();
    const Mat3 FtdF = F.transpose() * dF;
    const Mat3 dE = 0.5 * (FtdF + FtdF.transpose());
    const Mat3 dP = dF * S + F * material_.tangent(dE);
    for (int p = 0; p < 4; ++p)
      Kv.segment<3>(3 * static_cast<Eigen::Index>(tet[p])) += r.volume * (dP * r.grad[p]);
  }
}

void TotalLagrangianStVK::tangent(const VecX& u, SpMat& K) const {
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(tets_.size() * 144);
  for (Index t = 0; t < num_tets(); ++t) {
    const Mat12 Kt = tet_stiffness(t, u);
    const Tet& tet = tets_[static_cast<std::size_t>(t)];
    for (int p = 0; p < 4; ++p)
      for (int q = 0; q < 4; ++q)
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            trip.emplace_back(3 * tet[p] + a, 3 * tet[q] + b, Kt(3 * p + a, 3 * q + b));
  }
  K.resize(num_dofs(), num_dofs());
  K.setFromTriplets(trip.begin(), trip.end());
  K.makeCompressed();
}

}  // namespace tmlab::tm
