#include "tensormass/system/lumped_mass.hpp"

#include "core/base/error.hpp"
#include "tensormass/kernels/p2_quadrature.hpp"
#include "tensormass/kernels/tet_geometry.hpp"

#include <Eigen/LU>

#include <array>
#include <cmath>

namespace tmlab::tm {

VecX lumped_node_mass(const Mesh& mesh, double density) {
  if (!(density > 0.0) || !std::isfinite(density))
    throw Error("density must be > 0 (got " + std::to_string(density) + ")");
  const std::vector<TetRest> rest = compute_tet_rest(mesh);  // throws naming an inverted tet
  VecX m = VecX::Zero(mesh.num_points());
  for (Index t = 0; t < mesh.num_tets(); ++t)
    for (Index n : mesh.tets[t]) m[n] += density * rest[t].volume / 4.0;
  return m;
}

VecX hrz_lumped_node_mass(const QuadraticMesh& mesh, double density) {
  if (!(density > 0.0) || !std::isfinite(density))
    throw Error("density must be > 0 (got " + std::to_string(density) + ")");
  const P2Quadrature rule = p2_quadrature();
  std::array<std::array<double, 10>, P2Quadrature::kPoints> N;
  std::array<std::array<Vec3, 10>, P2Quadrature::kPoints> G;
  for (std::size_t q = 0; q < N.size(); ++q) {
    N[q] = p2_shape_values(rule.points[q]);
    G[q] = p2_shape_gradients(rule.points[q]);
  }
  VecX m = VecX::Zero(mesh.num_points());
  for (Index t = 0; t < mesh.num_tets(); ++t) {
    const Tet10& tet = mesh.tets[static_cast<std::size_t>(t)];
    for (Index n : tet)
      if (n < 0 || n >= mesh.num_points())
        throw Error("quadratic tet " + std::to_string(t) + " references node " + std::to_string(n) +
                    " outside the mesh");
    std::array<double, 10> diag{};
    double volume = 0.0;
    for (std::size_t q = 0; q < N.size(); ++q) {
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      for (std::size_t a = 0; a < 10; ++a)
        J.noalias() += mesh.points[static_cast<std::size_t>(tet[a])] * G[q][a].transpose();
      const double det = J.determinant();
      if (!(det > 0.0))
        throw Error("quadratic tet " + std::to_string(t) + ": non-positive Jacobian at quadrature point " +
                    std::to_string(q));
      const double w = rule.weights[q] * det;
      volume += w;
      for (std::size_t a = 0; a < 10; ++a) diag[a] += w * N[q][a] * N[q][a];
    }
    double sum = 0.0;
    for (double d : diag) sum += d;
    for (std::size_t a = 0; a < 10; ++a) m[tet[a]] += density * volume * diag[a] / sum;
  }
  return m;
}

VecX lumped_dof_mass(const VecX& node_mass) {
  VecX m(3 * node_mass.size());
  for (Eigen::Index i = 0; i < node_mass.size(); ++i) m.segment<3>(3 * i).setConstant(node_mass[i]);
  return m;
}

}  // namespace tmlab::tm
