// Constitutive laws of the reference solver, as stateless value types: strain energy density W(E),
// second Piola-Kirchhoff stress S = dW/dE and material tangent D = dS/dE, all as functions of the
// Green-Lagrange strain E = (F^T F - I)/2 (C = I + 2E). tests/test_reference_materials.cpp checks
// S against finite differences of W and D against finite differences of S, for every law.
//
// Prony viscoelasticity (PronySeries) acts on the PK2 stress at each quadrature point, with the
// update schemes of the tensor-mass model (docs/reference-fem.md, "Viscoelasticity"): the choices,
// recursion factors and weight conversion are the shared ones of core/constitutive/prony.hpp.
#pragma once

#include "core/base/error.hpp"
#include "core/constitutive/material_law.hpp"
#include "core/constitutive/prony.hpp"

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <cmath>
#include <string>
#include <vector>

namespace tmlab::ref {

using SymTensor2 = dealii::SymmetricTensor<2, 3>;
using SymTensor4 = dealii::SymmetricTensor<4, 3>;

/// Identity (rank 2) and the "box" product (A (.) B)_ijkl = 1/2 (A_ik B_jl + A_il B_jk), which
/// is dA^{-1}/dA = -(A^{-1} (.) A^{-1}) for symmetric A.
inline SymTensor4 box_product(const SymTensor2& A, const SymTensor2& B) {
  SymTensor4 out;
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned j = i; j < 3; ++j)
      for (unsigned k = 0; k < 3; ++k)
        for (unsigned l = k; l < 3; ++l) out[i][j][k][l] = 0.5 * (A[i][k] * B[j][l] + A[i][l] * B[j][k]);
  return out;
}

/// St Venant-Kirchhoff: W = lambda/2 (tr E)^2 + mu tr(E^2), S = lambda tr(E) I + 2 mu E,
/// D = lambda I (x) I + 2 mu II (constant). Identical to tmlab::tm::StVenantKirchhoff.
struct StVenantKirchhoffLaw {
  double lambda = 0.0, mu = 0.0;
  double energy(const SymTensor2& E) const {
    const double tr = dealii::trace(E);
    return 0.5 * lambda * tr * tr + mu * (E * E);
  }
  SymTensor2 stress(const SymTensor2& E) const {
    return lambda * dealii::trace(E) * dealii::unit_symmetric_tensor<3>() + 2.0 * mu * E;
  }
  SymTensor4 tangent(const SymTensor2& /*E*/) const {
    const SymTensor2 I = dealii::unit_symmetric_tensor<3>();
    return lambda * dealii::outer_product(I, I) + 2.0 * mu * dealii::identity_tensor<3>();
  }
};

/// Compressible neo-Hookean: W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2, I1 = tr C, J = det F.
/// S = mu (I - C^-1) + lambda ln J C^-1, D = lambda C^-1 (x) C^-1 + 2 (mu - lambda ln J) C^-1 (.) C^-1.
/// Linearises to the same Lame constants as St Venant-Kirchhoff.
struct NeoHookeanLaw {
  double lambda = 0.0, mu = 0.0;
  double energy(const SymTensor2& E) const {
    const SymTensor2 C = dealii::unit_symmetric_tensor<3>() + 2.0 * E;
    const double lnJ = 0.5 * std::log(dealii::determinant(C));
    return 0.5 * mu * (dealii::trace(C) - 3.0) - mu * lnJ + 0.5 * lambda * lnJ * lnJ;
  }
  SymTensor2 stress(const SymTensor2& E) const {
    const SymTensor2 C = dealii::unit_symmetric_tensor<3>() + 2.0 * E;
    const SymTensor2 Ci = dealii::invert(C);
    const double lnJ = 0.5 * std::log(dealii::determinant(C));
    return mu * (dealii::unit_symmetric_tensor<3>() - Ci) + lambda * lnJ * Ci;
  }
  SymTensor4 tangent(const SymTensor2& E) const {
    const SymTensor2 C = dealii::unit_symmetric_tensor<3>() + 2.0 * E;
    const SymTensor2 Ci = dealii::invert(C);
    const double lnJ = 0.5 * std::log(dealii::determinant(C));
    return lambda * dealii::outer_product(Ci, Ci) + 2.0 * (mu - lambda * lnJ) * box_product(Ci, Ci);
  }
};

