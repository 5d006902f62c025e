#include "core/results/recorder.hpp"

#include "core/results/series_names.hpp"

#include "core/base/error.hpp"

#include <algorithm>

namespace tmlab {

namespace sn = series_names;

void write_series_file(const std::filesystem::path& path, const SeriesTable& table,
                       const std::vector<std::pair<std::string, std::string>>& root_attributes) {
  H5File h5 = H5File::create(path.string());
  for (const auto& s : table.series()) {
    h5.write("/series/" + s.name, s.values, {s.values.size()});
    if (!s.unit.empty()) h5.set_attribute("/series/" + s.name, "unit", s.unit);
  }
  for (const auto& [key, value] : root_attributes) h5.set_attribute("/", key, value);
  h5.close();
}

Recorder::Recorder(std::vector<std::string> conditions, std::vector<std::string> probe_names,
                   std::vector<Index> probe_nodes)
    : conditions_(std::move(conditions)),
      probe_names_(std::move(probe_names)),
      probe_nodes_(std::move(probe_nodes)) {
  if (probe_names_.size() != probe_nodes_.size())
    throw Error("Recorder: " + std::to_string(probe_names_.size()) + " probe names for " +
                std::to_string(probe_nodes_.size()) + " probe nodes");
}

void Recorder::record(const StepValues& v) {
  min_volume_ratio_ = std::min(min_volume_ratio_, v.min_volume_ratio);
  table_.add(sn::kTime, "s", v.time);
  table_.add(sn::kMaxDisplacement, "m", v.max_displacement);
  table_.add(sn::kElasticEnergy, "J", v.elastic_energy);
  for (const Extra& e : v.extras) table_.add(e.name, e.unit, e.value);
  table_.add(sn::kKineticEnergy, "J", v.kinetic_energy);
  table_.add(sn::kMinVolumeRatio, "1", v.min_volume_ratio);
  table_.add(sn::kNewtonIterations, "1", v.newton_iterations);
  for (std::size_t k = 0; k < conditions_.size(); ++k) {
    const auto& r = v.reactions.at(k);
    sn::add_vector(table_, sn::reaction(conditions_[k]), "N", r[0], r[1], r[2]);
  }
  for (std::size_t k = 0; k < probe_names_.size(); ++k) {
    const auto& u = v.probes.at(k);
    sn::add_vector(table_, sn::probe(probe_names_[k]), "m", u[0], u[1], u[2]);
  }
  for (const sn::ContactValues& c : v.contact) sn::add_contact(table_, c);
}

void Recorder::open_displacements(const std::filesystem::path& path) {
  displacements_ = std::make_unique<H5File>(H5File::create(path.string()));
}

void Recorder::add_field_frame(double t, const std::vector<double>& U) {
  if (displacements_) {
    displacements_->append_row("/u", U);
    displacements_->append("/time", t);
  }
  ++field_frames_;
}

void Recorder::close_displacements(const std::string& note) {
  if (!displacements_) return;
  displacements_->set_attribute("/u", "unit", "m");
  displacements_->set_attribute("/u", "layout",
                                "rows: field frames; columns: 3*node + component (tmlab node order" +
                                    (note.empty() ? "" : "; " + note) + ")");
  displacements_->close();
}

void Recorder::write_timeseries(
    const std::filesystem::path& path,
    const std::vector<std::pair<std::string, std::string>>& root_attributes) const {
  write_series_file(path, table_, root_attributes);
}

nlohmann::json Recorder::plots(const std::string& case_name) const {
  auto plot = [&](const char* file, const nlohmann::json& y, const std::string& title, const char* ylabel) {
    return nlohmann::json{
        {"file", file},         {"x", sn::kTime},  {"y", y}, {"title", case_name + ": " + title},
        {"xlabel", "time [s]"}, {"ylabel", ylabel}};
  };
  auto has = [&](const char* name) {
    for (const auto& s : table_.series())
      if (s.name == name) return true;
    return false;
  };
  nlohmann::json out = nlohmann::json::array();
  out.push_back(plot("displacement.png", {sn::kMaxDisplacement}, "largest displacement", "displacement [m]"));
  nlohmann::json reactions = nlohmann::json::array();
  for (const auto& c : conditions_) reactions.push_back(sn::component(sn::reaction(c), "norm"));
  if (!reactions.empty()) out.push_back(plot("reaction.png", reactions, "reaction forces", "|reaction| [N]"));
  nlohmann::json energies = nlohmann::json::array();
  for (const char* e : {sn::kElasticEnergy, sn::kKineticEnergy, sn::kExternalWork, sn::kSpringEnergy,
                        sn::kBranchEnergy, sn::kDissipatedEnergy})
    if (has(e)) energies.push_back(e);
  out.push_back(plot("energy.png", energies, "energies", "energy [J]"));
  if (!probe_names_.empty()) {
    nlohmann::json y = nlohmann::json::array();
    for (const auto& p : probe_names_) y.push_back(sn::component(sn::probe(p), "norm"));
    out.push_back(plot("probes.png", y, "probe displacements", "|u| [m]"));
  }
  return out;
}

nlohmann::json Recorder::summary_blocks() const {
  nlohmann::json reactions = nlohmann::json::object();
  for (const auto& c : conditions_) reactions[c] = sn::last_vector(table_, sn::reaction(c));
  nlohmann::json probes = nlohmann::json::object();
  for (std::size_t k = 0; k < probe_names_.size(); ++k) {
    const std::string& n = probe_names_[k];
    probes[n] = {{"node", probe_nodes_[k]}, {"displacement_m", sn::last_vector(table_, sn::probe(n))}};
  }
  return {{"final_time", table_.last(sn::kTime)},
          {"max_displacement_m", table_.last(sn::kMaxDisplacement)},
          {"elastic_energy_J", table_.last(sn::kElasticEnergy)},
          {"min_volume_ratio", min_volume_ratio_},
          {"min_volume_ratio_over", "all recorded steps, t = 0 included"},
          {"field_frames", field_frames_},
          {"final_reactions_N", reactions},
          {"probes", probes}};
}

}  // namespace tmlab
