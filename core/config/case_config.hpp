// A case file: geometry, material, boundary conditions, loads, solver and outputs of one run,
// read strictly from JSON (unknown keys are errors). It is model-agnostic: the tensor-mass runner
// and the deal.II reference both build their problem from it. docs/case-files.md is the reference.
#pragma once

#include "core/config/contact_spec.hpp"
#include "core/config/implicit_scheme.hpp"
#include "core/config/line_search.hpp"
#include "core/config/time_function.hpp"
#include "core/constitutive/material_law.hpp"
#include "core/constitutive/prony.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "core/mesh/mesh_quality.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace tmlab {

/// The fast model's element (`mesh.element`; core/config/element_kind.hpp, docs/elements.md).
enum class ElementKind { P1, P1Anp, P2, P2MeanDilatation };

struct MeshSpec {
  std::string file;    ///< resolved path
  double scale = 1.0;  ///< multiply coordinates (e.g. 0.001 for a mesh in mm)
  bool repair_orientation = false;
  ElementKind element = ElementKind::P1;  ///< p1 | p1_anp | p2 | p2_mean_dilatation
};

/// Prony-series viscoelasticity (issue 3; docs/theory/viscoelasticity.md). The choices are the
/// shared vocabulary of core/constitutive/prony.hpp, parsed once here; the weights are as given.
struct ViscoelasticSpec {
  bool enabled = false;
  PronyConvention convention =
      PronyConvention::LongTerm;             ///< long_term (alpha_j, eq. 10) | instantaneous (g_j, eq. 24)
  std::vector<double> weights, taus;         ///< one per Prony term
  PronyHistory history = PronyHistory::Pk2;  ///< nodal_force (the seed's eq. 20) | pk2 (objective)
  PronyIntegration integration = PronyIntegration::ExactLinear;  ///< midpoint | exact_linear | backward_euler
  PronyRelaxation relaxation = PronyRelaxation::Full;            ///< full | deviatoric (pk2 only)
  std::optional<PronyScheme> scheme;  ///< the shorthand given, if any (xu2011, objective, ...)
};

/// The material section: the law and its parameters (core/constitutive/material_law.hpp; each
/// law's keys in docs/case-files.md), the density and the viscoelasticity. The models build their
/// law from `law` + `parameters` (the fast model through tensormass/materials/law_factory.hpp).
struct MaterialSpec {
  MaterialLaw law = MaterialLaw::StVK;
  LawParameters parameters;  ///< the law's parameters; kappa resolved when the case gave nu instead
  /// Young's modulus (Pa) and Poisson's ratio: as given for stvk and neo_hookean; for the other laws
  /// those of their small-strain limit (small_strain_moduli), derived. The long-term modulus E_inf of
  /// a viscoelastic material.
  double young = 0.0;
  double poisson = 0.0;
  double density = 0.0;  ///< kg/m^3
  ViscoelasticSpec viscoelastic;
};

struct BoundarySpec {
  std::string name;
  NodeSelector nodes;
  std::array<bool, 3> components{true, true, true};
  Vec3 value = Vec3::Zero();  ///< m, scaled by function(t)
  TimeFunction function = TimeFunction::constant(1.0);
};

struct LoadSpec {
  enum class Type { NodalForce, Pressure, Traction, Gravity };
  Type type = Type::NodalForce;
  std::string name;
  NodeSelector selector;       ///< nodes (nodal force) or faces (pressure)
  Vec3 vector = Vec3::Zero();  ///< total force (N), traction (Pa, per reference area) or gravity (m/s^2)
  double pressure = 0.0;       ///< Pa
  bool follower = false;
  TimeFunction function = TimeFunction::constant(1.0);
};

