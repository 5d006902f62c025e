// The `contact` section of a case file: a full section parses into the spec and round-trips
// through contact_spec_json; every kind of bad input is refused with an error naming file and key;
// parse_case carries the section into CaseConfig.
#include "core/config/contact_spec.hpp"

#include "core/base/error.hpp"
#include "core/config/case_config.hpp"
#include "core/testing/temp_dir.hpp"

#include <gtest/gtest.h>

namespace tmlab {
namespace {

using json = nlohmann::json;

json good_section() {
  return json::parse(R"({
    "method": "augmented_lagrangian", "stiffness_factor": 50, "gap_tol": 1e-9, "max_outer_iterations": 20,
    "max_initial_gap": 0.002,
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
    parse_contact_spec(section, "case.json");
    FAIL() << "accepted: " << section.dump();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("case.json"), std::string::npos) << e.what();
  }
}

TEST(ContactSpec, ParsesAFullSection) {
  const ContactSpec s = parse_contact_spec(good_section(), "case.json");
  EXPECT_TRUE(s.enabled);
  EXPECT_EQ(s.method, ContactEnforcement::AugmentedLagrangian);
  EXPECT_EQ(s.stiffness_factor, 50.0);
  EXPECT_EQ(s.gap_tol, 1e-9);
  EXPECT_EQ(s.max_initial_gap, 0.002);
  EXPECT_EQ(s.max_outer_iterations, 20);
  ASSERT_EQ(s.bodies.size(), 3u);
  EXPECT_EQ(s.bodies[0].shape, ContactShape::Sphere);
  EXPECT_EQ(s.bodies[0].key, "contact.bodies[0]");
  EXPECT_TRUE(s.bodies[0].axis.isApprox(-Vec3::UnitZ()));  // the direction of travel
  EXPECT_NEAR(s.bodies[0].position(0.5).z(), 0.0095, 1e-15);
  EXPECT_EQ(s.bodies[1].shape, ContactShape::Punch);
  EXPECT_TRUE(s.bodies[1].axis.isApprox(-Vec3::UnitZ()));  // normalised
  EXPECT_EQ(s.bodies[1].edge_radius, 0.0005);
  EXPECT_EQ(s.bodies[2].mode, ContactBodyMode::Bonded);
  EXPECT_EQ(s.bodies[2].shape, ContactShape::Plane);
  EXPECT_EQ(s.bodies[2].name, "bottom");
}

TEST(ContactSpec, RoundTripsThroughItsJson) {
  const ContactSpec s = parse_contact_spec(good_section(), "case.json");
  const json j = contact_spec_json(s);
  const ContactSpec t = parse_contact_spec(j, "effective");
  EXPECT_EQ(contact_spec_json(t), j);
  ASSERT_EQ(t.bodies.size(), 3u);
  EXPECT_EQ(t.bodies[1].radius, 0.003);
  EXPECT_EQ(t.bodies[0].function(0.25), 0.25);
}

TEST(ContactSpec, BadInputNamesTheKey) {
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
  j["bodies"][2].erase("type");
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
  j["max_initial_gap"] = -1.0;
  expect_error(j, "contact.max_initial_gap");
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
  expect_error(json::array(), "contact");
}

using testing::write_file;
class ContactInCase : public testing::TempDirTest {};

TEST_F(ContactInCase, ParseCaseCarriesTheSectionAndTheEffectiveCaseRoundTrips) {
  write_file(dir_ / "m.msh", "placeholder");  // only existence is checked by parse_case
  json doc = json::parse(R"({"name": "t", "mesh": {"file": "m.msh"},
      "material": {"E": 1000, "nu": 0.3, "density": 1000}, "solver": {"type": "static"}})");
  EXPECT_FALSE(parse_case(doc, "case.json", {dir_.string()}).contact.enabled);
  EXPECT_EQ(effective_case_json(parse_case(doc, "case.json", {dir_.string()})).count("contact"), 0u);
  doc["contact"] = good_section();
  const CaseConfig c = parse_case(doc, "case.json", {dir_.string()});
  ASSERT_TRUE(c.contact.enabled);
  EXPECT_EQ(c.contact.bodies.size(), 3u);
  const json e = effective_case_json(c);
  EXPECT_EQ(effective_case_json(parse_case(e, "effective.json", {dir_.string()})), e);
  doc["contact"]["bodies"][0]["radius"] = 0;
  try {
    parse_case(doc, "case.json", {dir_.string()});
    FAIL();
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("case.json: key 'contact.bodies[0].radius'"), std::string::npos)
        << err.what();
  }
}

}  // namespace
}  // namespace tmlab
