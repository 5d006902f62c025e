// tmlab::Error and input_error(): the "file:line: reason" form every input error uses (the line is
// left out when it is 0, e.g. for a file that cannot be opened at all).
#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace tmlab {
namespace {

TEST(Error, InputErrorNamesFileLineAndReason) {
  EXPECT_STREQ(input_error("cases/a.json", 12, "unknown key 'dtt'").what(),
               "cases/a.json:12: unknown key 'dtt'");
  EXPECT_STREQ(input_error("mesh.msh", 1, "empty").what(), "mesh.msh:1: empty");
}

TEST(Error, LineZeroIsLeftOut) {
  EXPECT_STREQ(input_error("/no/such.msh", 0, "cannot open mesh file").what(),
               "/no/such.msh: cannot open mesh file");
}

TEST(Error, IsARuntimeErrorCarryingItsMessage) {
  try {
    throw Error("node selector 'top': no node matches");
  } catch (const std::runtime_error& e) {  // the CLI catches std::exception and prints what()
    EXPECT_STREQ(e.what(), "node selector 'top': no node matches");
    EXPECT_NE(dynamic_cast<const Error*>(&e), nullptr);
  }
}

}  // namespace
}  // namespace tmlab
