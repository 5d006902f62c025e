// A contact run's part of the run's checkpoint: see contact_checkpoint.hpp.
#include "runner/contact_checkpoint.hpp"

#include "core/base/error.hpp"

#include <cstdint>
#include <string>

namespace tmlab::tm::runner {

void save_contact_outputs(CheckpointData& d, const std::vector<ContactBodyState>& states) {
  for (std::size_t b = 0; b < states.size(); ++b) {
    const ContactBodyState& st = states[b];
    const std::string at = "contact.out." + std::to_string(b) + ".";
    d.put_text(at + "name", st.name);
    std::vector<double> x;
    for (const Vec3* v : {&st.position, &st.force, &st.moment}) x.insert(x.end(), {v->x(), v->y(), v->z()});
    x.insert(x.end(), {st.area, st.radius_equivalent, st.radius_max, st.max_penetration, st.complementarity,
                       st.min_multiplier});
    d.put(at + "scalars", x);
    std::vector<std::int64_t> nodes{st.active_nodes};
    nodes.insert(nodes.end(), st.nodes.begin(), st.nodes.end());
    d.put(at + "nodes", nodes);
    std::vector<double> f;
    for (const Vec3& v : st.nodal_force) f.insert(f.end(), {v.x(), v.y(), v.z()});
    d.put(at + "nodal_force", f);
    d.put(at + "gap", st.gap);
    d.put(at + "pressure", st.pressure);
  }
}

std::vector<ContactBodyState> restore_contact_outputs(const CheckpointData& d, std::size_t n_bodies) {
  std::vector<ContactBodyState> states(n_bodies);
  for (std::size_t b = 0; b < n_bodies; ++b) {
    ContactBodyState& st = states[b];
    const std::string at = "contact.out." + std::to_string(b) + ".";
    st.name = d.text(at + "name");
    const auto& x = d.doubles(at + "scalars");
    const auto& nodes = d.ints(at + "nodes");
    const auto& f = d.doubles(at + "nodal_force");
    if (x.size() != 15 || nodes.empty() || f.size() != 3 * (nodes.size() - 1))
      throw Error(d.source() + ": inconsistent contact outputs; run without --resume");
    st.position = Vec3(x[0], x[1], x[2]);
    st.force = Vec3(x[3], x[4], x[5]);
    st.moment = Vec3(x[6], x[7], x[8]);
    st.area = x[9];
    st.radius_equivalent = x[10];
    st.radius_max = x[11];
    st.max_penetration = x[12];
    st.complementarity = x[13];
    st.min_multiplier = x[14];
    st.active_nodes = static_cast<int>(nodes[0]);
    st.nodes.assign(nodes.begin() + 1, nodes.end());
    for (std::size_t i = 0; i + 2 < f.size(); i += 3) st.nodal_force.emplace_back(f[i], f[i + 1], f[i + 2]);
    st.gap = d.doubles(at + "gap");
    st.pressure = d.doubles(at + "pressure");
  }
  return states;
}

void save_contact(CheckpointData& d, const ContactLoop& c) {
  if (c.augmented) {
    d.put("contact.committed", c.augmented->committed_state());
    save_contact_outputs(d, c.augmented->state());
  }
  if (c.kinematic) {
    d.put("contact.committed", c.kinematic->committed_state());
    save_contact_outputs(d, c.kinematic->state());
  }
  if (c.implicit)
    d.put("implicit.a",
          std::vector<double>(c.implicit->acceleration().data(),
                              c.implicit->acceleration().data() + c.implicit->acceleration().size()));
  if (c.log) c.log->save(d);
}

void restore_contact(const CheckpointData& d, const LoopState& loop, const ContactLoop& c) {
  try {
    if (c.augmented)
      c.augmented->restore_committed_state(d.doubles("contact.committed"),
                                           restore_contact_outputs(d, c.augmented->bodies().size()));
    if (c.kinematic)
      c.kinematic->restore_committed_state(d.doubles("contact.committed"),
                                           restore_contact_outputs(d, c.kinematic->bodies().size()));
  } catch (const Error& e) {
    throw Error(d.source() + ": " + e.what() + "; run without --resume");
  }
  if (c.implicit) {
    const auto& a = d.doubles("implicit.a");
    c.implicit->restore(loop.t, loop.s.u, loop.s.v,
                        Eigen::Map<const VecX>(a.data(), static_cast<Eigen::Index>(a.size())));
  }
  if (c.log) c.log->restore(d);
}

}  // namespace tmlab::tm::runner
