// The fast model's kernel for a law: see fast_model.hpp.
#include "core/config/fast_model.hpp"

namespace tmlab {

CaseModel fast_model_for(MaterialLaw law) {
  return law == MaterialLaw::StVK ? CaseModel::TensorMass : CaseModel::HyperelasticTL;
}

}  // namespace tmlab
