// The problem a case file describes, built once per run: the mesh (read, scaled, checked), the
// material and model, the Dirichlet conditions, the loads, the mechanical system and the probes.
#pragma once

#include "core/config/case_config.hpp"
#include "core/config/dirichlet_conditions.hpp"
#include "core/mesh/mesh.hpp"
#include "core/mesh/mesh_quality.hpp"
#include "core/mesh/quadratic_mesh.hpp"
#include "tensormass/kernels/elastic_model.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/materials/law.hpp"
#include "tensormass/materials/stvk_material.hpp"
#include "tensormass/system/external_loads.hpp"
#include "tensormass/system/mechanical_system.hpp"
#include "tensormass/viscoelastic/viscoelastic_base.hpp"

#include <memory>
#include <vector>

namespace tmlab::tm::runner {

/// The problem a case describes: mesh (read, scaled and checked: an inverted or degenerate tet stops
/// the run here), material, model, constraints, loads and probes. Built in place and never moved:
/// the model, loads and system refer to the mesh.
///
/// Quadratic elements (mesh.element p2, p2_mean_dilatation; docs/elements.md): the model, masses,
/// loads, constraints and every nodal output live on the points of `quadratic` (the linear mesh's
/// vertices keep their indices, the midside nodes follow). Constraints selected on the linear mesh
/// are extended to the midside nodes (a surface group: the nodes of its 6-node faces; any other
/// selection: the midside node of every edge whose ends are both selected); nodal forces act on the
/// selected vertices; pressure and traction give the consistent quadratic face load; probes are
/// vertices.
struct Problem {
  /// Builds everything; bad input (mesh, parameters, an empty selection, a static run without
  /// constraints, a probe off the mesh) throws tmlab::Error naming the case file and the key.
  explicit Problem(const CaseConfig& config);
  Problem(const Problem&) = delete;
  Problem& operator=(const Problem&) = delete;

  const CaseConfig& cfg;
  MeshReport report;
  int repaired = 0;
  Mesh mesh;  ///< the linear mesh, as read (its tets are the elements' vertex tets)
  /// The quadratic mesh of `mesh` for the 10-node elements, else null.
  std::unique_ptr<QuadraticMesh> quadratic;
  /// Quadratic elements: `mesh`'s tets over the quadratic mesh's points (the node set loads, the
  /// XDMF output and node-indexed helpers see); empty for linear elements (node_mesh() is `mesh`).
  Mesh quadratic_nodes;
  double size;                 ///< bounding-box diagonal, m
  StVenantKirchhoff material;  ///< the small-strain St VK (the law of tensor_mass and tl_oracle)
  Law law;                     ///< the case's law (hyperelastic_tl; St VK as `material` otherwise)
  /// The model when it is viscoelastic (ViscoelasticStVK or ViscoelasticHyperelastic), else null.
  const ViscoelasticBase* visco = nullptr;
  std::unique_ptr<ElasticModel> model;
  TotalLagrangianStVK fields_kernel;  // per-tet F for output (geometry only: the stress is the law's)
  VecX node_mass;
  std::vector<DirichletCondition> conditions;
  ExternalLoads loads;
  MechanicalSystem system;
  std::vector<Index> probe_nodes;

  /// The mesh whose points are the model's nodes: `mesh` (linear), `quadratic_nodes` (quadratic).
  const Mesh& node_mesh() const { return quadratic ? quadratic_nodes : mesh; }
  Index num_nodes() const { return node_mesh().num_points(); }
};

}  // namespace tmlab::tm::runner
