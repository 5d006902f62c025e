// The liver of the paper experiments as a model problem, read once from the parameter document
// (cases/paper/xu2011_liver.json): the mesh, the long-term St Venant-Kirchhoff material, the Prony
// series, the density and the fixed base. The hereditary study's fig6 relaxation (hereditary_study.hpp)
// and the work-precision study's liver problem (work_precision.hpp) both start from it, each adding
// its own loading (a pushed node, a probe force).
#pragma once

#include "core/config/dirichlet_conditions.hpp"
#include "core/mesh/mesh.hpp"
#include "tensormass/materials/stvk_material.hpp"
#include "tensormass/viscoelastic/prony_series.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace tmlab::tm {

struct LiverProblem {
  std::string mesh_file;  ///< the mesh path resolved against the tmlab root
  Mesh mesh;
  double young = 0.0, poisson = 0.0;  ///< long-term E (Pa) and nu
  StVenantKirchhoff material;         ///< from young and poisson
  double density = 0.0;               ///< kg/m^3
  PronySeries prony = PronySeries::from_long_term({0.0}, {1.0});
  DirichletCondition base;  ///< "base": the nodes of the params' base selector, fixed
};

/// Reads the liver problem from the parameter document `params` (`where` names it in errors; the mesh
/// path is relative to `tmlab_root` unless absolute). Throws tmlab::Error naming the file and key for
/// a missing key, a missing mesh file, an inverted or degenerate tet, or a base that selects no node.
LiverProblem liver_problem(const nlohmann::json& params, const std::string& where,
                           const std::string& tmlab_root);

}  // namespace tmlab::tm
