// Per-tet kinematics of a displacement: see cell_fields.hpp.
#include "runner/cell_fields.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cmath>
#include <cstddef>
#include <limits>

namespace tmlab::tm::runner {

std::pair<double, Index> min_volume_ratio(const Mesh& mesh, const VecX& u) {
  double jmin = std::numeric_limits<double>::infinity();
  Index where = -1;
  for (Index t = 0; t < mesh.num_tets(); ++t) {
    Vec3 x[4], X[4];
    for (int a = 0; a < 4; ++a) {
      X[a] = mesh.points[mesh.tets[t][a]];
      x[a] = X[a] + u.segment<3>(3 * mesh.tets[t][a]);
    }
    const double v0 = (X[1] - X[0]).dot((X[2] - X[0]).cross(X[3] - X[0]));
    const double v = (x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0]));
    const double j = v / v0;
    if (j < jmin) {
      jmin = j;
      where = t;
    }
  }
  return {jmin, where};
}

Eigen::Matrix3d quadratic_centroid_gradient(const QuadraticMesh& qm, Index t, const VecX& u) {
  // At the centroid (all L = 1/4) grad N = (4 L_a - 1) grad L_a = 0 for a vertex and
  // 4 (L_b grad L_a + L_a grad L_b) = grad L_a + grad L_b for the midside node of edge (a, b).
  const Tet10& tet = qm.tets[static_cast<std::size_t>(t)];
  Eigen::Matrix3d Dm;
  for (int k = 0; k < 3; ++k) Dm.col(k) = qm.points[tet[k + 1]] - qm.points[tet[0]];
  const Eigen::Matrix3d inv = Dm.inverse();  // rows: grad L_1, grad L_2, grad L_3
  Vec3 g[4];
  for (int k = 0; k < 3; ++k) g[k + 1] = inv.row(k).transpose();
  g[0] = -(g[1] + g[2] + g[3]);
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  for (std::size_t e = 0; e < 6; ++e) {
    const Vec3 grad = g[kTet10Edges[e][0]] + g[kTet10Edges[e][1]];
    F += u.segment<3>(3 * static_cast<Eigen::Index>(tet[4 + e])) * grad.transpose();
  }
  return F;
}

CellFields cell_fields(const Problem& p, const VecX& u) {
  const std::size_t n = p.mesh.tets.size();
  CellFields c{std::vector<double>(n), std::vector<double>(n), std::vector<Eigen::Matrix3d>(n),
               std::vector<Eigen::Matrix3d>(n)};
  for (Index t2 = 0; t2 < p.mesh.num_tets(); ++t2) {
    const Eigen::Matrix3d F = p.quadratic ? quadratic_centroid_gradient(*p.quadratic, t2, u)
                                          : p.fields_kernel.deformation_gradient(t2, u);
    const Eigen::Matrix3d E = 0.5 * (F.transpose() * F - Eigen::Matrix3d::Identity());
    const Eigen::Matrix3d S = p.law.pk2_stress(E);
    const double J = F.determinant();
    const Eigen::Matrix3d sigma = F * S * F.transpose() / J;
    const Eigen::Matrix3d dev = sigma - sigma.trace() / 3.0 * Eigen::Matrix3d::Identity();
    c.jratio[t2] = J;
    c.strain[t2] = E;
    c.cauchy[t2] = sigma;
    c.von_mises[t2] = std::sqrt(1.5 * dev.cwiseProduct(dev).sum());
  }
  return c;
}

}  // namespace tmlab::tm::runner
