// The `contact` section in the contact module's terms (core parses it, contact_settings converts):
// a full section converts into the bodies and options, each body named by file and key.
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

// The section's errors (every bad key, named with file and key) are tested once, beside the
// parser: core/config/tests/test_contact_spec.cpp (ContactSpec.BadInputNamesTheKey). Here only what
// the conversion adds: each body's origin for messages, and RigidBody::validate() on a spec that did
// not come from the parser.
TEST(ContactConfig, EachBodyIsNamedByFileAndKey) {
  const ContactSettings s = parse_contact_section(good_section(), "case.json");
  ASSERT_EQ(s.bodies.size(), 3u);
  EXPECT_EQ(s.bodies[1].origin, "case.json: key 'contact.bodies[1]'");
}

TEST(ContactConfig, AnInvalidSpecIsRefusedNamingItsOrigin) {
  ContactSpec spec = parse_contact_spec(good_section(), "case.json");
  spec.bodies[0].radius = -1.0;  // past the parser: only RigidBody::validate() can catch it
  try {
    contact_settings(spec, "case.json");
    FAIL() << "accepted a negative radius";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("case.json: key 'contact.bodies[0]'"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tmlab::tm
