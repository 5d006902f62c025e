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
}

}  // namespace tmlab::tm::runner
