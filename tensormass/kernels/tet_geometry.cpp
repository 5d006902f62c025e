#include "tensormass/kernels/tet_geometry.hpp"

#include "core/base/error.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tmlab::tm {

TetRest tet_rest(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, const std::string& element) {
  Eigen::Matrix3d J;
  J.col(0) = p1 - p0;
  J.col(1) = p2 - p0;
  J.col(2) = p3 - p0;
  const double det = J.determinant();  // = 6V
  double lmax = 0.0;
  const std::array<Vec3, 4> p{p0, p1, p2, p3};
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) lmax = std::max(lmax, (p[j] - p[i]).norm());
  if (!std::isfinite(det) || det <= 0.0 || det < 1e-12 * lmax * lmax * lmax) {
    std::ostringstream os;
    os << element << ": ";
    if (!std::isfinite(det))
      os << "non-finite vertex coordinates";
    else if (det < 0.0)
      os << "inverted (negative rest volume V = " << det / 6.0 << ")";
    else
      os << "degenerate (rest volume V = " << det / 6.0 << ", longest edge " << lmax << ")";
    throw Error(os.str());
  }
  TetRest r;
  r.volume = det / 6.0;
  const Eigen::Matrix3d Jinv = J.inverse();
  // grad N_j for j = 1..3 are the rows of J^{-1}: N_j(X) = row_j(J^{-1}) (X - P0).
  r.grad[1] = Jinv.row(0).transpose();
  r.grad[2] = Jinv.row(1).transpose();
  r.grad[3] = Jinv.row(2).transpose();
  r.grad[0] = -(r.grad[1] + r.grad[2] + r.grad[3]);
  return r;
}

std::vector<TetRest> compute_tet_rest(const Mesh& mesh) {
  std::vector<TetRest> rest(mesh.tets.size());
  const Index n = mesh.num_points();
  for (Index t = 0; t < mesh.num_tets(); ++t) {
    const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
    for (Index v : tet) {
      if (v < 0 || v >= n) {
        std::ostringstream os;
        os << mesh.tet_name(t) << ": node index " << v << " out of range [0, " << n << ")";
        throw Error(os.str());
      }
    }
    const auto& P = mesh.points;
    rest[static_cast<std::size_t>(t)] =
        tet_rest(P[static_cast<std::size_t>(tet[0])], P[static_cast<std::size_t>(tet[1])],
                 P[static_cast<std::size_t>(tet[2])], P[static_cast<std::size_t>(tet[3])], mesh.tet_name(t));
  }
  return rest;
}

}  // namespace tmlab::tm
