// The collapsed Gauss-Legendre rule on the reference tet: see quadrature.hpp.
#include "verification/numerics/quadrature.hpp"

#include <Eigen/Dense>

#include <cmath>

namespace tmlab::verify::numerics {

TetRule duffy_rule(int q) {
  Eigen::VectorXd x(q), w(q);
  // Gauss-Legendre on [0, 1] by the Golub-Welsch eigenvalue method.
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(q, q);
  for (int i = 1; i < q; ++i) J(i, i - 1) = J(i - 1, i) = i / std::sqrt(4.0 * i * i - 1.0);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(J);
  for (int i = 0; i < q; ++i) {
    x[i] = 0.5 * (es.eigenvalues()[i] + 1.0);
    w[i] = es.eigenvectors()(0, i) * es.eigenvectors()(0, i);  // sums to 1 on [0, 1]
  }
  TetRule r;
  for (int i = 0; i < q; ++i)
    for (int j = 0; j < q; ++j)
      for (int k = 0; k < q; ++k) {
        const double u = x[i], v = x[j], s = x[k];
        const double x1 = u, x2 = v * (1 - u), x3 = s * (1 - u) * (1 - v);
        r.bary.push_back({1 - x1 - x2 - x3, x1, x2, x3});
        r.weight.push_back(6.0 * w[i] * w[j] * w[k] * (1 - u) * (1 - u) * (1 - v));
      }
  return r;
}

}  // namespace tmlab::verify::numerics
