// Checks shared by the hyperelastic law tests (one test file per law, one executable): a set of
// deformations that includes compression to J = 0.3, large simple shear and equal principal
// stretches; fourth-order central differences of W (against S) and of S (against the tangent);
// the small-strain limit against linear elasticity; objectivity and isotropy.
#pragma once

#include "tensormass/materials/tensor_algebra.hpp"

#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace tmlab::tm::law_testing {

inline Mat3 green_strain(const Mat3& F) { return 0.5 * (F.transpose() * F - Mat3::Identity()); }

inline Mat3 random_sym(std::mt19937& rng, double s) {
  std::uniform_real_distribution<double> d(-s, s);
  Mat3 A;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) A(i, j) = d(rng);
  return 0.5 * (A + A.transpose());
}

inline Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized().toRotationMatrix();
}

/// A random F with det F = J (a random matrix near I, scaled).
inline Mat3 random_f(std::mt19937& rng, double J, double spread) {
  std::uniform_real_distribution<double> d(-spread, spread);
  for (;;) {
    Mat3 A = Mat3::Identity();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) A(i, j) += d(rng);
    const double det = A.determinant();
    if (det > 0.2) return std::cbrt(J / det) * A;
  }
}

struct Deformation {
  std::string name;
  Mat3 F;
};

/// The deformations every law is checked at.
inline std::vector<Deformation> deformations(std::mt19937& rng) {
  std::vector<Deformation> out;
  out.push_back({"identity", Mat3::Identity()});
  for (int k = 0; k < 3; ++k) {
    out.push_back({"random J=1", random_f(rng, 1.0, 0.4)});
    out.push_back({"random J=0.3 (compression)", random_f(rng, 0.3, 0.4)});
    out.push_back({"random J=1.6", random_f(rng, 1.6, 0.4)});
  }
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 1.5;  // simple shear, amount 1.5 (principal stretches 2.0 and 0.5)
  out.push_back({"simple shear 1.5", random_rotation(rng) * shear});
  out.push_back({"uniaxial compression J=0.3", Eigen::Vector3d(0.3, 1.0, 1.0).asDiagonal().toDenseMatrix()});
  out.push_back({"pure dilation J=0.3 (three equal stretches)", std::cbrt(0.3) * Mat3::Identity()});
  const Mat3 Q = random_rotation(rng);
  out.push_back({"two equal stretches (rotated)",
                 Q * Eigen::Vector3d(0.7, 0.7, 1.4).asDiagonal().toDenseMatrix() * Q.transpose()});
  out.push_back(
      {"two nearly equal stretches",
       Q * Eigen::Vector3d(0.8, 0.8 * (1.0 + 1e-9), 1.3).asDiagonal().toDenseMatrix() * Q.transpose()});
  return out;
}

/// Fourth-order central difference of f along t: (-f(2h) + 8 f(h) - 8 f(-h) + f(-2h)) / (12 h).
template <class F>
auto fd4(F&& f, double h) {
  return (-f(2 * h) + 8.0 * f(h) - 8.0 * f(-h) + f(-2 * h)) / (12.0 * h);
}

/// S = dW/dE and dS = D : dE (both the directional tangent and the 6x6 matrix) by finite
/// differences along random directions, and D symmetric, at every deformation. `scale` is the
/// law's stiffness scale (Pa) for the absolute part of the tolerance.
template <class Law>
void check_derivatives(const Law& law, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  for (const auto& d : deformations(rng)) {
    const Mat3 E = green_strain(d.F);
    const Mat3 S = law.pk2_stress(E);
    const Mat6 D = law.tangent_matrix(E);
    ASSERT_TRUE(S.allFinite() && D.allFinite()) << d.name;
    EXPECT_LE((D - D.transpose()).norm(), 1e-12 * D.norm()) << d.name << ": tangent not symmetric";
    for (int trial = 0; trial < 3; ++trial) {
      const Mat3 dE = random_sym(rng, 1.0);
      const double h =
          1e-4 * std::min(1.0, 1.0 / std::max(1.0, (Mat3::Identity() + 2.0 * E).inverse().norm()));
      const double fd_w = fd4([&](double s) { return law.energy_density(E + s * dE); }, h);
      const double an_w = S.cwiseProduct(dE).sum();
      EXPECT_NEAR(fd_w, an_w, 1e-8 * (std::abs(an_w) + S.norm() + scale)) << d.name << ": S != dW/dE";
      const Mat3 fd_s = fd4([&](double s) -> Mat3 { return law.pk2_stress(E + s * dE); }, h);
      const Mat3 an_s = law.tangent(E, dE);
      EXPECT_LE((fd_s - an_s).norm(), 1e-7 * (an_s.norm() + scale)) << d.name << ": tangent != dS/dE";
      EXPECT_LE((apply_tangent(D, dE) - an_s).norm(), 1e-12 * (an_s.norm() + scale)) << d.name;
    }
  }
}