/// Yeoh (strain-stiffening), decoupled: W = sum_i C_i0 (I1b - 3)^i + kappa/2 (ln J)^2 with the
/// isochoric invariant I1b = J^(-2/3) I1. With C10 = mu/2 and kappa = lambda + 2mu/3 it linearises
/// to the Lame constants (lambda, mu); C20, C30 > 0 stiffen it in shear at large strain.
///   S = 2 Psi'(I1b) G + kappa ln J C^-1,  G = dI1b/dC = J^(-2/3) (I - I1/3 C^-1),
///   D = 2 dS/dC = 4 Psi'' G (x) G + 4 Psi' dG/dC + kappa C^-1 (x) C^-1 - 2 kappa ln J C^-1 (.) C^-1,
///   dG/dC = J^(-2/3) [ -1/3 (I (x) C^-1 + C^-1 (x) I) + I1/9 C^-1 (x) C^-1 + I1/3 C^-1 (.) C^-1 ].
struct YeohLaw {
  double c10 = 0.0, c20 = 0.0, c30 = 0.0, kappa = 0.0;
  double energy(const SymTensor2& E) const {
    const SymTensor2 C = dealii::unit_symmetric_tensor<3>() + 2.0 * E;
    const double detC = dealii::determinant(C), lnJ = 0.5 * std::log(detC);
    const double x = std::pow(detC, -1.0 / 3.0) * dealii::trace(C) - 3.0;
    return c10 * x + c20 * x * x + c30 * x * x * x + 0.5 * kappa * lnJ * lnJ;
  }
  SymTensor2 stress(const SymTensor2& E) const {
    const SymTensor2 I = dealii::unit_symmetric_tensor<3>();
    const SymTensor2 C = I + 2.0 * E, Ci = dealii::invert(C);
    const double detC = dealii::determinant(C), lnJ = 0.5 * std::log(detC), I1 = dealii::trace(C);
    const double Jm23 = std::pow(detC, -1.0 / 3.0), x = Jm23 * I1 - 3.0;
    const double d1 = c10 + 2.0 * c20 * x + 3.0 * c30 * x * x;
    return 2.0 * d1 * Jm23 * (I - (I1 / 3.0) * Ci) + kappa * lnJ * Ci;
  }
  SymTensor4 tangent(const SymTensor2& E) const {
    const SymTensor2 I = dealii::unit_symmetric_tensor<3>();
    const SymTensor2 C = I + 2.0 * E, Ci = dealii::invert(C);
    const double detC = dealii::determinant(C), lnJ = 0.5 * std::log(detC), I1 = dealii::trace(C);
    const double Jm23 = std::pow(detC, -1.0 / 3.0), x = Jm23 * I1 - 3.0;
    const double d1 = c10 + 2.0 * c20 * x + 3.0 * c30 * x * x, d2 = 2.0 * c20 + 6.0 * c30 * x;
    const SymTensor2 G = Jm23 * (I - (I1 / 3.0) * Ci);
    const SymTensor4 CiCi = dealii::outer_product(Ci, Ci), box = box_product(Ci, Ci);
    const SymTensor4 dG = Jm23 * (-1.0 / 3.0 * (dealii::outer_product(I, Ci) + dealii::outer_product(Ci, I)) +
                                  (I1 / 9.0) * CiCi + (I1 / 3.0) * box);
    return 4.0 * d2 * dealii::outer_product(G, G) + 4.0 * d1 * dG + kappa * CiCi - 2.0 * kappa * lnJ * box;
  }
};

// ---------------------------------------------------------------------------------------------
// Further laws of the fast model (tensormass/materials/, docs/theory/hyperelastic-laws.md), with
// the same energies so that the two models agree to round-off pointwise and on the same mesh
// (tests/test_reference_materials.cpp; verification case reference-laws-same-mesh). Each has the
// energy / stress / tangent triad of the laws above. Decoupled: isochoric invariants
// I1b = J^{-2/3} I1, I2b = J^{-4/3} I2, volumetric kappa/2 (ln J)^2 as YeohLaw.
// ---------------------------------------------------------------------------------------------

