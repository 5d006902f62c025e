// The fast model's kernel for each law: tensor_mass for St VK only, hyperelastic_tl for the rest.
#include "core/config/fast_model.hpp"

#include <gtest/gtest.h>

namespace tmlab {
namespace {

TEST(FastModel, StVKRunsOnTheTensorMassKernel) {
  EXPECT_EQ(fast_model_for(MaterialLaw::StVK), CaseModel::TensorMass);
}

TEST(FastModel, EveryOtherLawRunsOnTheFBasedKernel) {
  for (const char* name : kMaterialLawNames) {
    const MaterialLaw law = *material_law_from_string(name);
    if (law == MaterialLaw::StVK) continue;
    EXPECT_EQ(fast_model_for(law), CaseModel::HyperelasticTL) << name;
  }
}

}  // namespace
}  // namespace tmlab
