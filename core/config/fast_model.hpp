// Which kernel of the fast model runs a law when the caller does not name one (tmlab compare, the
// verification's reference comparisons): the paper's tensor-mass kernel for St Venant-Kirchhoff,
// the F-based kernel (hyperelastic_tl) for every other law, which tensor_mass does not have.
#pragma once

#include "core/config/case_config.hpp"
#include "core/constitutive/material_law.hpp"

namespace tmlab {

/// St VK -> CaseModel::TensorMass; any other law -> CaseModel::HyperelasticTL.
CaseModel fast_model_for(MaterialLaw law);

}  // namespace tmlab
