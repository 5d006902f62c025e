#include "verification/harness/evaluate.hpp"

#include "core/base/format.hpp"

#include "verification/harness/convergence.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace tmlab::verify {

const char* to_string(Status s) {
  switch (s) {
    case Status::Pass:
      return "pass";
    case Status::Fail:
      return "fail";
    case Status::Error:
      return "error";
  }
  return "?";
}

namespace {

std::string num(double v) { return significant(v, 3); }

}  // namespace

std::string CheckOutcome::describe() const {
  if (!std::isfinite(measured) && measured != measured) return name + ": not measured";
  if (kind == "max") return name + " = " + num(measured) + (passed ? " <= " : " > ") + num(limit);
  if (kind == "min") return name + " = " + num(measured) + (passed ? " >= " : " < ") + num(limit);
  if (kind == "order")
    return name + " order = " + num(measured) + " (expected " + num(limit) + " +- " + num(tolerance) + ")";
  if (kind == "finest") return name + " finest = " + num(measured) + (passed ? " <= " : " > ") + num(limit);
  return name;
}

const CheckOutcome* CaseResult::primary() const {
  for (const CheckOutcome& o : outcomes)
    if (!o.passed) return &o;
  for (const CheckOutcome& o : outcomes)
    if (o.kind == "finest") return &o;
  return outcomes.empty() ? nullptr : &outcomes.front();
}

CaseResult evaluate(const VerificationCase& c, Measurements m) {
  CaseResult r;
  r.name = c.name;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& chk : c.checks) {
    CheckOutcome o;
    o.name = chk.metric;
    o.kind = chk.bound == MetricCheck::Bound::Max ? "max" : "min";
    o.limit = o.tolerance = chk.limit;
    o.rationale = chk.rationale;
    const auto it = m.metrics.find(chk.metric);
    o.measured = it == m.metrics.end() ? nan : it->second;
    // NaN fails both bounds: a metric that was not measured, or came out NaN, never passes.
    o.passed = chk.bound == MetricCheck::Bound::Max ? (o.measured <= chk.limit) : (o.measured >= chk.limit);
    if (it == m.metrics.end())
      m.notes.push_back("metric '" + chk.metric + "' was not produced by kind '" + c.kind + "'");
    r.outcomes.push_back(o);
  }
  for (const auto& cv : c.convergence) {
    CheckOutcome order, finest;
    order.name = finest.name = cv.series;
    order.kind = "order";
    finest.kind = "finest";
    order.limit = cv.expected_order;
    order.tolerance = cv.order_tolerance;
    finest.limit = finest.tolerance = cv.finest_max;
    order.rationale = finest.rationale = cv.rationale;
    order.measured = finest.measured = nan;
    const auto it = m.series.find(cv.series);
    if (it == m.series.end() || it->second.x.size() < 2) {
      m.notes.push_back("series '" + cv.series + "' was not produced (or has fewer than 2 points)");
    } else {
      const Series& s = it->second;
      try {
        order.measured = fitted_order(s.x, s.y, cv.fit_points);
      } catch (const Error& e) {
        m.notes.push_back("series '" + cv.series + "': " + e.what());
      }
      const auto fine = std::min_element(s.x.begin(), s.x.end()) - s.x.begin();
      finest.measured = s.y[static_cast<std::size_t>(fine)];
    }
    order.passed = std::abs(order.measured - cv.expected_order) <= cv.order_tolerance;
    finest.passed = finest.measured <= cv.finest_max;
    r.outcomes.push_back(order);
    r.outcomes.push_back(finest);
  }
  const bool all =
      std::all_of(r.outcomes.begin(), r.outcomes.end(), [](const CheckOutcome& o) { return o.passed; });
  r.status = all ? Status::Pass : Status::Fail;
  r.measurements = std::move(m);
  return r;
}

}  // namespace tmlab::verify