/// W(0) = 0, S(0) = 0 and D(0) = lambda I (x) I + 2 mu I (.) I for the Lame constants of (young, nu).
template <class Law>
void check_small_strain(const Law& law, double young, double nu) {
  const double lambda = young * nu / ((1 + nu) * (1 - 2 * nu)), mu = young / (2 * (1 + nu));
  const Mat3 Z = Mat3::Zero();
  EXPECT_NEAR(law.energy_density(Z), 0.0, 1e-12 * mu);
  EXPECT_LE(law.pk2_stress(Z).norm(), 1e-12 * mu);
  const Mat6 D0 = isotropic_tangent(lambda, mu);
  EXPECT_LE((law.tangent_matrix(Z) - D0).norm(), 1e-12 * D0.norm());
  EXPECT_NEAR(law.small_strain().lambda, lambda, 1e-12 * (lambda + mu));
  EXPECT_NEAR(law.small_strain().mu, mu, 1e-12 * mu);
  // and the stress of a small strain eps X is eps D0 : X + O(eps^2)
  std::mt19937 rng(3);
  const Mat3 X = random_sym(rng, 1.0);
  const double eps = 1e-6;
  EXPECT_LE((law.pk2_stress(eps * X) - eps * apply_tangent(D0, X)).norm(), 1e-5 * eps * D0.norm());
}

/// Objectivity: S from F and from Q F agree (E is frame-invariant), and the Cauchy stress rotates,
/// sigma(Q F) = Q sigma(F) Q^T. Isotropy: S(Q^T E Q) = Q^T S(E) Q and the same for the tangent.
template <class Law>
void check_objectivity_and_isotropy(const Law& law, unsigned seed) {
  std::mt19937 rng(seed);
  for (const auto& d : deformations(rng)) {
    const Mat3 Q = random_rotation(rng);
    const Mat3 S = law.pk2_stress(green_strain(d.F)), SQ = law.pk2_stress(green_strain(Q * d.F));
    const double tol = 1e-12 * (S.norm() + law.small_strain().mu);
    EXPECT_LE((S - SQ).norm(), tol) << d.name;
    const auto cauchy = [&](const Mat3& F) {
      return Mat3(F * law.pk2_stress(green_strain(F)) * F.transpose() / F.determinant());
    };
    EXPECT_LE((cauchy(Q * d.F) - Q * cauchy(d.F) * Q.transpose()).norm(), 10 * tol / d.F.determinant())
        << d.name;
    const Mat3 E = green_strain(d.F), ER = Q.transpose() * E * Q;
    EXPECT_LE((law.pk2_stress(ER) - Q.transpose() * S * Q).norm(), 10 * tol) << d.name << ": not isotropic";
    const Mat3 dE = random_sym(rng, 1.0);
    const Mat3 dS = law.tangent(E, dE), dSR = law.tangent(ER, Q.transpose() * dE * Q);
    EXPECT_LE((dSR - Q.transpose() * dS * Q).norm(), 1e-11 * (dS.norm() + law.small_strain().mu)) << d.name;
  }
}

/// Two laws that must be the same function of E (energy, stress, tangent) to round-off.
template <class A, class B>
void check_same_law(const A& a, const B& b, unsigned seed) {
  std::mt19937 rng(seed);
  for (const auto& d : deformations(rng)) {
    const Mat3 E = green_strain(d.F);
    const double wa = a.energy_density(E), wb = b.energy_density(E);
    const double sc = a.small_strain().mu + a.small_strain().lambda;
    EXPECT_NEAR(wa, wb, 1e-12 * (std::abs(wa) + sc)) << d.name;
    const Mat3 sa = a.pk2_stress(E), sb = b.pk2_stress(E);
    EXPECT_LE((sa - sb).norm(), 1e-12 * (sa.norm() + sc)) << d.name;
    const Mat6 da = a.tangent_matrix(E), db = b.tangent_matrix(E);
    EXPECT_LE((da - db).norm(), 1e-11 * (da.norm() + sc)) << d.name;
  }
}

}  // namespace tmlab::tm::law_testing
