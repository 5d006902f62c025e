// Fourth-order material tangents of the hyperelastic laws as 6x6 Voigt matrices, and the two
// tensor products the laws' tangents are written with.
//
// Voigt order (xx, yy, zz, xy, xz, yz), as to_voigt/from_voigt. A tangent D = dS/dE with the minor
// symmetries is stored as the 6x6 matrix D_ab = D_{i(a) j(a) k(b) l(b)}; it acts on the strain
// increment in ENGINEERING form e = (dE_xx, dE_yy, dE_zz, 2 dE_xy, 2 dE_xz, 2 dE_yz), so that
// dS_a = sum_b D_ab e_b, and D is a symmetric matrix exactly when the tensor has the major symmetry
// (a hyperelastic tangent, D = d^2 W / dE^2).
#pragma once

#include "tensormass/materials/stvk_material.hpp"

#include <Eigen/Core>

namespace tmlab::tm {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// The Lame constants of a law's small-strain (linear elastic) limit, Pa.
struct LameConstants {
  double lambda = 0.0;
  double mu = 0.0;
};

/// Index pairs of the Voigt positions.
inline constexpr int kVoigtI[6] = {0, 1, 2, 0, 0, 1};
inline constexpr int kVoigtJ[6] = {0, 1, 2, 1, 2, 2};

/// The engineering strain vector of a symmetric increment dE.
inline Vec6 engineering_strain(const Mat3& dE) {
  Vec6 e;
  e << dE(0, 0), dE(1, 1), dE(2, 2), 2.0 * dE(0, 1), 2.0 * dE(0, 2), 2.0 * dE(1, 2);
  return e;
}

/// dS = D : dE for a Voigt tangent D.
inline Mat3 apply_tangent(const Mat6& D, const Mat3& dE) {
  const Vec6 s = D * engineering_strain(dE);
  return from_voigt(s.data());
}

/// (A (x) B)_ijkl = A_ij B_kl.
inline Mat6 outer(const Mat3& A, const Mat3& B) {
  Mat6 D;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) D(a, b) = A(kVoigtI[a], kVoigtJ[a]) * B(kVoigtI[b], kVoigtJ[b]);
  return D;
}

/// A (x) B + B (x) A.
inline Mat6 sym_outer(const Mat3& A, const Mat3& B) {
  const Mat6 D = outer(A, B);
  return D + D.transpose();
}

/// The "box" product (A (.) B)_ijkl = 1/2 (A_ik B_jl + A_il B_jk). For symmetric A,
/// d(A^{-1})/dA = -(A^{-1} (.) A^{-1}), and I (.) I is the symmetric fourth-order identity.
inline Mat6 box(const Mat3& A, const Mat3& B) {
  Mat6 D;
  for (int a = 0; a < 6; ++a) {
    const int i = kVoigtI[a], j = kVoigtJ[a];
    for (int b = 0; b < 6; ++b) {
      const int k = kVoigtI[b], l = kVoigtJ[b];
      D(a, b) = 0.5 * (A(i, k) * B(j, l) + A(i, l) * B(j, k));
    }
  }
  return D;
}

/// The small-strain (linear elastic) tangent lambda I (x) I + 2 mu I (.) I.
inline Mat6 isotropic_tangent(double lambda, double mu) {
  const Mat3 I = Mat3::Identity();
  return lambda * outer(I, I) + 2.0 * mu * box(I, I);
}

}  // namespace tmlab::tm
