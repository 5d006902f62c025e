// The contact block of a run's summary: see contact_log.hpp.
#include "runner/contact_log.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace tmlab::tm::runner {

void ContactLog::add(const ContactStepReport& r) {
  outer_.push_back(r.outer_iterations_total);
  natural_.push_back(r.natural_residual);
}

nlohmann::json ContactLog::json(const std::string& scheme, double eps, double gap_tol,
                                const std::vector<ContactBodyState>& final_state) const {
  nlohmann::json bodies = nlohmann::json::array();
  for (std::size_t b = 0; b < final_state.size(); ++b) {
    const ContactBodyState& st = final_state[b];
    const ContactBodySpec& spec = cfg_.contact.bodies[b];
    double pmax = 0.0;
    for (double pr : st.pressure) pmax = std::max(pmax, pr);
    bodies.push_back({{"name", st.name},
                      {"type", to_string(spec.shape)},
                      {"mode", to_string(spec.mode)},
                      {"final_position_m", {st.position.x(), st.position.y(), st.position.z()}},
                      {"final_force_N", {st.force.x(), st.force.y(), st.force.z()}},
                      {"final_moment_Nm", {st.moment.x(), st.moment.y(), st.moment.z()}},
                      {"final_area_m2", st.area},
                      {"final_radius_m", st.radius_equivalent},
                      {"final_radius_max_m", st.radius_max},
                      {"final_active_nodes", st.active_nodes},
                      {"final_max_pressure_Pa", pmax},
                      {"final_max_penetration_m", st.max_penetration}});
  }
  nlohmann::json j = {{"scheme", scheme}, {"gap_tol_m", gap_tol}, {"bodies", bodies}};
  if (eps > 0.0) {
    j["method"] = to_string(cfg_.contact.method);
    j["stiffness_N_per_m"] = eps;
    j["outer_iterations_per_step"] = outer_;
    j["natural_residual_per_step_m"] = natural_;
  }
  return j;
}

void ContactLog::save(CheckpointData& d) const {
  d.put("contact.log.outer", std::vector<std::int64_t>(outer_.begin(), outer_.end()));
  d.put("contact.log.natural", natural_);
}

void ContactLog::restore(const CheckpointData& d) {
  const auto& outer = d.ints("contact.log.outer");
  outer_.assign(outer.begin(), outer.end());
  natural_ = d.doubles("contact.log.natural");
}

}  // namespace tmlab::tm::runner