/// d I2b / dC = J^{-4/3} (I1 I - C - 2/3 I2 C^-1) and its derivative
/// J^{-4/3} [ I (x) I - II - 2/3 ((I1 I - C) (x) C^-1 + C^-1 (x) (I1 I - C)) + 4/9 I2 C^-1 (x) C^-1
///            + 2/3 I2 C^-1 (.) C^-1 ],  II the symmetric fourth-order identity.
struct IsochoricSecondInvariant {
  SymTensor2 G;
  SymTensor4 dG;
  double value = 3.0;  ///< I2b
  IsochoricSecondInvariant(const SymTensor2& C, const SymTensor2& Ci, double detC, bool with_tangent) {
    const SymTensor2 I = dealii::unit_symmetric_tensor<3>();
    const double I1 = dealii::trace(C), I2 = 0.5 * (I1 * I1 - C * C), Jm43 = std::pow(detC, -2.0 / 3.0);
    value = Jm43 * I2;
    const SymTensor2 A = I1 * I - C;
    G = Jm43 * (A - (2.0 / 3.0) * I2 * Ci);
    if (with_tangent)
      dG = Jm43 * (dealii::outer_product(I, I) - dealii::identity_tensor<3>() -
                   (2.0 / 3.0) * (dealii::outer_product(A, Ci) + dealii::outer_product(Ci, A)) +
                   (4.0 / 9.0) * I2 * dealii::outer_product(Ci, Ci) + (2.0 / 3.0) * I2 * box_product(Ci, Ci));
  }
};

/// d I1b / dC = J^{-2/3} (I - I1/3 C^-1) and its derivative (as in YeohLaw).
struct IsochoricFirstInvariant {
  SymTensor2 G;
  SymTensor4 dG;
  double value = 3.0;  ///< I1b
  IsochoricFirstInvariant(const SymTensor2& C, const SymTensor2& Ci, double detC, bool with_tangent) {
    const SymTensor2 I = dealii::unit_symmetric_tensor<3>();
    const double I1 = dealii::trace(C), Jm23 = std::pow(detC, -1.0 / 3.0);
    value = Jm23 * I1;
    G = Jm23 * (I - (I1 / 3.0) * Ci);
    if (with_tangent)
      dG = Jm23 * (-1.0 / 3.0 * (dealii::outer_product(I, Ci) + dealii::outer_product(Ci, I)) +
                   (I1 / 9.0) * dealii::outer_product(Ci, Ci) + (I1 / 3.0) * box_product(Ci, Ci));
  }
};

/// Mooney-Rivlin, decoupled: W = c10 (I1b - 3) + c01 (I2b - 3) + kappa/2 (ln J)^2.
///   S = 2 (c10 G1 + c01 G2) + kappa ln J C^-1,
///   D = 4 (c10 dG1 + c01 dG2) + kappa C^-1 (x) C^-1 - 2 kappa ln J C^-1 (.) C^-1.
/// Small-strain mu = 2 (c10 + c01), bulk modulus kappa.
struct MooneyRivlinLaw {
  double c10 = 0.0, c01 = 0.0, kappa = 0.0;
  double energy(const SymTensor2& E) const {
    const SymTensor2 C = dealii::unit_symmetric_tensor<3>() + 2.0 * E, Ci = dealii::invert(C);
    const double detC = dealii::determinant(C), lnJ = 0.5 * std::log(detC);
    return c10 * (IsochoricFirstInvariant(C, Ci, detC, false).value - 3.0) +
           c01 * (IsochoricSecondInvariant(C, Ci, detC, false).value - 3.0) + 0.5 * kappa * lnJ * lnJ;
  }
  SymTensor2 stress(const SymTensor2& E) const {
    const SymTensor2 C = dealii::unit_symmetric_tensor<3>() + 2.0 * E, Ci = dealii::invert(C);
    const double detC = dealii::determinant(C), lnJ = 0.5 * std::log(detC);
    return 2.0 * (c10 * IsochoricFirstInvariant(C, Ci, detC, false).G +
                  c01 * IsochoricSecondInvariant(C, Ci, detC, false).G) +
           kappa * lnJ * Ci;
  }
  SymTensor4 tangent(const SymTensor2& E) const {
    const SymTensor2 C = dealii::unit_symmetric_tensor<3>() + 2.0 * E, Ci = dealii::invert(C);
    const double detC = dealii::determinant(C), lnJ = 0.5 * std::log(detC);
    return 4.0 * (c10 * IsochoricFirstInvariant(C, Ci, detC, true).dG +
                  c01 * IsochoricSecondInvariant(C, Ci, detC, true).dG) +
           kappa * dealii::outer_product(Ci, Ci) - 2.0 * kappa * lnJ * box_product(Ci, Ci);
  }
};

