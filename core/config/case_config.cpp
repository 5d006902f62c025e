#include "core/config/case_config.hpp"
#include "core/mesh/mesh_ops.hpp"

#include "core/base/enum_names.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/config/config_reader.hpp"
#include "core/config/element_kind.hpp"
#include "core/constitutive/law_catalogue.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/results/run_output.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

namespace tmlab {

namespace fs = std::filesystem;

namespace {

std::array<bool, 3> read_components(ConfigReader& r, const std::string& key) {
  const std::string s = r.get<std::string>(key, "xyz");
  std::array<bool, 3> c{false, false, false};
  if (s.empty()) throw r.error(key, "must name at least one of x, y, z");
  for (char ch : s) {
    if (ch < 'x' || ch > 'z') throw r.error(key, "must be made of the letters x, y, z (got '" + s + "')");
    c[ch - 'x'] = true;
  }
  return c;
}

TimeFunction read_function(ConfigReader& r) {
  if (!r.has("function")) return TimeFunction::constant(1.0);
  return TimeFunction::from_json(r.raw("function"), r.where() + ": key '" + r.key_path("function") + "'");
}

std::string resolve(const std::string& file, const std::vector<std::string>& dirs, const ConfigReader& r,
                    const std::string& key) {
  const fs::path p(file);
  if (p.is_absolute()) {
    if (!fs::exists(p)) throw r.error(key, "file not found: " + file);
    return file;
  }
  for (const auto& d : dirs) {
    const fs::path c = fs::path(d) / p;
    if (fs::exists(c)) return c.lexically_normal().string();
  }
  std::string tried;
  for (const auto& d : dirs) tried += " " + (fs::path(d) / p).string();
  throw r.error(key, "file not found: '" + file + "' (tried:" + tried + ")");
}

const char* const kModelNames[] = {"tensor_mass", "tl_oracle",
                                   "hyperelastic_tl"};           ///< CaseModel in declaration order
const char* const kLinearNames[] = {"auto", "ldlt", "cholmod"};  ///< SolverSpec::Linear in declaration order

/// A choice named by a string: `fallback` when the key is absent; a name `parse` does not know is
/// refused with "must be 'a', 'b' or 'c' (got 'x')", the list from `names`.
template <class E>
E read_choice(ConfigReader& r, const std::string& key, E fallback,
              std::optional<E> (*parse)(const std::string&), const std::vector<std::string>& names) {
  if (!r.has(key)) return fallback;
  const std::string name = r.require<std::string>(key);
  if (const std::optional<E> value = parse(name)) return *value;
  throw r.error(key, "must be " + choice_list(names) + " (got '" + name + "')");
}

MeshSpec parse_mesh(ConfigReader& root, const std::vector<std::string>& search_dirs) {
  ConfigReader m = root.child("mesh");
  MeshSpec mesh;
  mesh.file = resolve(m.require<std::string>("file"), search_dirs, m, "file");
  mesh.scale = m.positive("scale", 1.0);
  mesh.repair_orientation = m.get<bool>("repair_orientation", false);
  mesh.element = read_choice(m, "element", ElementKind::P1, element_kind_from_string, element_kind_names());
  m.finish();
  return mesh;
}

/// material.viscoelastic.prony: the convention and the terms {weight, tau}.
void parse_prony(ConfigReader& v, ViscoelasticSpec& vs) {
  ConfigReader p = v.child("prony");
  vs.convention = read_choice(p, "convention", PronyConvention::LongTerm, prony_convention_from_string,
                              prony_convention_names());
  const auto& terms = p.raw("terms");
  if (!terms.is_array() || terms.empty()) throw p.error("terms", "must be a non-empty list of {weight, tau}");
  double gsum = 0.0;
  for (std::size_t k = 0; k < terms.size(); ++k) {
    ConfigReader t(terms[k], p.where(), p.key_path("terms") + "[" + std::to_string(k) + "]");
    const double w = t.positive("weight", /*allow_zero=*/true);
    const double tau = t.positive("tau");
    t.finish();
    vs.weights.push_back(w);
    vs.taus.push_back(tau);
    gsum += w;
  }
  if (vs.convention == PronyConvention::Instantaneous && !(gsum < 1.0))
    throw p.error("terms",
                  "instantaneous weights g_j must sum to less than 1 (got " + std::to_string(gsum) + ")");
  p.finish();
}

/// material.viscoelastic: the scheme shorthand or history + integration, the relaxation, the series.
ViscoelasticSpec parse_viscoelastic(ConfigReader& m) {
  ConfigReader v = m.child("viscoelastic");
  ViscoelasticSpec vs;
  vs.enabled = true;
  if (v.has("scheme")) {
    const std::string scheme = v.require<std::string>("scheme");
    if (v.has("history") || v.has("integration"))
      throw v.error("scheme", "is a shorthand for history + integration: give either it or them");
    vs.scheme = prony_scheme_from_string(scheme);
    if (!vs.scheme)
      throw v.error("scheme", "unknown scheme '" + scheme + "' (expected " +
                                  choice_list(prony_scheme_names(), "") + ")");
    const PronySchemeParts parts = scheme_parts(*vs.scheme);
    vs.history = parts.history, vs.integration = parts.integration;
  } else {
    vs.history =
        read_choice(v, "history", PronyHistory::Pk2, prony_history_from_string, prony_history_names());
    vs.integration = read_choice(v, "integration", PronyIntegration::ExactLinear,
                                 prony_integration_from_string, prony_integration_names());
  }
  vs.relaxation = read_choice(v, "relaxation", PronyRelaxation::Full, prony_relaxation_from_string,
                              prony_relaxation_names());
  if (vs.relaxation == PronyRelaxation::Deviatoric && vs.history != PronyHistory::Pk2)
    throw v.error("relaxation",
                  "'deviatoric' needs the pk2 (objective) history: nodal forces have no deviatoric part");
  parse_prony(v, vs);
  v.finish();
  return vs;
}

double finite_number(ConfigReader& m, const std::string& key) {
  const double x = m.require<double>(key);
  if (!std::isfinite(x)) throw m.error(key, "must be finite");
  return x;
}

/// material: the law, its parameters (docs/case-files.md), the density and the viscoelasticity.
/// Impossible parameters (core/constitutive/material_law.hpp, law_parameter_problem) are refused
/// naming the key, so every model receives a law it can build.
MaterialSpec parse_material(ConfigReader& root) {
  ConfigReader m = root.child("material");
  MaterialSpec material;
  material.law = read_choice(m, "law", MaterialLaw::StVK, material_law_from_string, law_name_list());
  const MaterialLaw law = material.law;
  const LawDescriptor& descriptor = law_descriptor(law);
  const std::string law_name = to_string(law);
  const std::vector<std::string> keys = law_case_keys(law);
  std::string key_list;
  for (const std::string& k : keys) key_list += (key_list.empty() ? "" : ", ") + k;
  // A key of another law gets a message naming this law's keys; any other stray key is reported by
  // finish() as an unknown key.
  for (auto it = m.json().begin(); it != m.json().end(); ++it) {
    const std::string& k = it.key();
    bool other_law = false;
    for (const LawDescriptor& other : law_catalogue()) {
      const std::vector<std::string> ks = law_case_keys(other.law);
      other_law = other_law || std::find(ks.begin(), ks.end(), k) != ks.end();
    }
    if (other_law && std::find(keys.begin(), keys.end(), k) == keys.end())
      throw m.error(
          k, "is not a parameter of law '" + law_name + "' (its keys: " + key_list + "; docs/case-files.md)");
  }
  LawParameters& p = material.parameters;
  for (const LawParameterInfo& info : descriptor.parameters) {
    if (info.list)
      p.*info.values = m.require<std::vector<double>>(info.case_key);
    else if (info.has_default && !m.has(info.case_key))
      p.*info.scalar = info.default_value;
    else
      p.*info.scalar = finite_number(m, info.case_key);
  }
  std::optional<double> nu_for_kappa;
  if (descriptor.bulk == BulkResponse::KappaOrPoisson) {
    // The bulk modulus, or Poisson's ratio of the small-strain limit (kappa from the shear modulus).
    const std::string kappa = bulk_modulus_parameter().case_key, nu = poisson_parameter().case_key;
    if (m.has(kappa) == m.has(nu))
      throw m.error(kappa, "or '" + nu + "': law '" + law_name + "' needs exactly one of the bulk modulus '" +
                               kappa + "' (Pa) and Poisson's ratio '" + nu + "'");
    if (m.has(kappa)) {
      p.kappa = finite_number(m, kappa);
    } else {
      nu_for_kappa = m.require<double>(nu);
      if (const std::string why = parameter_refusal(poisson_parameter(), *nu_for_kappa); !why.empty())
        throw m.error(nu, why);
      p.kappa = 1.0;  // checked below with the shear modulus; replaced by the kappa of nu
    }
  }
  if (const LawParameterProblem problem = law_parameter_problem(law, p); !problem.empty())
    throw m.error(problem.key, problem.reason + " (law '" + law_name + "')");
  const SmallStrainModuli moduli = small_strain_moduli(law, p);
  if (nu_for_kappa) p.kappa = bulk_from_poisson(moduli.shear, *nu_for_kappa);
  // E and nu of the small-strain limit: as given for stvk and neo_hookean, derived for the others.
  const bool given = descriptor.bulk == BulkResponse::YoungPoisson;
  material.young = given ? p.young : small_strain_moduli(law, p).young();
  material.poisson = given ? p.poisson : small_strain_moduli(law, p).poisson();
  material.density = m.positive("density");
  if (m.has("viscoelastic")) material.viscoelastic = parse_viscoelastic(m);
  m.finish();
  return material;
}

std::vector<BoundarySpec> parse_boundary(ConfigReader& root) {
  std::vector<BoundarySpec> out;
  if (!root.has("boundary")) return out;
  const auto& arr = root.raw("boundary");
  if (!arr.is_array()) throw root.error("boundary", "must be a list");
  for (std::size_t i = 0; i < arr.size(); ++i) {
    ConfigReader b(arr[i], root.where(), "boundary[" + std::to_string(i) + "]");
    BoundarySpec s;
    s.name = b.get<std::string>("name", "boundary" + std::to_string(i));
    s.nodes = NodeSelector::from_json(b.raw("nodes"), root.where() + ": key '" + b.key_path("nodes") + "'");
    s.components = read_components(b, "components");
    s.value = b.has("value") ? b.vec3("value") : Vec3::Zero();
    s.function = read_function(b);
    b.finish();
    out.push_back(s);
  }
  return out;
}

/// loads[i]: one nodal force, pressure, traction or gravity load.
LoadSpec parse_load(const nlohmann::json& j, const std::string& where, std::size_t i) {
  ConfigReader l(j, where, "loads[" + std::to_string(i) + "]");
  auto selector = [&](const std::string& key) {
    return NodeSelector::from_json(l.raw(key), where + ": key '" + l.key_path(key) + "'");
  };
  LoadSpec s;
  const std::string type = l.require<std::string>("type");
  s.name = l.get<std::string>("name", type + std::to_string(i));
  if (type == "nodal_force") {
    s.type = LoadSpec::Type::NodalForce;
    s.selector = selector("nodes");
    s.vector = l.vec3("force");
  } else if (type == "pressure") {
    s.type = LoadSpec::Type::Pressure;
    s.selector = selector("faces");
    s.pressure = l.require<double>("pressure");
    if (!std::isfinite(s.pressure)) throw l.error("pressure", "must be finite");
    s.follower = l.get<bool>("follower", false);
  } else if (type == "traction") {
    // A dead traction vector per unit reference area on the selected boundary faces.
    s.type = LoadSpec::Type::Traction;
    s.selector = selector("faces");
    s.vector = l.vec3("traction");
  } else if (type == "gravity") {
    s.type = LoadSpec::Type::Gravity;
    s.vector = l.vec3("acceleration");
  } else {
    throw l.error("type",
                  "unknown load type '" + type + "' (expected nodal_force, pressure, traction or gravity)");
  }
  s.function = read_function(l);
  l.finish();
  return s;
}

std::vector<LoadSpec> parse_loads(ConfigReader& root) {
  std::vector<LoadSpec> out;
  if (!root.has("loads")) return out;
  const auto& arr = root.raw("loads");
  if (!arr.is_array()) throw root.error("loads", "must be a list");
  for (std::size_t i = 0; i < arr.size(); ++i) out.push_back(parse_load(arr[i], root.where(), i));
  return out;
}

/// solver.newton (static and implicit solvers).
void parse_newton(ConfigReader& s, SolverSpec& solver) {
  if (solver.type == SolverSpec::Type::Explicit)
    throw s.error("newton", "is not used by the explicit solver");
  ConfigReader n = s.child("newton");
  solver.max_iterations = n.get<int>("max_iterations", 25);
  if (solver.max_iterations < 1) throw n.error("max_iterations", "must be >= 1");
  solver.rtol = n.positive("rtol", 1e-10);
  solver.atol = n.positive("atol", 1e-14, true);
  if (n.has("line_search")) {
    // "energy" | "residual" | "none"; true and false are kept for older case files (true = energy).
    const nlohmann::json& ls = n.raw("line_search");
    const auto named = ls.is_string() ? line_search_from_string(ls.get<std::string>()) : std::nullopt;
    if (ls.is_boolean()) {
      solver.line_search = ls.get<bool>() ? LineSearch::Energy : LineSearch::None;
    } else if (named) {
      solver.line_search = *named;
    } else {
      throw n.error("line_search", "must be \"energy\", \"residual\" or \"none\" (got " + ls.dump() + ")");
    }
  }
  solver.max_cutbacks = n.get<int>("max_cutbacks", 8);
  if (solver.max_cutbacks < 0) throw n.error("max_cutbacks", "must be >= 0");
  n.finish();
}

/// The time step, scheme or stability check, and damping of the explicit and implicit solvers.
void parse_dynamics(ConfigReader& s, SolverSpec& solver) {
  solver.dt = s.positive("dt");
  if (solver.dt > solver.t_end) throw s.error("dt", "must not exceed t_end");
  const double n = solver.t_end / solver.dt;
  if (n > 1e8) throw s.error("dt", "gives more than 1e8 steps");
  solver.steps = static_cast<int>(std::ceil(n - 1e-9));
  if (solver.type == SolverSpec::Type::Implicit) {
    const std::string scheme = s.get<std::string>("scheme", "newmark");
    const std::optional<ImplicitScheme> named = implicit_scheme_from_string(scheme);
    if (!named) throw s.error("scheme", "must be 'newmark' or 'backward_euler' (got '" + scheme + "')");
    solver.scheme = *named;
  } else {
    solver.check_stability = s.get<bool>("check_stability", true);
  }
  if (s.has("damping")) {
    ConfigReader d = s.child("damping");
    solver.damping_alpha = d.positive("alpha", 0.0, true);
    solver.damping_beta = d.positive("beta", 0.0, true);
    d.finish();
  }
}

SolverSpec parse_solver(ConfigReader& root) {
  ConfigReader s = root.child("solver");
  SolverSpec solver;
  const std::string type = s.require<std::string>("type");
  solver.t_end = s.positive("t_end", 1.0);
  if (type == "static") {
    solver.type = SolverSpec::Type::Static;
    solver.steps = s.get<int>("steps", 10);
    if (solver.steps < 1) throw s.error("steps", "must be >= 1");
  } else if (type == "explicit" || type == "implicit") {
    solver.type = type == "explicit" ? SolverSpec::Type::Explicit : SolverSpec::Type::Implicit;
    parse_dynamics(s, solver);
  } else {
    throw s.error("type", "unknown solver '" + type + "' (expected static, explicit or implicit)");
  }
  if (s.has("newton")) parse_newton(s, solver);
  if (s.has("linear")) {
    if (solver.type == SolverSpec::Type::Explicit)
      throw s.error("linear", "is not used by the explicit solver (no linear solves)");
    solver.linear = read_choice(s, "linear", SolverSpec::Linear::Auto, linear_solver_from_string,
                                enum_names(kLinearNames));
  }
  s.finish();
  return solver;
}

OutputSpec parse_output(ConfigReader& root) {
  OutputSpec output;
  if (!root.has("output")) return output;
  ConfigReader o = root.child("output");
  output.every = o.get<int>("every", 1);
  if (output.every < 1) throw o.error("every", "must be >= 1");
  output.vtu = o.get<bool>("vtu", true);
  output.xdmf = o.get<bool>("xdmf", true);
  output.plots = o.get<bool>("plots", true);
  if (o.has("probes")) {
    const auto& arr = o.raw("probes");
    if (!arr.is_array()) throw o.error("probes", "must be a list");
    for (std::size_t i = 0; i < arr.size(); ++i) {
      ConfigReader p(arr[i], o.where(), o.key_path("probes") + "[" + std::to_string(i) + "]");
      ProbeSpec ps;
      ps.name = p.require<std::string>("name");
      ps.point = p.vec3("point");
      p.finish();
      output.probes.push_back(ps);
    }
  }
  o.finish();
  return output;
}

}  // namespace

std::string to_string(CaseModel m) { return enum_name(kModelNames, m); }

std::string to_string(SolverSpec::Linear l) { return enum_name(kLinearNames, l); }

std::optional<SolverSpec::Linear> linear_solver_from_string(const std::string& name) {
  return enum_from_name<SolverSpec::Linear>(kLinearNames, name);
}

std::optional<CaseModel> case_model_from_string(const std::string& name) {
  return enum_from_name<CaseModel>(kModelNames, name);
}

CaseConfig parse_case(const nlohmann::json& doc, const std::string& where,
                      const std::vector<std::string>& search_dirs) {
  CaseConfig c;
  c.file = where;
  ConfigReader root(doc, where);
  c.name = root.require<std::string>("name");
  if (const std::string problem = result_name_problem(c.name); !problem.empty())
    throw root.error("name", "'" + c.name + "' " + problem + ": it names the result directory");
  c.description = root.get<std::string>("description", "");
  c.model =
      read_choice(root, "model", CaseModel::TensorMass, case_model_from_string, enum_names(kModelNames));
  c.mesh = parse_mesh(root, search_dirs);
  c.material = parse_material(root);
  c.boundary = parse_boundary(root);
  c.loads = parse_loads(root);
  c.solver = parse_solver(root);
  c.output = parse_output(root);
  if (root.has("contact")) c.contact = parse_contact_spec(root.raw("contact"), where, "contact");
  root.finish();
  return c;
}

MaterialSpec parse_material_section(const nlohmann::json& material, const std::string& where) {
  const nlohmann::json doc = {{"material", material}};
  ConfigReader root(doc, where);
  return parse_material(root);
}

namespace {

// The sections of effective_case_json, each the case-file form of one parse_* above.
using nlohmann::json;

json v3(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

json material_json(const MaterialSpec& m) {
  json material = {{"law", to_string(m.law)}, {"density", m.density}};
  const LawParameters& p = m.parameters;
  const LawDescriptor& descriptor = law_descriptor(m.law);
  for (const LawParameterInfo& info : descriptor.parameters) {
    if (info.list)
      material[info.case_key] = p.*info.values;
    else
      material[info.case_key] = p.*info.scalar;
  }
  if (descriptor.bulk == BulkResponse::KappaOrPoisson) material[bulk_modulus_parameter().case_key] = p.kappa;
  const ViscoelasticSpec& vs = m.viscoelastic;
  if (vs.enabled) {
    json terms = json::array();
    for (std::size_t k = 0; k < vs.weights.size(); ++k)
      terms.push_back({{"weight", vs.weights[k]}, {"tau", vs.taus[k]}});
    material["viscoelastic"] = {{"history", to_string(vs.history)},
                                {"integration", to_string(vs.integration)},
                                {"relaxation", to_string(vs.relaxation)},
                                {"prony", {{"convention", to_string(vs.convention)}, {"terms", terms}}}};
  }
  return material;
}

json boundary_json(const std::vector<BoundarySpec>& conditions) {
  json boundary = json::array();
  for (const BoundarySpec& b : conditions) {
    std::string comps;
    for (int k = 0; k < 3; ++k)
      if (b.components[static_cast<std::size_t>(k)]) comps += "xyz"[k];
    boundary.push_back({{"name", b.name},
                        {"nodes", b.nodes.to_json()},
                        {"components", comps},
                        {"value", v3(b.value)},
                        {"function", b.function.to_json()}});
  }
  return boundary;
}

json load_json(const LoadSpec& l) {
  json j = {{"name", l.name}, {"function", l.function.to_json()}};
  switch (l.type) {
    case LoadSpec::Type::NodalForce:
      j["type"] = "nodal_force", j["nodes"] = l.selector.to_json(), j["force"] = v3(l.vector);
      break;
    case LoadSpec::Type::Pressure:
      j["type"] = "pressure", j["faces"] = l.selector.to_json(), j["pressure"] = l.pressure;
      j["follower"] = l.follower;
      break;
    case LoadSpec::Type::Traction:
      j["type"] = "traction", j["faces"] = l.selector.to_json(), j["traction"] = v3(l.vector);
      break;
    case LoadSpec::Type::Gravity:
      j["type"] = "gravity", j["acceleration"] = v3(l.vector);
      break;
  }
  return j;
}

json solver_json(const SolverSpec& sv) {
  json solver = {{"t_end", sv.t_end}};
  if (sv.type == SolverSpec::Type::Static) {
    solver["type"] = "static";
    solver["steps"] = sv.steps;
  } else {
    solver["type"] = sv.type == SolverSpec::Type::Explicit ? "explicit" : "implicit";
    solver["dt"] = sv.dt;
    if (sv.type == SolverSpec::Type::Implicit)
      solver["scheme"] = to_string(sv.scheme);
    else
      solver["check_stability"] = sv.check_stability;
    solver["damping"] = {{"alpha", sv.damping_alpha}, {"beta", sv.damping_beta}};
  }
  if (sv.type != SolverSpec::Type::Explicit) {
    solver["linear"] = to_string(sv.linear);
    solver["newton"] = {{"max_iterations", sv.max_iterations},
                        {"rtol", sv.rtol},
                        {"atol", sv.atol},
                        {"line_search", to_string(sv.line_search)},
                        {"max_cutbacks", sv.max_cutbacks}};
  }
  return solver;
}

json output_json(const OutputSpec& o) {
  json probes = json::array();
  for (const ProbeSpec& p : o.probes) probes.push_back({{"name", p.name}, {"point", v3(p.point)}});
  return {{"every", o.every}, {"vtu", o.vtu}, {"xdmf", o.xdmf}, {"plots", o.plots}, {"probes", probes}};
}

}  // namespace

nlohmann::json effective_case_json(const CaseConfig& c) {
  json doc = {{"name", c.name},
              {"description", c.description},
              {"model", to_string(c.model)},
              {"mesh",
               {{"file", c.mesh.file},
                {"scale", c.mesh.scale},
                {"repair_orientation", c.mesh.repair_orientation},
                {"element", to_string(c.mesh.element)}}}};
  doc["material"] = material_json(c.material);
  doc["boundary"] = boundary_json(c.boundary);
  json loads = json::array();
  for (const LoadSpec& l : c.loads) loads.push_back(load_json(l));
  doc["loads"] = loads;
  doc["solver"] = solver_json(c.solver);
  doc["output"] = output_json(c.output);
  if (c.contact.enabled) doc["contact"] = contact_spec_json(c.contact);
  return doc;
}

Mesh load_case_mesh(const MeshSpec& spec, MeshReport& report, int& repaired) {
  Mesh mesh = read_mesh(spec.file);
  if (spec.scale != 1.0) scale_mesh(mesh, spec.scale);
  repaired = spec.repair_orientation ? repair_orientation(mesh) : 0;
  report = analyse_mesh(mesh);
  if (!report.inverted.empty())
    throw Error(spec.file + ": tet " + std::to_string(report.inverted.front()) + " is inverted (" +
                std::to_string(report.inverted.size()) +
                " inverted in all); set mesh.repair_orientation = true or run 'tmlab mesh check --repair'");
  if (!report.degenerate.empty())
    throw Error(spec.file + ": tet " + std::to_string(report.degenerate.front()) +
                " is degenerate (zero volume; " + std::to_string(report.degenerate.size()) + " in all)");
  return mesh;
}

CaseConfig load_case(const std::string& path, const std::string& tmlab_root) {
  const nlohmann::json doc = ConfigReader::parse_file(path);
  const std::string dir = fs::path(path).parent_path().string();
  return parse_case(doc, path, {dir.empty() ? "." : dir, tmlab_root});
}

Index probe_node(const Mesh& mesh, const ProbeSpec& probe, const std::string& case_file) {
  if (mesh.num_points() == 0) throw Error(case_file + ": probe '" + probe.name + "': the mesh has no nodes");
  const Index n = nearest_node(mesh, probe.point);
  Vec3 lo = mesh.points[0], hi = mesh.points[0];
  for (const Vec3& x : mesh.points) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const double diagonal = (hi - lo).norm(), distance = (mesh.points[n] - probe.point).norm();
  if (distance > 0.05 * diagonal) {
    std::ostringstream msg;
    msg << case_file << ": output.probes '" << probe.name << "' at (" << probe.point.x() << ", "
        << probe.point.y() << ", " << probe.point.z() << ") is " << distance
        << " m from the nearest mesh node, more than 5 % of the mesh's bounding-box diagonal (" << diagonal
        << " m; the mesh spans (" << lo.x() << ", " << lo.y() << ", " << lo.z() << ") to (" << hi.x() << ", "
        << hi.y() << ", " << hi.z() << ")): check the point and its units";
    throw Error(msg.str());
  }
  return n;
}

}  // namespace tmlab
