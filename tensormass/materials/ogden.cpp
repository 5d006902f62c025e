#include "tensormass/materials/ogden.hpp"

#include "core/base/error.hpp"
#include "tensormass/materials/isochoric_invariants.hpp"

#include <Eigen/Eigenvalues>

#include <array>
#include <cmath>
#include <limits>
#include <sstream>

namespace tmlab::tm {

Ogden::Ogden(std::vector<double> mu, std::vector<double> alpha, double kappa)
    : mu_(std::move(mu)), alpha_(std::move(alpha)), kappa_(kappa) {
  const char* law = "Ogden material";
  if (mu_.empty()) throw Error("Ogden material: needs at least one term (mu and alpha are empty)");
  if (mu_.size() != alpha_.size()) {
    std::ostringstream os;
    os << law << ": mu and alpha must have the same number of terms, got " << mu_.size() << " mu and "
       << alpha_.size() << " alpha";
    throw Error(os.str());
  }
  double sum = 0.0;
  for (std::size_t p = 0; p < mu_.size(); ++p) {
    const std::string mp = "mu[" + std::to_string(p) + "]", ap = "alpha[" + std::to_string(p) + "]";
    require_finite(law, mp.c_str(), mu_[p]);
    require_finite(law, ap.c_str(), alpha_[p]);
    if (alpha_[p] == 0.0) {
      throw Error(std::string(law) + ": " + ap + " must be non-zero (the term mu_p/alpha_p is undefined)");
    }
    sum += mu_[p] * alpha_[p];
  }
  if (!(sum > 0.0)) {
    std::ostringstream os;
    os << law << ": stability requires sum_p mu_p alpha_p > 0 (twice the shear modulus), got " << sum;
    throw Error(os.str());
  }
  require_positive(law, "kappa", "bulk modulus", kappa);
}

LameConstants Ogden::small_strain() const {
  double mu = 0.0;
  for (std::size_t p = 0; p < mu_.size(); ++p) mu += 0.5 * mu_[p] * alpha_[p];
  return {kappa_ - 2.0 * mu / 3.0, mu};
}

double Ogden::power_divided_difference(double k, double a, double b) {
  // (a^k - b^k)/(a - b) = -a^k expm1(k r) / (a - b),  r = ln(b/a) = log1p((b - a)/a).
  // b - a is exact for close a, b (Sterbenz), so r and expm1(k r) carry relative round-off only.
  if (a == b) return k * std::pow(a, k - 1.0);
  const double r = std::log1p((b - a) / a);
  return -std::pow(a, k) * std::expm1(k * r) / (a - b);
}

void Ogden::evaluate(const Mat3& E, double* W, Mat3* S, Mat6* D) const {
  const Mat3 C = Mat3::Identity() + 2.0 * E;
  // Symmetric QR (not the closed-form computeDirect, which loses accuracy for close eigenvalues).
  const Eigen::SelfAdjointEigenSolver<Mat3> es(C);
  const Eigen::Vector3d c = es.eigenvalues();
  const Mat3& n = es.eigenvectors();
  if (!(c.minCoeff() > 0.0)) {  // det F = 0 or a non-finite strain: outside the law's domain
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (W) *W = nan;
    if (S) S->setConstant(nan);
    if (D) D->setConstant(nan);
    return;
  }
  const double lnJ = 0.5 * (std::log(c[0]) + std::log(c[1]) + std::log(c[2]));
  const std::size_t np = mu_.size();
  double w = 0.5 * kappa_ * lnJ * lnJ;
  Eigen::Vector3d phi = (0.5 * kappa_ * lnJ) * c.cwiseInverse();  // volumetric part of Phi_i
  Eigen::Matrix3d phi2 = Eigen::Matrix3d::Zero();
  double theta[3] = {0.0, 0.0, 0.0};  // pairs (0,1), (0,2), (1,2)
  const int pi[3] = {0, 0, 1}, pj[3] = {1, 2, 2};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) phi2(i, j) = kappa_ / (4.0 * c[i] * c[j]);
    phi2(i, i) -= 0.5 * kappa_ * lnJ / (c[i] * c[i]);
  }
  for (int q = 0; q < 3; ++q) theta[q] = -0.5 * kappa_ * lnJ / (c[pi[q]] * c[pj[q]]);
  for (std::size_t p = 0; p < np; ++p) {
    const double al = alpha_[p], be = 0.5 * al, m = mu_[p];
    const double A = std::exp(-al / 3.0 * lnJ);  // J^{-alpha/3}
    Eigen::Vector3d cb;                          // c_k^beta
    for (int k = 0; k < 3; ++k) cb[k] = std::pow(c[k], be);
    const double s = cb.sum();
    w += m / al * (A * s - 3.0);
    if (!S && !D) continue;
    Eigen::Vector3d g;  // bracket of Phi_i: c_i^{beta-1}/2 - s/(6 c_i)
    for (int i = 0; i < 3; ++i) g[i] = 0.5 * cb[i] / c[i] - s / (6.0 * c[i]);
    phi += (m * A) * g;
    if (!D) continue;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        // d/dc_j of A g_i: -beta/(3 c_j) A g_i + A [delta_ij ((beta-1)/2 c_i^{beta-2} + s/(6 c_i^2))
        //                                          - beta c_j^{beta-1} / (6 c_i)]
        double v = -be / (3.0 * c[j]) * g[i] - be * cb[j] / (6.0 * c[j] * c[i]);
        if (i == j) v += 0.5 * (be - 1.0) * cb[i] / (c[i] * c[i]) + s / (6.0 * c[i] * c[i]);
        phi2(i, j) += m * A * v;
      }
    for (int q = 0; q < 3; ++q) {
      const double a = c[pi[q]], b = c[pj[q]];
      theta[q] += m * A * (0.5 * power_divided_difference(be - 1.0, a, b) + s / (6.0 * a * b));
    }
  }
  if (W) *W = w;
  std::array<Mat3, 3> N;
  for (int i = 0; i < 3; ++i) N[static_cast<std::size_t>(i)] = n.col(i) * n.col(i).transpose();
  if (S) *S = 2.0 * (phi[0] * N[0] + phi[1] * N[1] + phi[2] * N[2]);
  if (D) {
    // D = 4 [ sum_ij Phi_ij N_i (x) N_j + 2 sum_{i<j} Theta_ij M_ij (x) M_ij ],  M_ij = sym(n_i (x) n_j)
    Mat6 d = Mat6::Zero();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        d += (4.0 * 0.5 * (phi2(i, j) + phi2(j, i))) *
             outer(N[static_cast<std::size_t>(i)], N[static_cast<std::size_t>(j)]);
    for (int q = 0; q < 3; ++q) {
      const Mat3 nn = n.col(pi[q]) * n.col(pj[q]).transpose();
      const Mat3 M = 0.5 * (nn + nn.transpose());
      d += (8.0 * theta[q]) * outer(M, M);
    }
    *D = d;
  }
}

double Ogden::energy_density(const Mat3& E) const {
  double w = 0.0;
  evaluate(E, &w, nullptr, nullptr);
  return w;
}
Mat3 Ogden::pk2_stress(const Mat3& E) const {
  Mat3 s;
  evaluate(E, nullptr, &s, nullptr);
  return s;
}
Mat6 Ogden::tangent_matrix(const Mat3& E) const {
  Mat6 d;
  evaluate(E, nullptr, nullptr, &d);
  return d;
}
Mat3 Ogden::tangent(const Mat3& E, const Mat3& dE) const { return apply_tangent(tangent_matrix(E), dE); }

}  // namespace tmlab::tm
