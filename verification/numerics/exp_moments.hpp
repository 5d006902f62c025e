// Exponential moments I_k(t) = int_0^t s^k exp(-(t - s)/tau) ds, and with them the exact hereditary
// integral of a polynomial driver (held constant after its ramp): the closed forms the Prony checks
// compare the time-stepped models with (verification/checks/analytic_prony_checks.cpp).
#pragma once

#include "verification/numerics/polynomial.hpp"

#include <cstddef>
#include <vector>

namespace tmlab::verify::numerics {

/// I_k(t) = int_0^t s^k exp(-(t - s)/tau) ds, k = 0..kmax, exactly: by the recursion
/// I_k = tau t^k - k tau I_{k-1}, I_0 = -tau expm1(-t/tau) when t >= tau (no cancellation there), and
/// by the alternating series I_k = t^{k+1} k! sum_m (-t/tau)^m / (k+m+1)! when t < tau.
std::vector<double> exp_moments(double t, double tau, std::size_t kmax);

/// h(t) = int_0^t exp(-(t-s)/tau) Y'(s) ds for Y polynomial on [0, t1] and constant after.
double hereditary(const Poly& Y, double t1, double tau, double t);

}  // namespace tmlab::verify::numerics
