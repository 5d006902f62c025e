// The `contact` section in the contact module's terms (core parses it, contact_settings converts):
// a full section converts into the bodies and options; bad input is refused naming the key.
#include "tensormass/contact/contact_config.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

namespace tmlab::tm {
namespace {

using json = nlohmann::json;

json good_section() {
  return json::parse(R"({
    "method": "augmented_lagrangian", "stiffness_factor": 50, "gap_tol": 1e-9, "max_outer_iterations": 20,
    "bodies": [
      {"name": "indenter", "type": "sphere", "center": [0, 0, 0.01], "radius": 0.01,
       "displacement": [0, 0, -0.001], "function": {"type": "ramp", "t0": 0, "t1": 1}},
      {"name": "flat", "type": "punch", "center": [0, 0, 0.02], "axis": [0, 0, -2], "radius": 0.003,
       "edge_radius": 0.0005},
      {"name": "bottom", "type": "plane", "point": [0, 0, -0.01], "normal": [0, 0, 1], "mode": "bonded"}
    ]})");
}

void expect_error(const json& section, const std::string& needle) {
  try {
    parse_contact_section(section, "case.json");
    FAIL() << "accepted: " << section.dump();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("case.json"), std::string::npos) << e.what();
  }
}

TEST(ContactConfig, ParsesAFullSection) {
  const ContactSettings s = parse_contact_section(good_section(), "case.json");
  EXPECT_EQ(s.options.method, ContactMethod::AugmentedLagrangian);
  EXPECT_EQ(s.options.stiffness_factor, 50.0);
  EXPECT_EQ(s.options.gap_tol, 1e-9);
  EXPECT_EQ(s.options.max_outer_iterations, 20);
  ASSERT_EQ(s.bodies.size(), 3u);
  EXPECT_EQ(s.bodies[0].shape, RigidShape::Sphere);
  EXPECT_TRUE(s.bodies[0].axis.isApprox(-Vec3::UnitZ()));  // the direction of travel
  EXPECT_NEAR(s.bodies[0].position(0.5).z(), 0.0095, 1e-15);
  EXPECT_EQ(s.bodies[1].shape, RigidShape::Punch);
  EXPECT_TRUE(s.bodies[1].axis.isApprox(-Vec3::UnitZ()));  // normalised
  EXPECT_EQ(s.bodies[1].edge_radius, 0.0005);
  EXPECT_EQ(s.bodies[2].mode, ContactMode::Bonded);
  EXPECT_EQ(s.bodies[2].shape, RigidShape::Plane);
  ASSERT_EQ(s.keys.size(), 3u);
  EXPECT_EQ(s.keys[2], "contact.bodies[2]");
}

TEST(ContactConfig, BadInputNamesTheKey) {
  json j = good_section();
  j["bodies"][0]["radius"] = -1.0;
  expect_error(j, "contact.bodies[0].radius");
  j = good_section();
  j["bodies"][1]["typo"] = 1;
  expect_error(j, "typo");
  j = good_section();
  j["bodies"][2]["type"] = "cone";
  expect_error(j, "contact.bodies[2].type");
  j = good_section();
  j["bodies"][2]["normal"] = json::array({0, 0, 0});
  expect_error(j, "contact.bodies[2].normal");
  j = good_section();
  j["bodies"][1]["edge_radius"] = 0.004;
  expect_error(j, "contact.bodies[1].edge_radius");
  j = good_section();
  j["bodies"][1]["center"] = json::array({0, 0});
  expect_error(j, "contact.bodies[1].center");
  j = good_section();
  j["bodies"][1]["name"] = "indenter";
  expect_error(j, "contact.bodies[1].name");
  j = good_section();
  j["bodies"][0]["mode"] = "sticky";
  expect_error(j, "contact.bodies[0].mode");
  j = good_section();
  j["method"] = "lagrange";
  expect_error(j, "contact.method");
  j = good_section();
  j["gap_tol"] = -1.0;
  expect_error(j, "contact.gap_tol");
  j = good_section();
  j["max_outer_iterations"] = 0;
  expect_error(j, "contact.max_outer_iterations");
  j = good_section();
  j["bodies"] = json::array();
  expect_error(j, "contact.bodies");
  j = good_section();
  j.erase("bodies");
  expect_error(j, "contact.bodies");
  j = good_section();
  j["bodies"][0]["function"] = json{{"type", "nope"}};
  expect_error(j, "contact.bodies[0].function");
}

}  // namespace
}  // namespace tmlab::tm
