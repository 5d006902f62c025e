// The Newton iteration history of a run: see newton_log.hpp.
#include "runner/newton_log.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace tmlab::tm::runner {

void NewtonLog::add(const NewtonResult& last, int iterations, int cutbacks, int sub_increments,
                    bool at_roundoff) {
  iterations_.push_back(iterations);
  cutbacks_.push_back(cutbacks);
  sub_increments_.push_back(sub_increments);
  backtracks_.push_back(last.backtracks);
  residual_.push_back(last.residual_final);
  target_.push_back(last.target);
  roundoff_.push_back(at_roundoff);
  history_.push_back(last.history);
}

nlohmann::json NewtonLog::json(const SolverSpec& s) const {
  int roundoff_steps = 0, max_its = 0;
  for (bool b : roundoff_) roundoff_steps += b ? 1 : 0;
  for (int i : iterations_) max_its = std::max(max_its, i);
  nlohmann::json j = {{"line_search", to_string(s.line_search)},
                      {"linear", to_string(s.linear)},
                      {"rtol", s.rtol},
                      {"atol", s.atol},
                      {"max_iterations", s.max_iterations},
                      {"max_iterations_in_a_step", max_its},
                      {"steps_at_roundoff", roundoff_steps},
                      {"per_step",
                       {{"iterations", iterations_},
                        {"cutbacks", cutbacks_},
                        {"sub_increments", sub_increments_},
                        {"backtracks_last_solve", backtracks_},
                        {"residual_final", residual_},
                        {"residual_target", target_},
                        {"at_roundoff", roundoff_},
                        {"residual_history_last_solve", history_}}}};
  return j;
}

LinearSolveStats NewtonLog::linear() const {
  const LinearSolveStats& a = before_;
  const LinearSolveStats& b = process_;
  LinearSolveStats t;
  t.solves = a.solves + b.solves;
  t.cholmod_solves = a.cholmod_solves + b.cholmod_solves;
  t.ldlt_solves = a.ldlt_solves + b.ldlt_solves;
  t.lu_solves = a.lu_solves + b.lu_solves;
  t.cg_solves = a.cg_solves + b.cg_solves;
  t.cholmod_analyses = std::max(a.cholmod_analyses, b.cholmod_analyses);
  t.ldlt_analyses = std::max(a.ldlt_analyses, b.ldlt_analyses);
  t.lu_analyses = std::max(a.lu_analyses, b.lu_analyses);
  t.fallbacks_indefinite = a.fallbacks_indefinite + b.fallbacks_indefinite;
  t.fallbacks_round_off = a.fallbacks_round_off + b.fallbacks_round_off;
  t.max_negative_pivots = std::max(a.max_negative_pivots, b.max_negative_pivots);
  for (std::size_t k = 0; k < t.fallbacks_by_iteration.size(); ++k)
    t.fallbacks_by_iteration[k] = (k < a.fallbacks_by_iteration.size() ? a.fallbacks_by_iteration[k] : 0) +
                                  (k < b.fallbacks_by_iteration.size() ? b.fallbacks_by_iteration[k] : 0);
  return t;
}

void NewtonLog::save(CheckpointData& d) const {
  auto ints = [](const auto& v) { return std::vector<std::int64_t>(v.begin(), v.end()); };
  d.put("newton.iterations", ints(iterations_));
  d.put("newton.cutbacks", ints(cutbacks_));
  d.put("newton.sub_increments", ints(sub_increments_));
  d.put("newton.backtracks", ints(backtracks_));
  d.put("newton.roundoff", ints(roundoff_));
  d.put("newton.residual", residual_);
  d.put("newton.target", target_);
  std::vector<double> flat;
  std::vector<std::int64_t> lengths;
  for (const auto& h : history_) {
    flat.insert(flat.end(), h.begin(), h.end());
    lengths.push_back(static_cast<std::int64_t>(h.size()));
  }
  d.put("newton.history", flat);
  d.put("newton.history_lengths", lengths);
  const LinearSolveStats t = linear();
  std::vector<std::int64_t> lin = {t.solves,
                                   t.cholmod_solves,
                                   t.ldlt_solves,
                                   t.lu_solves,
                                   t.cg_solves,
                                   t.cholmod_analyses,
                                   t.ldlt_analyses,
                                   t.lu_analyses,
                                   t.fallbacks_indefinite,
                                   t.fallbacks_round_off,
                                   t.max_negative_pivots};
  lin.insert(lin.end(), t.fallbacks_by_iteration.begin(), t.fallbacks_by_iteration.end());
  d.put("newton.linear", lin);
}

void NewtonLog::restore(const CheckpointData& d) {
  auto ints = [&](const char* name) {
    const auto& v = d.ints(name);
    return std::vector<int>(v.begin(), v.end());
  };
  iterations_ = ints("newton.iterations");
  cutbacks_ = ints("newton.cutbacks");
  sub_increments_ = ints("newton.sub_increments");
  backtracks_ = ints("newton.backtracks");
  roundoff_.clear();
  for (const auto b : d.ints("newton.roundoff")) roundoff_.push_back(b != 0);
  residual_ = d.doubles("newton.residual");
  target_ = d.doubles("newton.target");
  history_.clear();
  const auto& flat = d.doubles("newton.history");
  std::size_t at = 0;
  for (const auto n : d.ints("newton.history_lengths")) {
    if (n < 0 || at + static_cast<std::size_t>(n) > flat.size())
      throw Error(d.source() + ": inconsistent Newton history; run without --resume");
    history_.emplace_back(flat.begin() + static_cast<std::ptrdiff_t>(at),
                          flat.begin() + static_cast<std::ptrdiff_t>(at + static_cast<std::size_t>(n)));
    at += static_cast<std::size_t>(n);
  }
  before_ = LinearSolveStats{};
  process_ = LinearSolveStats{};
  if (d.has("newton.linear")) {  // checkpoints written before 2026-12-02 have no linear counts
    const auto& v = d.ints("newton.linear");
    LinearSolveStats& t = before_;
    if (v.size() != 11 + t.fallbacks_by_iteration.size())
      throw Error(d.source() + ": inconsistent linear-solve counts; run without --resume");
    long* fields[] = {&t.solves,
                      &t.cholmod_solves,
                      &t.ldlt_solves,
                      &t.lu_solves,
                      &t.cg_solves,
                      &t.cholmod_analyses,
                      &t.ldlt_analyses,
                      &t.lu_analyses,
                      &t.fallbacks_indefinite,
                      &t.fallbacks_round_off};
    for (std::size_t k = 0; k < 10; ++k) *fields[k] = static_cast<long>(v[k]);
    t.max_negative_pivots = static_cast<Eigen::Index>(v[10]);
    for (std::size_t k = 0; k < t.fallbacks_by_iteration.size(); ++k)
      t.fallbacks_by_iteration[k] = static_cast<long>(v[11 + k]);
  }
}

}  // namespace tmlab::tm::runner
