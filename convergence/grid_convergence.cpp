#include "convergence/grid_convergence.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tmlab::convergence {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// The bracket of the bisection on p: orders beyond +-20 are no discretisation order.
constexpr double kOrderBracket = 20.0;

void require_finite(double v, const char* name) {
  if (!std::isfinite(v)) {
    std::ostringstream os;
    os << "grid convergence: " << name << " = " << v << " is not a finite number";
    throw Error(os.str());
  }
}

std::string number(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

/// ln((r21^p - 1) / (1 - r32^-p)) with a = ln r21, b = ln r32 > 0; its limit ln(a / b) at p = 0.
double log_ratio_model(double p, double a, double b) {
  if (p == 0.0) return std::log(a / b);
  return std::log(std::expm1(p * a) / -std::expm1(-p * b));
}

/// Why the differences d1 = f2 - f1, d2 = f3 - f2 give no order (empty when they do).
std::string difference_problem(double d1, double d2) {
  if (d1 == 0.0 || d2 == 0.0) return "zero difference";
  if ((d1 > 0.0) != (d2 > 0.0)) return "oscillatory";
  return {};
}

}  // namespace

double observed_order(double f1, double f2, double f3, double r) {
  require_finite(r, "ratio");
  if (!(r > 1.0))
    throw Error("grid convergence: ratio = " + number(r) + " must exceed 1 (the levels refine)");
  require_finite(f1, "f1");
  require_finite(f2, "f2");
  require_finite(f3, "f3");
  const double d1 = f2 - f1, d2 = f3 - f2;
  if (!difference_problem(d1, d2).empty()) return kNaN;
  return std::log(d1 / d2) / std::log(r);
}

