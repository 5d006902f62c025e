// The registry of check functions (registry.hpp): kinds registered once each, looked up by a case's
// kind, an unknown kind named with the case file and the known kinds, a kind registered twice refused.
#include "verification/harness/registry.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>
#include <string>

namespace tmlab::verify {
namespace {

Measurements measuring(double value) {
  Measurements m;
  m.set("value", value);
  return m;
}

VerificationCase case_of_kind(const std::string& kind) {
  VerificationCase c;
  c.name = "some-case";
  c.dir = "/cases/some-case";
  c.kind = kind;
  return c;
}

TEST(CheckRegistry, FindsTheFunctionOfACasesKind) {
  CheckRegistry reg;
  EXPECT_TRUE(reg.kinds().empty());
  reg.add("b.two", [](const CheckContext&) { return measuring(2.0); });
  reg.add({{"a.one", [](const CheckContext&) { return measuring(1.0); }},
           {"c.three", [](const CheckContext&) { return measuring(3.0); }}});
  EXPECT_TRUE(reg.has("a.one"));
  EXPECT_TRUE(reg.has("b.two"));
  EXPECT_FALSE(reg.has("a"));
  EXPECT_EQ(reg.kinds(), (std::vector<std::string>{"a.one", "b.two", "c.three"}));  // sorted
  std::ostringstream log;
  for (const auto& [kind, value] :
       {std::pair<std::string, double>{"a.one", 1.0}, {"b.two", 2.0}, {"c.three", 3.0}}) {
    const VerificationCase c = case_of_kind(kind);
    const CheckContext ctx{c, "/tree", "/work", log};
    EXPECT_EQ(reg.get(c)(ctx).metrics.at("value"), value) << kind;
  }
}

TEST(CheckRegistry, UnknownKindNamesTheCaseFileAndTheKnownKinds) {
  CheckRegistry reg;
  reg.add({{"kernel.x", [](const CheckContext&) { return measuring(0.0); }},
           {"model.y", [](const CheckContext&) { return measuring(0.0); }}});
  try {
    reg.get(case_of_kind("kernel.z"));
    ADD_FAILURE() << "an unknown kind was found";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("/cases/some-case/verify.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'kernel.z'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("kernel.x, model.y"), std::string::npos) << msg;
  }
}

TEST(CheckRegistry, AKindRegisteredTwiceIsAnInternalError) {
  CheckRegistry reg;
  reg.add("kernel.x", [](const CheckContext&) { return measuring(0.0); });
  EXPECT_THROW(reg.add("kernel.x", [](const CheckContext&) { return measuring(1.0); }), std::logic_error);
  EXPECT_THROW(reg.add({{"model.y", [](const CheckContext&) { return measuring(0.0); }},
                        {"model.y", [](const CheckContext&) { return measuring(1.0); }}}),
               std::logic_error);
  // The first registration stays.
  std::ostringstream log;
  const VerificationCase c = case_of_kind("kernel.x");
  EXPECT_EQ(reg.get(c)(CheckContext{c, "/tree", "/work", log}).metrics.at("value"), 0.0);
}

}  // namespace
}  // namespace tmlab::verify
