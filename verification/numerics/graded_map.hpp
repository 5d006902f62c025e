// The graded map of [0, 1] onto [0, W] the indentation checks build their blocks with: uniform
// over [0, L] (a fraction t_a of the cells, the patch under the load or indenter), then cells growing
// exponentially to W (C1 at t_a):
//   s(xi) = L xi / t_a                                   for xi <= t_a,
//   s(xi) = L + (L / t_a) (exp(k (xi - t_a)) - 1) / k    beyond,
// k from s(1) = W (analytic_hertz_checks.cpp, contact_checks.cpp).
#pragma once

namespace tmlab::verify::numerics {

/// k > 0 with L + (L/t_a)(e^{k(1 - t_a)} - 1)/k = W, W_over_L = W / L (bisection; the left side grows
/// with k). Needs W_over_L > 1 / t_a (the uniform slope alone must not reach W).
double grading_rate(double W_over_L, double t_a);

/// s(xi) above.
double graded(double xi, double L, double t_a, double k);

}  // namespace tmlab::verify::numerics
