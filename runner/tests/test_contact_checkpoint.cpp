// The contact part of a run's checkpoint: every body's outputs come back exactly (save_contact and
// restore_contact over a real contact run are covered by test_run_checkpoint and the resume tests);
// inconsistent entries are refused naming the file.
#include "core/base/error.hpp"
#include "runner/contact_checkpoint.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm::runner {
namespace {

ContactBodyState body(const std::string& name, double scale) {
  ContactBodyState st;
  st.name = name;
  st.position = Vec3(1, 2, 3) * scale;
  st.force = Vec3(0.1, 0.2, 0.3) * scale;
  st.moment = Vec3(-1, 0, 1) * scale;
  st.active_nodes = 2;
  st.area = 1.0 / 3.0 * scale;
  st.radius_equivalent = 0.5 * scale;
  st.radius_max = 0.7 * scale;
  st.max_penetration = 1e-9 * scale;
  st.complementarity = 1e-12 * scale;
  st.min_multiplier = 0.25 * scale;
  st.nodes = {4, 17};
  st.nodal_force = {Vec3(0, 0, 1.0 / 7.0), Vec3(0, 0, 2.0 / 7.0)};
  st.gap = {-1e-9, 0.0};
  st.pressure = {1.0 / 3.0, 2.0 / 3.0};
  return st;
}

void expect_same(const ContactBodyState& a, const ContactBodyState& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.force, b.force);
  EXPECT_EQ(a.moment, b.moment);
  EXPECT_EQ(a.active_nodes, b.active_nodes);
  EXPECT_EQ(a.area, b.area);
  EXPECT_EQ(a.radius_equivalent, b.radius_equivalent);
  EXPECT_EQ(a.radius_max, b.radius_max);
  EXPECT_EQ(a.max_penetration, b.max_penetration);
  EXPECT_EQ(a.complementarity, b.complementarity);
  EXPECT_EQ(a.min_multiplier, b.min_multiplier);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.nodal_force, b.nodal_force);
  EXPECT_EQ(a.gap, b.gap);
  EXPECT_EQ(a.pressure, b.pressure);
}

TEST(ContactCheckpoint, OutputsOfEveryBodyComeBackExactly) {
  const std::vector<ContactBodyState> states{body("top", 1.0), body("bottom", -3.0)};
  CheckpointData d;
  save_contact_outputs(d, states);
  const std::vector<ContactBodyState> back = restore_contact_outputs(d, 2);
  ASSERT_EQ(back.size(), 2u);
  expect_same(back[0], states[0]);
  expect_same(back[1], states[1]);
}

TEST(ContactCheckpoint, InconsistentOutputsAreRefused) {
  CheckpointData d;
  save_contact_outputs(d, {body("top", 1.0)});
  d.put("contact.out.0.nodal_force", std::vector<double>{1.0, 2.0, 3.0});  // 2 nodes, 1 force
  d.set_source("ck.h5");
  try {
    restore_contact_outputs(d, 1);
    FAIL() << "inconsistent contact outputs were accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ck.h5: inconsistent contact outputs"), std::string::npos)
        << e.what();
  }
}

TEST(ContactCheckpoint, AMissingBodyIsAnError) {
  CheckpointData d;
  save_contact_outputs(d, {body("top", 1.0)});
  EXPECT_THROW(restore_contact_outputs(d, 2), Error);
}

}  // namespace
}  // namespace tmlab::tm::runner
