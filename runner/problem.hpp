// The problem a case file describes, built once per run: the mesh (read, scaled, checked), the
// material and model, the Dirichlet conditions, the loads, the mechanical system and the probes.
#pragma once

#include "core/config/case_config.hpp"
#include "core/config/dirichlet_conditions.hpp"
#include "core/mesh/mesh.hpp"
#include "core/mesh/mesh_quality.hpp"
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
struct Problem {
  /// Builds everything; bad input (mesh, parameters, an empty selection, a static run without
  /// constraints, a probe off the mesh) throws tmlab::Error naming the case file and the key.
  explicit Problem(const CaseConfig& config);
  Problem(const Problem&) = delete;
  Problem& operator=(const Problem&) = delete;

  const CaseConfig& cfg;
  MeshReport report;
  int repaired = 0;
  Mesh mesh;
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
};

}  // namespace tmlab::tm::runner