struct SolverSpec {
  enum class Type { Static, Explicit, Implicit };
  Type type = Type::Static;
  double t_end = 1.0;  ///< end time (pseudo-time for static)
  int steps = 10;      ///< static: number of load steps; dynamics: derived from dt
  double dt = 0.0;     ///< dynamics: time step
  ImplicitScheme scheme = ImplicitScheme::Newmark;  ///< implicit: newmark | backward_euler
  double damping_alpha = 0.0, damping_beta = 0.0;
  int max_iterations = 25;
  double rtol = 1e-10;
  double atol = 1e-14;
  LineSearch line_search = LineSearch::Energy;  ///< core/config/line_search.hpp
  int max_cutbacks = 8;
  bool check_stability = true;
  /// solver.linear (static, implicit): the sparse direct solver of the Newton steps (docs/case-files.md):
  /// "auto" (the default: SuiteSparse CHOLMOD's LL^T, Eigen's LDL^T for a tangent that is not positive
  /// definite) | "cholmod" (the same solves: the name this choice had before it became the default) |
  /// "ldlt" (Eigen's SimplicialLDLT for every tangent).
  enum class Linear { Auto, Ldlt, Cholmod };
  Linear linear = Linear::Auto;
};
/// "auto" | "ldlt" | "cholmod", and back (nothing for any other name).
std::string to_string(SolverSpec::Linear l);
std::optional<SolverSpec::Linear> linear_solver_from_string(const std::string& name);

struct ProbeSpec {
  std::string name;
  Vec3 point = Vec3::Zero();  ///< the nearest mesh node is tracked
};

struct OutputSpec {
  int every = 1;  ///< write fields every n-th step (the last step always)
  bool vtu = true;
  bool xdmf = true;
  bool plots = true;
  std::vector<ProbeSpec> probes;
};

/// The fast model's elastic kernel: tensor_mass (Picinbono's tensors, relative displacements; St
/// Venant-Kirchhoff only, the paper's model) | tl_oracle (the slow St VK total-Lagrangian oracle) |
/// hyperelastic_tl (the F-based kernel for every law of core/constitutive/material_law.hpp, elastic
/// or with the objective Prony scheme). The reference is chosen on the command line.
enum class CaseModel { TensorMass, TlOracle, HyperelasticTL };
std::string to_string(CaseModel m);
/// The model a name denotes ("tensor_mass", "tl_oracle", "hyperelastic_tl"), or nothing.
std::optional<CaseModel> case_model_from_string(const std::string& name);

struct CaseConfig {
  std::string name;
  std::string description;
  std::string file;                         ///< where the case came from ("<embedded>" for the demo)
  CaseModel model = CaseModel::TensorMass;  ///< tensor_mass | tl_oracle | hyperelastic_tl
  MeshSpec mesh;
  MaterialSpec material;
  std::vector<BoundarySpec> boundary;
  std::vector<LoadSpec> loads;
  SolverSpec solver;
  OutputSpec output;
  ContactSpec contact;  ///< rigid bodies pressed into the sample (core/config/contact_spec.hpp)
};

/// Parses a case document. `where` names it in messages; relative mesh paths are looked up in
/// `search_dirs` in order (the case file's directory first, then the tmlab root).
CaseConfig parse_case(const nlohmann::json& doc, const std::string& where,
                      const std::vector<std::string>& search_dirs);
/// A case file's `material` section alone, checked exactly as parse_case checks it (the test rigs
/// refuse an impossible material before they write a case). `where` names the document in messages
/// ("<where>: key 'material.E': ...").
MaterialSpec parse_material_section(const nlohmann::json& material, const std::string& where);
/// Reads the case's mesh, scales it, re-orients tets when asked, and refuses a mesh with inverted
/// or degenerate tets (tmlab::Error naming the file and the first bad tet). Every model's runner
/// starts here. `report` receives the mesh report, `repaired` the number of re-oriented tets.
Mesh load_case_mesh(const MeshSpec& spec, MeshReport& report, int& repaired);

/// Reads and parses a case file.
CaseConfig load_case(const std::string& path, const std::string& tmlab_root);

/// The case in case-file form with every default filled in and every choice resolved (the mesh
/// path absolute, a viscoelastic "scheme" shorthand as its history + integration): what the run
/// actually used, for the manifest. parse_case() of it gives the same case again.
nlohmann::json effective_case_json(const CaseConfig& config);

/// The mesh node a probe tracks: the nearest node to its point. A point farther from every node
/// than 5 % of the mesh's bounding-box diagonal is refused (a typo or wrong units would otherwise
/// snap silently to some boundary node); the error names the case file, the probe and the distance.
Index probe_node(const Mesh& mesh, const ProbeSpec& probe, const std::string& case_file);

}  // namespace tmlab
