// Polynomials in t as coefficient vectors (c[k] multiplies t^k): product, scaled sum, derivative,
// Horner evaluation, and the C1 cubic ramp as one. The Prony checks build their exact drivers
// (strain, stress, E11 = eps + eps^2/2, ...) from these (verification/checks/analytic_prony_checks.cpp).
#pragma once

#include <vector>

namespace tmlab::verify::numerics {

/// Polynomial in t, coefficients c[k] of t^k.
using Poly = std::vector<double>;

/// a * b.
Poly poly_mul(const Poly& a, const Poly& b);

/// a + sb * b (the result has the length of the longer operand).
Poly poly_add(Poly a, const Poly& b, double sb = 1.0);

/// da/dt ({0} for a constant).
Poly poly_deriv(const Poly& a);

/// a(t) by Horner's rule.
double poly_eval(const Poly& a, double t);

/// The C1 cubic ramp 3 s^2 - 2 s^3, s = t/t1, as a polynomial in t (TimeFunction::smooth_ramp).
Poly smooth_ramp_poly(double t1);

}  // namespace tmlab::verify::numerics
