// The checkpoint layout of a viscoelastic model's committed state, shared by ViscoelasticStVK and
// ViscoelasticHyperelastic: the branch histories, the drivers, then the five scalars of the energy
// bookkeeping at the last commit. One copy, so both models write and read the same layout.
#pragma once

#include "core/base/error.hpp"

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

namespace tmlab::tm {

/// The energy bookkeeping at the last commit.
struct CommittedEnergies {
  double elastic = 0.0, branch = 0.0, rate = 0.0, step_dissipation = 0.0, total_dissipation = 0.0;
};

/// hist, driver, then the five scalars of `e`.
inline std::vector<double> pack_committed_state(const std::vector<double>& hist,
                                                const std::vector<double>& driver,
                                                const CommittedEnergies& e) {
  std::vector<double> s(hist);
  s.insert(s.end(), driver.begin(), driver.end());
  s.insert(s.end(), {e.elastic, e.branch, e.rate, e.step_dissipation, e.total_dissipation});
  return s;
}

/// The inverse of pack_committed_state into `hist` and `driver` (their sizes are the model's); a
/// state of another size is a tmlab::Error (a checkpoint of another mesh or Prony series).
inline CommittedEnergies unpack_committed_state(const std::vector<double>& s, std::vector<double>& hist,
                                                std::vector<double>& driver) {
  const std::size_t nh = hist.size(), nd = driver.size();
  if (s.size() != nh + nd + 5)
    throw Error("checkpoint: a viscoelastic committed state of " + std::to_string(s.size()) +
                " values, this model has " + std::to_string(nh + nd + 5) +
                " (another mesh or Prony series?)");
  std::copy(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(nh), hist.begin());
  std::copy(s.begin() + static_cast<std::ptrdiff_t>(nh), s.begin() + static_cast<std::ptrdiff_t>(nh + nd),
            driver.begin());
  const double* e = s.data() + nh + nd;
  return {e[0], e[1], e[2], e[3], e[4]};
}

}  // namespace tmlab::tm
