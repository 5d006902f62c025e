// Polynomial arithmetic on coefficient vectors: see polynomial.hpp.
#include "verification/numerics/polynomial.hpp"

namespace tmlab::verify::numerics {

Poly poly_mul(const Poly& a, const Poly& b) {
  Poly r(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) r[i + j] += a[i] * b[j];
  return r;
}
Poly poly_add(Poly a, const Poly& b, double sb) {
  if (a.size() < b.size()) a.resize(b.size(), 0.0);
  for (std::size_t i = 0; i < b.size(); ++i) a[i] += sb * b[i];
  return a;
}
Poly poly_deriv(const Poly& a) {
  if (a.size() < 2) return {0.0};
  Poly r(a.size() - 1);
  for (std::size_t k = 1; k < a.size(); ++k) r[k - 1] = double(k) * a[k];
  return r;
}
double poly_eval(const Poly& a, double t) {
  double v = 0.0;
  for (std::size_t k = a.size(); k-- > 0;) v = v * t + a[k];
  return v;
}

Poly smooth_ramp_poly(double t1) { return {0.0, 0.0, 3.0 / (t1 * t1), -2.0 / (t1 * t1 * t1)}; }

}  // namespace tmlab::verify::numerics