double observed_order_h(double h1, double h2, double h3, double f1, double f2, double f3) {
  for (const auto& [v, name] :
       {std::pair{h1, "h1"}, {h2, "h2"}, {h3, "h3"}, {f1, "f1"}, {f2, "f2"}, {f3, "f3"}})
    require_finite(v, name);
  if (!(h1 > 0.0 && h2 > 0.0 && h3 > 0.0))
    throw Error("grid convergence: h must be positive (h1 = " + number(h1) + ", h2 = " + number(h2) +
                ", h3 = " + number(h3) + ")");
  if (!(h1 > h2 && h2 > h3))
    throw Error("grid convergence: h must decrease from level to level (the levels refine): h1 = " +
                number(h1) + ", h2 = " + number(h2) + ", h3 = " + number(h3));
  const double d1 = f2 - f1, d2 = f3 - f2;
  if (!difference_problem(d1, d2).empty()) return kNaN;
  const double a = std::log(h1 / h2), b = std::log(h2 / h3);
  const double target = std::log(d1 / d2);
  double lo = -kOrderBracket, hi = kOrderBracket;
  const double f_lo = log_ratio_model(lo, a, b) - target, f_hi = log_ratio_model(hi, a, b) - target;
  if (!(f_lo <= 0.0 && f_hi >= 0.0)) return kNaN;  // the root lies outside the bracket
  // Bisection to the last bit: 200 halvings of a width-40 bracket reach below any double spacing.
  for (int it = 0; it < 200 && hi - lo > 0.0; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    if (log_ratio_model(mid, a, b) - target < 0.0)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

double richardson(double f_coarse, double f_fine, double r, double p) {
  return f_fine + (f_fine - f_coarse) / (std::pow(r, p) - 1.0);
}

double gci(double f_coarse, double f_fine, double r, double p, double safety_factor) {
  if (f_fine == 0.0) return kNaN;
  return safety_factor * std::abs((f_fine - f_coarse) / f_fine) / (std::pow(r, p) - 1.0);
}

ConvergenceAnalysis analyse_convergence(const std::vector<double>& h, const std::vector<double>& value,
                                        double max_order_spread) {
  const std::size_t n = value.size();
  if (n < 3)
    throw Error("grid convergence: value: " + std::to_string(n) +
                " levels given; an observed order needs at least 3");
  if (h.size() != n)
    throw Error("grid convergence: h: " + std::to_string(h.size()) + " sizes for " + std::to_string(n) +
                " values");
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(h[k]) || !(h[k] > 0.0))
      throw Error("grid convergence: h of level " + std::to_string(k + 1) + " = " + number(h[k]) +
                  " is not a positive finite size");
    if (!std::isfinite(value[k]))
      throw Error("grid convergence: value of level " + std::to_string(k + 1) + " = " + number(value[k]) +
                  " is not a finite number");
    if (k > 0 && !(h[k] < h[k - 1]))
      throw Error("grid convergence: h: level " + std::to_string(k + 1) + " (h = " + number(h[k]) +
                  ") does not refine level " + std::to_string(k) + " (h = " + number(h[k - 1]) + ")");
  }
  ConvergenceAnalysis a;
  a.h = h;
  a.value = value;
  a.ratio.assign(n, kNaN);
  for (std::size_t k = 1; k < n; ++k) a.ratio[k] = h[k - 1] / h[k];
  a.constant_ratio = true;
  for (std::size_t k = 2; k < n; ++k)
    if (std::abs(a.ratio[k] - a.ratio[1]) > 1e-9 * a.ratio[1]) a.constant_ratio = false;
  a.relative_error.assign(n, kNaN);
  a.gci.assign(n, kNaN);

  std::string reason;
  for (std::size_t k = 0; k + 2 < n; ++k) {
    TripleOrder t;
    t.first = static_cast<int>(k);
    const double d1 = value[k + 1] - value[k], d2 = value[k + 2] - value[k + 1];
    const std::string levels =
        "levels " + std::to_string(k + 1) + "-" + std::to_string(k + 2) + "-" + std::to_string(k + 3);
    t.problem = difference_problem(d1, d2);
    if (t.problem.empty()) {
      t.order = a.constant_ratio
                    ? observed_order(value[k], value[k + 1], value[k + 2], a.ratio[1])
                    : observed_order_h(h[k], h[k + 1], h[k + 2], value[k], value[k + 1], value[k + 2]);
      if (!std::isfinite(t.order))
        t.problem = "no order in [-20, 20]";
      else if (!(t.order > 0.0))
        t.problem = "diverging (observed order " + number(t.order) + " <= 0)";
    }
    if (!t.problem.empty() && reason.empty()) {
      if (t.problem == "oscillatory")
        reason = "oscillatory: the differences change sign across " + levels;
      else if (t.problem == "zero difference")
        reason = "a difference is zero across " + levels + " (the value does not change between levels)";
      else
        reason = t.problem + " across " + levels;
    }
    a.triples.push_back(t);
  }
  if (reason.empty()) {
    double lo = a.triples.front().order, hi = lo;
    for (const TripleOrder& t : a.triples) {
      lo = std::min(lo, t.order);
      hi = std::max(hi, t.order);
    }
    a.order_spread = hi - lo;
    if (a.order_spread > max_order_spread)
      reason = "the observed orders of the triples differ by " + number(a.order_spread) + " (more than " +
               number(max_order_spread) + ")";
  }
  a.asymptotic = reason.empty();
  a.verdict = a.asymptotic ? "asymptotic" : "not asymptotic";
  a.reason = reason;
  if (!a.asymptotic) return a;
  if (a.triples.size() == 1)
    a.note = "three levels: one observed order, its consistency across triples is not checked";
  a.order = a.triples.back().order;
  a.extrapolated = richardson(value[n - 2], value[n - 1], a.ratio[n - 1], a.order);
  for (std::size_t k = 0; k < n; ++k) {
    if (a.extrapolated != 0.0)
      a.relative_error[k] = std::abs(value[k] - a.extrapolated) / std::abs(a.extrapolated);
    if (k > 0) a.gci[k] = gci(value[k - 1], value[k], a.ratio[k], a.order);
  }
  return a;
}

}  // namespace tmlab::convergence