/// Veronda-Westmann, decoupled: W = c1 (exp(c2 (I1b - 3)) - 1) - c1 c2/2 (I2b - 3) + kappa/2 (ln J)^2.
/// With Psi_1 = c1 c2 e^{c2 x}, Psi_11 = c2 Psi_1, Psi_2 = -c1 c2/2 (x = I1b - 3):
///   S = 2 (Psi_1 G1 + Psi_2 G2) + kappa ln J C^-1,
///   D = 4 (Psi_11 G1 (x) G1 + Psi_1 dG1 + Psi_2 dG2) + kappa C^-1 (x) C^-1 - 2 kappa ln J C^-1 (.) C^-1.
/// Small-strain mu = c1 c2, bulk modulus kappa.
struct VerondaWestmannLaw {
  double c1 = 0.0, c2 = 0.0, kappa = 0.0;
  double energy(const SymTensor2& E) const {
    const SymTensor2 C = dealii::unit_symmetric_tensor<3>() + 2.0 * E, Ci = dealii::invert(C);
    const double detC = dealii::determinant(C), lnJ = 0.5 * std::log(detC);
    const double x = IsochoricFirstInvariant(C, Ci, detC, false).value - 3.0;
    const double y = IsochoricSecondInvariant(C, Ci, detC, false).value - 3.0;
    return c1 * std::expm1(c2 * x) - 0.5 * c1 * c2 * y + 0.5 * kappa * lnJ * lnJ;
  }
  SymTensor2 stress(const SymTensor2& E) const {
    const SymTensor2 C = dealii::unit_symmetric_tensor<3>() + 2.0 * E, Ci = dealii::invert(C);
    const double detC = dealii::determinant(C), lnJ = 0.5 * std::log(detC);
    const IsochoricFirstInvariant i1(C, Ci, detC, false);
    const double p1 = c1 * c2 * std::exp(c2 * (i1.value - 3.0)), p2 = -0.5 * c1 * c2;
    return 2.0 * (p1 * i1.G + p2 * IsochoricSecondInvariant(C, Ci, detC, false).G) + kappa * lnJ * Ci;
  }
  SymTensor4 tangent(const SymTensor2& E) const {
    const SymTensor2 C = dealii::unit_symmetric_tensor<3>() + 2.0 * E, Ci = dealii::invert(C);
    const double detC = dealii::determinant(C), lnJ = 0.5 * std::log(detC);
    const IsochoricFirstInvariant i1(C, Ci, detC, true);
    const double p1 = c1 * c2 * std::exp(c2 * (i1.value - 3.0)), p2 = -0.5 * c1 * c2;
    return 4.0 * (c2 * p1 * dealii::outer_product(i1.G, i1.G) + p1 * i1.dG +
                  p2 * IsochoricSecondInvariant(C, Ci, detC, true).dG) +
           kappa * dealii::outer_product(Ci, Ci) - 2.0 * kappa * lnJ * box_product(Ci, Ci);
  }
};

/// Ogden (N terms), decoupled: W = sum_p mu_p/alpha_p (sum_i lb_i^alpha_p - 3) + kappa/2 (ln J)^2,
/// lb_i = J^{-1/3} lambda_i, lambda_i^2 = c_i the eigenvalues of C (eigenvectors n_i, N_i = n_i (x) n_i).
/// As a symmetric function Phi(c_1, c_2, c_3):
///   S = 2 sum_i Phi_i N_i,
///   D = 4 [ sum_ij Phi_ij N_i (x) N_j + 2 sum_{i<j} Theta_ij M_ij (x) M_ij ],  M_ij = sym(n_i (x) n_j),
///   Theta_ij = (Phi_i - Phi_j)/(c_i - c_j), evaluated by the divided difference of c^{beta-1}
///   (power_divided_difference: exact limit at c_i = c_j, so repeated eigenvalues need no special case).
/// Small-strain mu = 1/2 sum_p mu_p alpha_p, bulk modulus kappa.
struct OgdenLaw {
  std::vector<double> mu, alpha;
  double kappa = 0.0;

