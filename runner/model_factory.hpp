// The elastic model a case file asks for ("model" and "material"), built on a mesh: the tensor-mass
// kernel, its total-Lagrangian oracle, the F-based kernel for any law, or their viscoelastic forms.
#pragma once

#include "core/config/case_config.hpp"
#include "core/mesh/mesh.hpp"
#include "core/mesh/quadratic_mesh.hpp"
#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/materials/law.hpp"
#include "tensormass/materials/stvk_material.hpp"
#include "tensormass/viscoelastic/viscoelastic_base.hpp"

#include <memory>

namespace tmlab::tm::runner {

/// The quadratic mesh of `mesh` when the case's element is a 10-node one (mesh.element p2,
/// p2_mean_dilatation), else null.
std::unique_ptr<QuadraticMesh> make_quadratic_mesh(const CaseConfig& cfg, const Mesh& mesh);

/// The lumped nodal masses of the case's element: row sums on linear tets, HRZ (diagonal scaling)
/// on the quadratic mesh when `quadratic` is given (row sums give negative vertex masses there).
VecX make_node_mass(const CaseConfig& cfg, const Mesh& mesh, const QuadraticMesh* quadratic);

/// The elastic model a case asks for; `visco` is set when it is a viscoelastic one. tensor_mass and
/// tl_oracle are St Venant-Kirchhoff models (the paper's and its oracle): another law is refused
/// with the name of the model that runs it, hyperelastic_tl (HyperelasticTL, any law). The element
/// (mesh.element, core/config/element_kind.hpp): p1 the above; p1_anp AveragedPressureTet (or
/// ViscoelasticAveragedPressureTet); p2 and
/// p2_mean_dilatation HyperelasticP2 (or ViscoelasticHyperelasticP2) on `quadratic`, which must then
/// be given (make_quadratic_mesh). Refusals throw tmlab::Error naming the case file and the key
/// ('model', 'mesh.element', 'material.viscoelastic').
std::unique_ptr<ElasticModel> make_model(const CaseConfig& cfg, const Mesh& mesh,
                                         const QuadraticMesh* quadratic, const StVenantKirchhoff& material,
                                         const Law& law, const ViscoelasticBase*& visco);

}  // namespace tmlab::tm::runner
