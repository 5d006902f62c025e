// ContactLog: the summary's contact block (each body's final state; the enforcement's per-step log
// only for a penalty or augmented-Lagrangian run) and its exact checkpoint round trip.
#include "runner/contact_log.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm::runner {
namespace {

CaseConfig one_sphere() {
  CaseConfig cfg;
  ContactBodySpec b;
  b.name = "probe";
  b.shape = ContactShape::Sphere;
  cfg.contact.bodies.push_back(b);
  return cfg;
}

std::vector<ContactBodyState> final_state() {
  ContactBodyState st;
  st.name = "probe";
  st.force = Vec3(0.0, 0.0, 2.5);
  st.area = 1e-6;
  st.active_nodes = 3;
  st.pressure = {10.0, 40.0, 20.0};
  st.max_penetration = 1e-9;
  return {st};
}

ContactStepReport step(int outer, double natural) {
  ContactStepReport r;
  r.outer_iterations_total = outer;
  r.natural_residual = natural;
  return r;
}

TEST(ContactLog, BodiesAndTheEnforcementLog) {
  const CaseConfig cfg = one_sphere();
  ContactLog log(cfg);
  log.add(step(3, 1e-10));
  log.add(step(5, 2e-10));
  const nlohmann::json j = log.json("augmented_lagrangian_static", 1e4, 1e-8, final_state());
  EXPECT_EQ(j["scheme"], "augmented_lagrangian_static");
  EXPECT_EQ(j["gap_tol_m"], 1e-8);
  EXPECT_EQ(j["stiffness_N_per_m"], 1e4);
  EXPECT_EQ(j["method"], to_string(cfg.contact.method));
  EXPECT_EQ(j["outer_iterations_per_step"], nlohmann::json({3, 5}));
  EXPECT_EQ(j["natural_residual_per_step_m"], nlohmann::json({1e-10, 2e-10}));
  const nlohmann::json& b = j["bodies"][0];
  EXPECT_EQ(b["name"], "probe");
  EXPECT_EQ(b["type"], "sphere");
  EXPECT_EQ(b["final_force_N"], nlohmann::json({0.0, 0.0, 2.5}));
  EXPECT_EQ(b["final_max_pressure_Pa"], 40.0);
  EXPECT_EQ(b["final_active_nodes"], 3);
}

TEST(ContactLog, KinematicContactHasNoEnforcementLog) {
  const CaseConfig cfg = one_sphere();
  const nlohmann::json j = ContactLog(cfg).json("kinematic_explicit", 0.0, 1e-8, final_state());
  EXPECT_FALSE(j.contains("method"));
  EXPECT_FALSE(j.contains("outer_iterations_per_step"));
  EXPECT_EQ(j["bodies"].size(), 1u);
}

TEST(ContactLog, CheckpointRoundTripIsExact) {
  const CaseConfig cfg = one_sphere();
  ContactLog log(cfg);
  log.add(step(3, 0.1 + 0.2));
  CheckpointData d;
  log.save(d);
  ContactLog back(cfg);
  back.add(step(9, 9.0));  // replaced, not appended to
  back.restore(d);
  EXPECT_EQ(back.json("s", 1.0, 0.0, final_state()), log.json("s", 1.0, 0.0, final_state()));
}

}  // namespace
}  // namespace tmlab::tm::runner