  /// (a^k - b^k)/(a - b) for a, b > 0, accurate to round-off; k a^{k-1} at a = b.
  static double power_divided_difference(double k, double a, double b) {
    if (a == b) return k * std::pow(a, k - 1.0);
    return -std::pow(a, k) * std::expm1(k * std::log1p((b - a) / a)) / (a - b);
  }

  /// Eigenvalues c_i and projectors N_i = n_i (x) n_i of C, and the M_ij of the pairs (0,1), (0,2), (1,2).
  struct Spectrum {
    double c[3];
    SymTensor2 N[3], M[3];
    double lnJ = 0.0;
  };
  static Spectrum spectrum(const SymTensor2& E) {
    const SymTensor2 C = dealii::unit_symmetric_tensor<3>() + 2.0 * E;
    const auto eig = dealii::eigenvectors(C, dealii::SymmetricTensorEigenvectorMethod::jacobi);
    Spectrum s;
    for (unsigned i = 0; i < 3; ++i) {
      s.c[i] = eig[i].first;
      s.N[i] = dealii::symmetrize(dealii::outer_product(eig[i].second, eig[i].second));
      s.lnJ += 0.5 * std::log(s.c[i]);
    }
    const unsigned pi[3] = {0, 0, 1}, pj[3] = {1, 2, 2};
    for (unsigned q = 0; q < 3; ++q)
      s.M[q] = dealii::symmetrize(dealii::outer_product(eig[pi[q]].second, eig[pj[q]].second));
    return s;
  }

  double energy(const SymTensor2& E) const {
    const Spectrum s = spectrum(E);
    double w = 0.5 * kappa * s.lnJ * s.lnJ;
    for (std::size_t p = 0; p < mu.size(); ++p) {
      double sum = 0.0;
      for (unsigned k = 0; k < 3; ++k) sum += std::pow(s.c[k], 0.5 * alpha[p]);
      w += mu[p] / alpha[p] * (std::exp(-alpha[p] / 3.0 * s.lnJ) * sum - 3.0);
    }
    return w;
  }

  /// Phi_i (first partials), Phi_ij (second partials) and Theta for the pairs (0,1), (0,2), (1,2).
  void partials(const Spectrum& s, double phi[3], double phi2[3][3], double theta[3]) const {
    const double* c = s.c;
    const unsigned pi[3] = {0, 0, 1}, pj[3] = {1, 2, 2};
    for (unsigned i = 0; i < 3; ++i) {
      phi[i] = 0.5 * kappa * s.lnJ / c[i];  // kappa ln J d(ln J)/dc_i
      for (unsigned j = 0; j < 3; ++j)
        phi2[i][j] = kappa / (4.0 * c[i] * c[j]) - (i == j ? 0.5 * kappa * s.lnJ / (c[i] * c[i]) : 0.0);
    }
    for (unsigned q = 0; q < 3; ++q) theta[q] = -0.5 * kappa * s.lnJ / (c[pi[q]] * c[pj[q]]);
    for (std::size_t p = 0; p < mu.size(); ++p) {
      // term mu/alpha A sum_k c_k^beta, A = J^{-alpha/3}, beta = alpha/2:
      //   Phi_i = mu A [c_i^{beta-1}/2 - sum/(6 c_i)]
      const double be = 0.5 * alpha[p], A = std::exp(-alpha[p] / 3.0 * s.lnJ), mA = mu[p] * A;
      double cb[3], sum = 0.0;
      for (unsigned k = 0; k < 3; ++k) sum += (cb[k] = std::pow(c[k], be));
      double g[3];
      for (unsigned i = 0; i < 3; ++i) {
        g[i] = 0.5 * cb[i] / c[i] - sum / (6.0 * c[i]);
        phi[i] += mA * g[i];
      }
      for (unsigned i = 0; i < 3; ++i)
        for (unsigned j = 0; j < 3; ++j) {
          // d(A g_i)/dc_j = A [ -beta/(3 c_j) g_i - beta c_j^beta/(6 c_i c_j)
          //                     + delta_ij ((beta - 1) c_i^beta/(2 c_i^2) + sum/(6 c_i^2)) ]
          double v = -be / (3.0 * c[j]) * g[i] - be * cb[j] / (6.0 * c[i] * c[j]);
          if (i == j) v += (0.5 * (be - 1.0) * cb[i] + sum / 6.0) / (c[i] * c[i]);
          phi2[i][j] += mA * v;
        }
      for (unsigned q = 0; q < 3; ++q) {
        const double a = c[pi[q]], b = c[pj[q]];
        theta[q] += mA * (0.5 * power_divided_difference(be - 1.0, a, b) + sum / (6.0 * a * b));
      }
    }
  }

