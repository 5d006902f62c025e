// What summary.json says about a contact run's enforcement and its bodies at the end (the
// "contact" block), and the log's part of the run's checkpoint.
#pragma once

#include "core/config/case_config.hpp"
#include "core/results/checkpoint.hpp"
#include "tensormass/contact/contact_solver.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tmlab::tm::runner {

/// What the summary says about the contact enforcement and its bodies at the end.
class ContactLog {
 public:
  explicit ContactLog(const CaseConfig& cfg) : cfg_(cfg) {}
  /// One accepted step: its outer (augmented-Lagrangian) iterations and natural residual.
  void add(const ContactStepReport& r);
  /// The block: `scheme`, the gap tolerance and each body's final state; with `eps` > 0 (a
  /// penalty or augmented-Lagrangian run) also the method, the stiffness and the per-step log.
  nlohmann::json json(const std::string& scheme, double eps, double gap_tol,
                      const std::vector<ContactBodyState>& final_state) const;
  /// The log as checkpoint entries "contact.log.*", and back.
  void save(CheckpointData& d) const;
  void restore(const CheckpointData& d);

 private:
  const CaseConfig& cfg_;
  std::vector<int> outer_;
  std::vector<double> natural_;
};

}  // namespace tmlab::tm::runner
