// The fast model's kernel for a law: see fast_model.hpp.
#include "core/config/fast_model.hpp"

#include "core/constitutive/law_catalogue.hpp"

namespace tmlab {

CaseModel fast_model_for(MaterialLaw law) {
  // The catalogue's kernel column says which laws the tensor-mass kernel runs (St VK).
  return law_descriptor(law).tensor_mass ? CaseModel::TensorMass : CaseModel::HyperelasticTL;
}

}  // namespace tmlab
