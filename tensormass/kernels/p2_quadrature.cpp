// The 10-node tet's quadrature rule and shape functions; see p2_quadrature.hpp.
#include "tensormass/kernels/p2_quadrature.hpp"

#include "core/mesh/quadratic_mesh.hpp"

#include <algorithm>
#include <vector>

namespace tmlab::tm {

namespace {

/// Appends every distinct permutation of the barycentric point b (lexicographic order), with weight w.
void add_orbit(std::array<double, 4> b, double w, P2Quadrature& q, int& n) {
  std::sort(b.begin(), b.end());
  do {
    q.points[static_cast<std::size_t>(n)] = Vec3(b[0], b[1], b[2]);
    q.weights[static_cast<std::size_t>(n)] = (1.0 / 6.0) * w;  // as deal.II: volume * weight
    ++n;
  } while (std::next_permutation(b.begin(), b.end()));
}

}  // namespace

P2Quadrature p2_quadrature() {
  P2Quadrature q;
  int n = 0;
  // (a, a, a, 1 - 3a)
  const double a1 = 3.108859192633006e-01, w1 = 1.126879257180159e-01;
  add_orbit({a1, a1, a1, 1.0 - 3.0 * a1}, w1, q, n);
  const double a2 = 9.273525031089125e-02, w2 = 7.349304311636196e-02;
  add_orbit({a2, a2, a2, 1.0 - 3.0 * a2}, w2, q, n);
  // (a, a, (1 - 2a)/2, (1 - 2a)/2)
  const double a3 = 4.550370412564964e-02, w3 = 4.254602077708147e-02;
  const double b3 = (1.0 - 2.0 * a3) / 2.0;
  add_orbit({a3, a3, b3, b3}, w3, q, n);
  return q;
}

std::array<double, 10> p2_shape_values(const Vec3& xi) {
  const double L[4] = {1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
  std::array<double, 10> N{};
  for (int i = 0; i < 4; ++i) N[static_cast<std::size_t>(i)] = L[i] * (2.0 * L[i] - 1.0);
  for (std::size_t e = 0; e < 6; ++e) N[4 + e] = 4.0 * L[kTet10Edges[e][0]] * L[kTet10Edges[e][1]];
  return N;
}

std::array<Vec3, 10> p2_shape_gradients(const Vec3& xi) {
  const double L[4] = {1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
  const Vec3 dL[4] = {Vec3(-1.0, -1.0, -1.0), Vec3(1.0, 0.0, 0.0), Vec3(0.0, 1.0, 0.0), Vec3(0.0, 0.0, 1.0)};
  std::array<Vec3, 10> G{};
  for (int i = 0; i < 4; ++i) G[static_cast<std::size_t>(i)] = (4.0 * L[i] - 1.0) * dL[i];
  for (std::size_t e = 0; e < 6; ++e) {
    const int a = kTet10Edges[e][0], b = kTet10Edges[e][1];
    G[4 + e] = 4.0 * (L[b] * dL[a] + L[a] * dL[b]);
  }
  return G;
}

}  // namespace tmlab::tm