  SymTensor2 stress(const SymTensor2& E) const {
    const Spectrum s = spectrum(E);
    double phi[3], phi2[3][3], theta[3];
    partials(s, phi, phi2, theta);
    return 2.0 * (phi[0] * s.N[0] + phi[1] * s.N[1] + phi[2] * s.N[2]);
  }
  SymTensor4 tangent(const SymTensor2& E) const {
    const Spectrum s = spectrum(E);
    double phi[3], phi2[3][3], theta[3];
    partials(s, phi, phi2, theta);
    SymTensor4 D;
    for (unsigned i = 0; i < 3; ++i)
      for (unsigned j = 0; j < 3; ++j)
        D += 2.0 * (phi2[i][j] + phi2[j][i]) * dealii::outer_product(s.N[i], s.N[j]);
    for (unsigned q = 0; q < 3; ++q) D += 8.0 * theta[q] * dealii::outer_product(s.M[q], s.M[q]);
    return D;
  }
};

/// One of the laws above, chosen at run time (a closed set: a switch is clearer than virtuals).
struct Material {
  using Kind = MaterialLaw;
  Kind kind = Kind::StVK;
  double lambda = 0.0, mu = 0.0;  ///< Lame constants of the small-strain limit
  StVenantKirchhoffLaw stvk;
  NeoHookeanLaw neo;
  YeohLaw yeoh;
  MooneyRivlinLaw mooney_rivlin;
  OgdenLaw ogden;
  VerondaWestmannLaw veronda_westmann;

  /// The law of a case file's material section (core/constitutive/material_law.hpp: the same
  /// parameters the fast model builds its law from, tensormass/materials/law_factory.hpp). Throws
  /// tmlab::Error naming the parameter when law_parameter_problem() refuses them.
  static Material make(MaterialLaw law, const LawParameters& parameters);
  /// The legacy override of the command line (tmlab_reference --law) for a case given by E and nu:
  /// stvk | neo_hookean | yeoh, lambda = E nu / ((1+nu)(1-2nu)), mu = E / (2(1+nu)); Yeoh with C10 = mu/2,
  /// kappa = lambda + 2 mu/3 and C20, C30 as multiples of C10. Throws tmlab::Error for bad E, nu or
  /// Yeoh ratios and for the other laws (they have their own parameters: give them in the case).
  static Material make(MaterialLaw law, double young, double poisson, double yeoh_c20_ratio = 1.0,
                       double yeoh_c30_ratio = 0.0);
  /// As above, by name (the names of core/constitutive/material_law.hpp).
  static Material make(const std::string& law, double young, double poisson, double yeoh_c20_ratio = 1.0,
                       double yeoh_c30_ratio = 0.0);
  std::string name() const { return to_string(kind); }

