// The elastic model a case file asks for ("model" and "material"), built on a mesh: the tensor-mass
// kernel, its total-Lagrangian oracle, the F-based kernel for any law, or their viscoelastic forms.
#pragma once

#include "core/config/case_config.hpp"
#include "core/mesh/mesh.hpp"
#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/materials/law.hpp"
#include "tensormass/materials/stvk_material.hpp"
#include "tensormass/viscoelastic/viscoelastic_base.hpp"

#include <memory>

namespace tmlab::tm::runner {

/// The elastic model a case asks for; `visco` is set when it is a viscoelastic one. tensor_mass and
/// tl_oracle are St Venant-Kirchhoff models (the paper's and its oracle): another law is refused
/// with the name of the model that runs it, hyperelastic_tl (HyperelasticTL, any law).
/// Refusals throw tmlab::Error naming the case file and the key ('model', 'material.viscoelastic').
std::unique_ptr<ElasticModel> make_model(const CaseConfig& cfg, const Mesh& mesh,
                                         const StVenantKirchhoff& material, const Law& law,
                                         const ViscoelasticBase*& visco);

}  // namespace tmlab::tm::runner
