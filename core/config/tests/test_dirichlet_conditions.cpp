// The DOF ownership rule both models share: first condition wins, overlaps only where both are zero.
#include "core/base/error.hpp"
#include "core/config/dirichlet_conditions.hpp"

#include <gtest/gtest.h>

namespace tmlab {
namespace {

TEST(DirichletConditions, OwnershipAndConflicts) {
  DirichletCondition fixed{"fixed", {0, 1}, {true, true, true}, Vec3::Zero(), TimeFunction::constant()};
  DirichletCondition slide{"slide", {1, 2}, {false, false, true}, Vec3::Zero(), TimeFunction::constant()};
  auto owner = dirichlet_dof_owners(3, {fixed, slide});
  EXPECT_EQ(owner, (std::vector<int>{0, 0, 0, 0, 0, 0, -1, -1, 1}));  // node 1 z: both zero, first wins
  DirichletCondition push{"push", {1}, {false, false, true}, Vec3(0, 0, -0.01), TimeFunction::constant()};
  try {
    dirichlet_dof_owners(3, {fixed, push});
    FAIL() << "a conflicting non-zero value was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'fixed' and 'push' both prescribe component 2 of node 1"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(
      dirichlet_dof_owners(
          3, {DirichletCondition{"none", {}, {true, true, true}, Vec3::Zero(), TimeFunction::constant()}}),
      Error);
  EXPECT_THROW(dirichlet_dof_owners(2, {slide}), Error);  // node 2 out of range
}

}  // namespace
}  // namespace tmlab