  /// f(law) on the law in use.
  template <class F>
  auto visit(F&& f) const {
    switch (kind) {
      case Kind::StVK:
        return f(stvk);
      case Kind::NeoHookean:
        return f(neo);
      case Kind::MooneyRivlin:
        return f(mooney_rivlin);
      case Kind::Yeoh:
        return f(yeoh);
      case Kind::Ogden:
        return f(ogden);
      case Kind::VerondaWestmann:
        break;
    }
    return f(veronda_westmann);
  }
  double energy(const SymTensor2& E) const {
    return visit([&](const auto& law) { return law.energy(E); });
  }
  SymTensor2 stress(const SymTensor2& E) const {
    return visit([&](const auto& law) { return law.stress(E); });
  }
  SymTensor4 tangent(const SymTensor2& E) const {
    return visit([&](const auto& law) { return law.tangent(E); });
  }
};

inline Material Material::make(MaterialLaw law, const LawParameters& p) {
  if (const LawParameterProblem problem = law_parameter_problem(law, p); !problem.empty())
    throw Error("material: key '" + problem.key + "' " + problem.reason + " (law '" + to_string(law) + "')");
  if (law_takes_young_poisson(law)) return make(law, p.young, p.poisson);
  Material m;
  m.kind = law;
  const SmallStrainModuli small = small_strain_moduli(law, p);
  m.lambda = small.lambda();
  m.mu = small.shear;
  m.mooney_rivlin = {p.c10, p.c01, p.kappa};
  m.yeoh = {p.c10, p.c20, p.c30, p.kappa};
  m.ogden = {p.mu, p.alpha, p.kappa};
  m.veronda_westmann = {p.c1, p.c2, p.kappa};
  return m;
}

struct PronySeries {
  using Integration = PronyIntegration;
  std::vector<double> alpha, tau;
  Integration integration = Integration::ExactLinear;
  bool deviatoric = false;

  /// The weights as given in `convention`. Throws tmlab::Error for bad input (sizes, a negative
  /// weight, a tau <= 0, instantaneous weights summing to >= 1).
  static PronySeries make(PronyConvention convention, const std::vector<double>& weights,
                          const std::vector<double>& taus, PronyIntegration integration,
                          PronyRelaxation relaxation);
  std::size_t size() const { return alpha.size(); }

  /// Recursion factors (a_j, c_j) for a step dt >= 0.
  void factors(std::size_t j, double dt, double& a, double& c) const {
    const RecursionFactors f = recursion_factors(integration, dt, tau[j]);
    a = f.a, c = f.c;
  }
  /// The relaxing stress S_r(E) and its tangent dS_r/dE.
  SymTensor2 relaxing_stress(const Material& m, const SymTensor2& E) const {
    if (!deviatoric) return m.stress(E);
    return 2.0 * m.mu * (E - dealii::trace(E) / 3.0 * dealii::unit_symmetric_tensor<3>());
  }
  SymTensor4 relaxing_tangent(const Material& m, const SymTensor2& E) const {
    if (!deviatoric) return m.tangent(E);
    return 2.0 * m.mu * dealii::deviator_tensor<3>();
  }
};

/// History of one quadrature point: the committed state (h_j^n, S_r^n) and the trial state of the
/// step being solved; commit() makes the trial state the committed one (once per converged step).
struct PronyState {
  std::vector<SymTensor2> h, h_trial;
  SymTensor2 s_r, s_r_trial;
  void resize(std::size_t n) {
    h.assign(n, SymTensor2());
    h_trial.assign(n, SymTensor2());
  }
  void commit() {
    h = h_trial;
    s_r = s_r_trial;
  }
};

/// Total stress of the trial state and its consistent tangent for step dt, updating state.h_trial.
inline void prony_update(const Material& m, const PronySeries& p, const SymTensor2& E, double dt,
                         PronyState& state, SymTensor2& S, SymTensor4* D) {
  S = m.stress(E);
  if (D) *D = m.tangent(E);
  const SymTensor2 sr = p.relaxing_stress(m, E);
  state.s_r_trial = sr;
  double dfac = 0.0;
  for (std::size_t j = 0; j < p.size(); ++j) {
    double a = 0.0, c = 0.0;
    p.factors(j, dt, a, c);
    state.h_trial[j] = a * state.h[j] + c * (sr - state.s_r);
    S += p.alpha[j] * state.h_trial[j];
    dfac += p.alpha[j] * c;
  }
  if (D && dfac != 0.0) *D += dfac * p.relaxing_tangent(m, E);
}

}  // namespace tmlab::ref
