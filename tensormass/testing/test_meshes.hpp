// Test helpers for the kernel tests: random tets, jittered Kuhn-split boxes (via
// tmlab::make_box_mesh), displacement fields (random, affine, rigid) and norm-wise relative errors.
#pragma once

#include "core/mesh/mesh.hpp"
#include "core/mesh/mesh_generator.hpp"

#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include <cmath>
#include <random>

namespace tmlab::tm::testing {

inline double uniform(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

inline Vec3 random_vec(std::mt19937& rng, double scale) {
  return Vec3(uniform(rng, -scale, scale), uniform(rng, -scale, scale), uniform(rng, -scale, scale));
}

/// One random, positively oriented tet of size ~`size` around `center`, quality bounded away from 0
/// (6V >= 0.05 * longest_edge^3).
inline std::array<Vec3, 4> random_tet_points(std::mt19937& rng, double size, const Vec3& center) {
  for (;;) {
    std::array<Vec3, 4> p;
    for (auto& x : p) x = center + random_vec(rng, size);
    Eigen::Matrix3d J;
    for (int j = 0; j < 3; ++j) J.col(j) = p[static_cast<std::size_t>(j + 1)] - p[0];
    double det = J.determinant();
    if (det < 0) {
      std::swap(p[1], p[2]);
      det = -det;
    }
    double lmax = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        lmax = std::max(lmax, (p[static_cast<std::size_t>(i)] - p[static_cast<std::size_t>(j)]).norm());
    if (det >= 0.05 * lmax * lmax * lmax) return p;
  }
}

/// `n` disconnected random tets (a "tet soup"), sizes ~`size`, spread over a box of side ~n^(1/3)*size.
inline Mesh random_tet_soup(int n, double size, std::mt19937& rng) {
  Mesh m;
  const double spread = 2.0 * size * std::cbrt(static_cast<double>(n));
  for (int t = 0; t < n; ++t) {
    const auto p = random_tet_points(rng, size, random_vec(rng, spread));
    Tet tet{};
    for (int j = 0; j < 4; ++j) {
      tet[static_cast<std::size_t>(j)] = m.num_points();
      m.points.push_back(p[static_cast<std::size_t>(j)]);
    }
    m.tets.push_back(tet);
  }
  return m;
}

/// Kuhn-split box [0, n h]^3 (6 tets per hex, tmlab::make_box_mesh) shifted by `origin`, with the
/// interior points moved randomly by up to `jitter * h` per axis (0 keeps the structured mesh).
inline Mesh jittered_box(int n, double h, double jitter, std::mt19937& rng,
                         const Vec3& origin = Vec3::Zero()) {
  Mesh m = make_box_mesh(origin, origin + Vec3::Constant(n * h), n, n, n);
  if (jitter > 0.0) {
    const double eps = 1e-9 * h;
    for (Vec3& p : m.points) {
      bool interior = true;
      for (int c = 0; c < 3; ++c)
        interior = interior && p(c) > origin(c) + eps && p(c) < origin(c) + n * h - eps;
      if (interior) p += random_vec(rng, jitter * h);
    }
  }
  return m;
}

inline Eigen::VectorXd random_displacement(Index num_nodes, double scale, std::mt19937& rng) {
  Eigen::VectorXd u(3 * num_nodes);
  for (Eigen::Index i = 0; i < u.size(); ++i) u(i) = uniform(rng, -scale, scale);
  return u;
}

/// The rigid-motion tests' problem: a jittered 6^3 box of 1 cm cells and a random displacement of
/// up to a tenth of a cell, drawn from `rng` in that order.
struct DeformedBox {
  double h = 0.01;  ///< cell size, metres
  Mesh mesh;
  Eigen::VectorXd u;
};

inline DeformedBox deformed_jittered_box(std::mt19937& rng) {
  DeformedBox b;
  b.mesh = jittered_box(6, b.h, 0.25, rng);
  b.u = random_displacement(b.mesh.num_points(), 0.1 * b.h, rng);
  return b;
}

/// u(X) = G X + c at every node.
inline Eigen::VectorXd affine_displacement(const Mesh& m, const Eigen::Matrix3d& G, const Vec3& c) {
  Eigen::VectorXd u(3 * m.num_points());
  for (Index i = 0; i < m.num_points(); ++i)
    u.segment<3>(3 * i) = G * m.points[static_cast<std::size_t>(i)] + c;
  return u;
}

/// The displacement that moves the deformed state X + u rigidly: x' = R (X + u) + t.
inline Eigen::VectorXd rigidly_moved(const Mesh& m, const Eigen::VectorXd& u, const Eigen::Matrix3d& R,
                                     const Vec3& t) {
  Eigen::VectorXd w(u.size());
  for (Index i = 0; i < m.num_points(); ++i) {
    const Vec3 X = m.points[static_cast<std::size_t>(i)];
    w.segment<3>(3 * i) = R * (X + u.segment<3>(3 * i)) + t - X;
  }
  return w;
}

inline Eigen::Matrix3d rotation(const Vec3& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

/// ||a - b|| / ||b|| (vectors or sparse matrices, Frobenius).
inline double rel_err(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).norm() / b.norm();
}
inline double rel_err(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  return Eigen::SparseMatrix<double>(a - b).norm() / b.norm();
}
inline double rel_err(double a, double b) { return std::abs(a - b) / std::abs(b); }

/// Mean edge length of a mesh.
inline double mean_edge(const Mesh& m) {
  double s = 0.0;
  long n = 0;
  for (const Tet& t : m.tets)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j, ++n)
        s += (m.points[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])] -
              m.points[static_cast<std::size_t>(t[static_cast<std::size_t>(j)])])
                 .norm();
  return s / static_cast<double>(n);
}

}  // namespace tmlab::tm::testing
