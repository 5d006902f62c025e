// DirichletSet: conflicting conditions are refused, agreeing (zero) overlaps allowed, values applied
// with their time functions.
#include "core/base/error.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/system/dirichlet.hpp"
#include "tensormass/system/external_loads.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tmlab::tm {
namespace {

TEST(Dirichlet, ConflictingConditionsAreRejected) {
  DirichletCondition a{"a", {0, 1}, {true, true, true}, Vec3(0, 0, 0.1), TimeFunction::constant()};
  DirichletCondition b{"b", {1, 2}, {true, true, true}, Vec3(0, 0, 0.2), TimeFunction::constant()};
  try {
    DirichletSet s(3, {a, b});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'a' and 'b'"), std::string::npos) << e.what();
  }
  DirichletCondition z1{"z1", {0, 1}, {true, true, true}, Vec3::Zero(), TimeFunction::constant()};
  DirichletCondition z2{"z2", {1, 2}, {true, true, true}, Vec3::Zero(), TimeFunction::constant()};
  EXPECT_NO_THROW(DirichletSet(3, {z1, z2}));
}

TEST(Dirichlet, AppliesValuesWithTheirTimeFunctions) {
  DirichletCondition fixed{"fixed", {0}, {true, true, true}, Vec3::Zero(), TimeFunction::constant()};
  DirichletCondition push{"push", {1}, {false, false, true}, Vec3(0, 0, -0.01), TimeFunction::ramp(0.0, 2.0)};
  const DirichletSet bc(2, {fixed, push});
  EXPECT_EQ(bc.dofs(), (std::vector<Index>{0, 1, 2, 5}));
  VecX u = VecX::Constant(6, 7.0);
  bc.apply(1.0, u);
  EXPECT_EQ(u[0], 0.0);
  EXPECT_EQ(u[3], 7.0);  // free DOFs untouched
  EXPECT_DOUBLE_EQ(u[5], -0.005);
  EXPECT_TRUE(bc.is_constrained(5));
  EXPECT_FALSE(bc.is_constrained(4));
}

}  // namespace
}  // namespace tmlab::tm
