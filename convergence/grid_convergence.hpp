// The numerics of a mesh-convergence study (issue 28, `tmlab converge`; docs/convergence.md): from
// one quantity's values f_1..f_n on levels of representative mesh size h_1 > h_2 > ... > h_n, the
// observed order of each successive triple, Richardson's extrapolation, each level's estimated
// error and Roache's grid-convergence index, and the verdict whether the levels are in the
// asymptotic range. Pure functions of doubles, each tested against closed forms
// (tests/test_grid_convergence.cpp).
//
// Levels are numbered from the coarsest (1) to the finest (n); the refinement ratio between levels
// k-1 and k is r_k = h_{k-1} / h_k > 1.
//
// Observed order of the triple (k-1, k, k+1), with d_k = f_k - f_{k-1}:
//   constant ratio r:  p = ln(d_k / d_{k+1}) / ln r;
//   any ratios: the p that solves (f_k - f_{k-1}) / (f_{k+1} - f_k) = (r_k^p - 1) / (1 - r_{k+1}^-p),
//   the exact relation for f(h) = f0 + C h^p (it is (h_{k-1}^p - h_k^p) / (h_k^p - h_{k+1}^p));
//   Celik et al. 2008 (J. Fluids Eng. 130, 078001, eq. 3) write the same equation as a fixed point
//   with an absolute value, which hides a diverging sequence; here it is solved by bisection and a
//   negative order is kept. For r_k = r_{k+1} = r the right side is r^p: the closed form above.
// Richardson: f_inf = f_n + (f_n - f_{n-1}) / (r_n^p - 1), with p the finest triple's order.
// Estimated error of level k: |f_k - f_inf| / |f_inf|.
// GCI of level k >= 2 (Roache's fine-grid index of the pair (k-1, k)):
//   GCI_k = Fs |(f_k - f_{k-1}) / f_k| / (r_k^p - 1), Fs = 1.25 (three or more levels).
//
// Verdict: "asymptotic" (the extrapolation is given) unless, for any triple,
//   - a difference d_k is zero (the levels do not change the value: no order),
//   - successive differences change sign (oscillatory convergence),
//   - the observed order is not positive (the differences do not shrink: diverging),
// or the observed orders of the triples differ by more than `max_order_spread` (0.3). With three
// levels there is one triple and the spread cannot be checked; the result says so (`note`).
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace tmlab::convergence {

/// Roache's safety factor for three or more levels.
inline constexpr double kSafetyFactor = 1.25;
/// The largest difference between the observed orders of the triples of an asymptotic sequence.
inline constexpr double kMaxOrderSpread = 0.3;

/// p = ln((f2 - f1) / (f3 - f2)) / ln r for levels with the constant ratio r = h1/h2 = h2/h3 > 1
/// (f1 the coarsest). Returns NaN when the differences are zero or of opposite signs (no order).
/// Throws tmlab::Error naming the argument for r <= 1 or a non-finite value.
double observed_order(double f1, double f2, double f3, double r);

/// The observed order of three levels with sizes h1 > h2 > h3 (any ratios r21 = h1/h2,
/// r32 = h2/h3): the p that solves (f2 - f1) / (f3 - f2) = (r21^p - 1) / (1 - r32^-p) (the file
/// comment), by bisection on p in [-20, 20] (the right side is monotone in p). NaN when the
/// differences are zero or of opposite signs, or the root lies outside the bracket. Throws
/// tmlab::Error naming the argument for sizes that are not positive or do not decrease, or
/// non-finite values.
double observed_order_h(double h1, double h2, double h3, double f1, double f2, double f3);

/// Richardson's extrapolation of the pair (coarse, fine) with ratio r > 1 and order p > 0:
/// f_fine + (f_fine - f_coarse) / (r^p - 1).
double richardson(double f_coarse, double f_fine, double r, double p);

/// Roache's fine-grid GCI of the pair: Fs |(f_fine - f_coarse) / f_fine| / (r^p - 1)
/// (NaN when f_fine = 0).
double gci(double f_coarse, double f_fine, double r, double p, double safety_factor = kSafetyFactor);

/// One triple (k-1, k, k+1) of levels (0-based: `first` = k-1).
struct TripleOrder {
  int first = 0;
  double order = std::numeric_limits<double>::quiet_NaN();  ///< NaN: none (see `problem`)
  std::string problem;                                      ///< empty, or why the triple has no usable order
};

/// The analysis of one quantity over the levels.
struct ConvergenceAnalysis {
  std::vector<double> h, value;
  std::vector<double> ratio;         ///< ratio[k] = h[k-1] / h[k] (ratio[0] = NaN)
  bool constant_ratio = false;       ///< all ratios equal to 1e-9 (the closed-form order is used)
  std::vector<TripleOrder> triples;  ///< n - 2 of them
  bool asymptotic = false;
  std::string verdict;  ///< "asymptotic" | "not asymptotic"
  std::string reason;   ///< why not (empty when asymptotic)
  std::string note;     ///< a caveat of an asymptotic verdict (one triple only)
  double order_spread = std::numeric_limits<double>::quiet_NaN();  ///< max - min of the orders
  double order = std::numeric_limits<double>::quiet_NaN();         ///< p of the finest triple
  double extrapolated = std::numeric_limits<double>::quiet_NaN();  ///< f_inf (asymptotic only)
  std::vector<double> relative_error;  ///< |f_k - f_inf| / |f_inf| (NaN unless asymptotic)
  std::vector<double> gci;             ///< GCI_k (NaN for level 1 and unless asymptotic)
};

/// Analyses `value` on levels of sizes `h` (coarsest first). Throws tmlab::Error naming the argument
/// ("h", "value") for fewer than three levels, sizes of another count than the values, sizes that
/// are not positive and finite or do not decrease (the levels do not refine), or a non-finite value.
ConvergenceAnalysis analyse_convergence(const std::vector<double>& h, const std::vector<double>& value,
                                        double max_order_spread = kMaxOrderSpread);

}  // namespace tmlab::convergence
