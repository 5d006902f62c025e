#include "core/config/case_config.hpp"
#include "core/mesh/mesh_ops.hpp"

#include "core/base/error.hpp"
#include "core/config/config_reader.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/results/run_output.hpp"

#include <cmath>
#include <filesystem>

namespace tmlab {

namespace fs = std::filesystem;

namespace {

Vec3 read_vec3(ConfigReader& r, const std::string& key) {
  const auto v = r.require<std::vector<double>>(key);
  if (v.size() != 3) throw r.error(key, "must be a list of 3 numbers");
  for (double x : v)
    if (!std::isfinite(x)) throw r.error(key, "must be finite");
  return Vec3(v[0], v[1], v[2]);
}

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

}  // namespace

CaseConfig parse_case(const nlohmann::json& doc, const std::string& where,
                      const std::vector<std::string>& search_dirs) {
  CaseConfig c;
  c.file = where;
  ConfigReader root(doc, where);
  c.name = root.require<std::string>("name");
  if (const std::string problem = result_name_problem(c.name); !problem.empty())
    throw root.error("name", "'" + c.name + "' " + problem + ": it names the result directory");
  c.description = root.get<std::string>("description", "");
  c.model = root.get<std::string>("model", "tensor_mass");
  if (c.model != "tensor_mass" && c.model != "tl_oracle")
    throw root.error("model", "must be 'tensor_mass' or 'tl_oracle' (got '" + c.model + "')");

  {
    ConfigReader m = root.child("mesh");
    c.mesh.file = resolve(m.require<std::string>("file"), search_dirs, m, "file");
    c.mesh.scale = m.positive("scale", 1.0);
    c.mesh.repair_orientation = m.get<bool>("repair_orientation", false);
    m.finish();
  }
  {
    ConfigReader m = root.child("material");
    c.material.law = m.get<std::string>("law", "stvk");
    if (c.material.law != "stvk")
      throw m.error("law", "must be 'stvk' (St Venant-Kirchhoff; got '" + c.material.law + "')");
    c.material.young = m.positive("E");
    c.material.poisson = m.require<double>("nu");
    if (!(c.material.poisson > -1.0 && c.material.poisson < 0.5))
      throw m.error("nu", "must satisfy -1 < nu < 0.5 (got " + std::to_string(c.material.poisson) + ")");
    c.material.density = m.positive("density");
    if (m.has("viscoelastic")) {
      ConfigReader v = m.child("viscoelastic");
      ViscoelasticSpec& vs = c.material.viscoelastic;
      vs.enabled = true;
      if (v.has("scheme")) {
        vs.scheme = v.require<std::string>("scheme");
        if (v.has("history") || v.has("integration"))
          throw v.error("scheme", "is a shorthand for history + integration: give either it or them");
        if (vs.scheme == "seed") {
          vs.history = "nodal_force", vs.integration = "midpoint";
        } else if (vs.scheme == "seed_exact_linear") {
          vs.history = "nodal_force", vs.integration = "exact_linear";
        } else if (vs.scheme == "backward_euler") {
          vs.history = "nodal_force", vs.integration = "backward_euler";
        } else if (vs.scheme == "objective") {
          vs.history = "pk2", vs.integration = "exact_linear";
        } else {
          throw v.error("scheme", "unknown scheme '" + vs.scheme +
                                      "' (expected seed, seed_exact_linear, backward_euler or objective)");
        }
      } else {
        vs.history = v.get<std::string>("history", "pk2");
        vs.integration = v.get<std::string>("integration", "exact_linear");
      }
      if (vs.history != "nodal_force" && vs.history != "pk2")
        throw v.error("history", "must be 'nodal_force' or 'pk2' (got '" + vs.history + "')");
      if (vs.integration != "midpoint" && vs.integration != "exact_linear" &&
          vs.integration != "backward_euler")
        throw v.error("integration", "must be 'midpoint', 'exact_linear' or 'backward_euler' (got '" +
                                         vs.integration + "')");
      vs.relaxation = v.get<std::string>("relaxation", "full");
      if (vs.relaxation != "full" && vs.relaxation != "deviatoric")
        throw v.error("relaxation", "must be 'full' or 'deviatoric' (got '" + vs.relaxation + "')");
      if (vs.relaxation == "deviatoric" && vs.history != "pk2")
        throw v.error("relaxation",
                      "'deviatoric' needs the pk2 (objective) history: nodal forces have no deviatoric part");
      ConfigReader p = v.child("prony");
      vs.convention = p.get<std::string>("convention", "long_term");
      if (vs.convention != "long_term" && vs.convention != "instantaneous")
        throw p.error("convention", "must be 'long_term' or 'instantaneous' (got '" + vs.convention + "')");
      const auto& terms = p.raw("terms");
      if (!terms.is_array() || terms.empty())
        throw p.error("terms", "must be a non-empty list of {weight, tau}");
      double gsum = 0.0;
      for (std::size_t k = 0; k < terms.size(); ++k) {
        ConfigReader t(terms[k], where, p.key_path("terms") + "[" + std::to_string(k) + "]");
        const double w = t.positive("weight", /*allow_zero=*/true);
        const double tau = t.positive("tau");
        t.finish();
        vs.weights.push_back(w);
        vs.taus.push_back(tau);
        gsum += w;
      }
      if (vs.convention == "instantaneous" && !(gsum < 1.0))
        throw p.error("terms",
                      "instantaneous weights g_j must sum to less than 1 (got " + std::to_string(gsum) + ")");
      p.finish();
      v.finish();
    }
    m.finish();
  }
  if (root.has("boundary")) {
    const auto& arr = root.raw("boundary");
    if (!arr.is_array()) throw root.error("boundary", "must be a list");
    for (std::size_t i = 0; i < arr.size(); ++i) {
      ConfigReader b(arr[i], where, "boundary[" + std::to_string(i) + "]");
      BoundarySpec s;
      s.name = b.get<std::string>("name", "boundary" + std::to_string(i));
      s.nodes = NodeSelector::from_json(b.raw("nodes"), where + ": key '" + b.key_path("nodes") + "'");
      s.components = read_components(b, "components");
      s.value = b.has("value") ? read_vec3(b, "value") : Vec3::Zero();
      s.function = read_function(b);
      b.finish();
      c.boundary.push_back(s);
    }
  }
  if (root.has("loads")) {
    const auto& arr = root.raw("loads");
    if (!arr.is_array()) throw root.error("loads", "must be a list");
    for (std::size_t i = 0; i < arr.size(); ++i) {
      ConfigReader l(arr[i], where, "loads[" + std::to_string(i) + "]");
      LoadSpec s;
      const std::string type = l.require<std::string>("type");
      s.name = l.get<std::string>("name", type + std::to_string(i));
      if (type == "nodal_force") {
        s.type = LoadSpec::Type::NodalForce;
        s.selector = NodeSelector::from_json(l.raw("nodes"), where + ": key '" + l.key_path("nodes") + "'");
        s.vector = read_vec3(l, "force");
      } else if (type == "pressure") {
        s.type = LoadSpec::Type::Pressure;
        s.selector = NodeSelector::from_json(l.raw("faces"), where + ": key '" + l.key_path("faces") + "'");
        s.pressure = l.require<double>("pressure");
        if (!std::isfinite(s.pressure)) throw l.error("pressure", "must be finite");
        s.follower = l.get<bool>("follower", false);
      } else if (type == "traction") {
        // A dead traction vector per unit reference area on the selected boundary faces.
        s.type = LoadSpec::Type::Traction;
        s.selector = NodeSelector::from_json(l.raw("faces"), where + ": key '" + l.key_path("faces") + "'");
        s.vector = read_vec3(l, "traction");
      } else if (type == "gravity") {
        s.type = LoadSpec::Type::Gravity;
        s.vector = read_vec3(l, "acceleration");
      } else {
        throw l.error(
            "type", "unknown load type '" + type + "' (expected nodal_force, pressure, traction or gravity)");
      }
      s.function = read_function(l);
      l.finish();
      c.loads.push_back(s);
    }
  }
  {
    ConfigReader s = root.child("solver");
    const std::string type = s.require<std::string>("type");
    c.solver.t_end = s.positive("t_end", 1.0);
    if (type == "static") {
      c.solver.type = SolverSpec::Type::Static;
      c.solver.steps = s.get<int>("steps", 10);
      if (c.solver.steps < 1) throw s.error("steps", "must be >= 1");
    } else if (type == "explicit" || type == "implicit") {
      c.solver.type = type == "explicit" ? SolverSpec::Type::Explicit : SolverSpec::Type::Implicit;
      c.solver.dt = s.positive("dt");
      if (c.solver.dt > c.solver.t_end) throw s.error("dt", "must not exceed t_end");
      const double n = c.solver.t_end / c.solver.dt;
      if (n > 1e8) throw s.error("dt", "gives more than 1e8 steps");
      c.solver.steps = static_cast<int>(std::ceil(n - 1e-9));
      if (type == "implicit") {
        c.solver.scheme = s.get<std::string>("scheme", "newmark");
        if (c.solver.scheme != "newmark" && c.solver.scheme != "backward_euler")
          throw s.error("scheme", "must be 'newmark' or 'backward_euler' (got '" + c.solver.scheme + "')");
      } else {
        c.solver.check_stability = s.get<bool>("check_stability", true);
      }
      if (s.has("damping")) {
        ConfigReader d = s.child("damping");
        c.solver.damping_alpha = d.positive("alpha", 0.0, true);
        c.solver.damping_beta = d.positive("beta", 0.0, true);
        d.finish();
      }
    } else {
      throw s.error("type", "unknown solver '" + type + "' (expected static, explicit or implicit)");
    }
    if (s.has("newton")) {
      if (c.solver.type == SolverSpec::Type::Explicit)
        throw s.error("newton", "is not used by the explicit solver");
      ConfigReader n = s.child("newton");
      c.solver.max_iterations = n.get<int>("max_iterations", 25);
      if (c.solver.max_iterations < 1) throw n.error("max_iterations", "must be >= 1");
      c.solver.rtol = n.positive("rtol", 1e-10);
      c.solver.atol = n.positive("atol", 1e-14, true);
      if (n.has("line_search")) {
        // "energy" | "residual" | "none"; true and false are kept for older case files (true = energy).
        const nlohmann::json& ls = n.raw("line_search");
        const auto named = ls.is_string() ? line_search_from_string(ls.get<std::string>()) : std::nullopt;
        if (ls.is_boolean()) {
          c.solver.line_search = ls.get<bool>() ? LineSearch::Energy : LineSearch::None;
        } else if (named) {
          c.solver.line_search = *named;
        } else {
          throw n.error("line_search",
                        "must be \"energy\", \"residual\" or \"none\" (got " + ls.dump() + ")");
        }
      }
      c.solver.max_cutbacks = n.get<int>("max_cutbacks", 8);
      if (c.solver.max_cutbacks < 0) throw n.error("max_cutbacks", "must be >= 0");
      n.finish();
    }
    s.finish();
  }
  if (root.has("output")) {
    ConfigReader o = root.child("output");
    c.output.every = o.get<int>("every", 1);
    if (c.output.every < 1) throw o.error("every", "must be >= 1");
    c.output.vtu = o.get<bool>("vtu", true);
    c.output.xdmf = o.get<bool>("xdmf", true);
    c.output.plots = o.get<bool>("plots", true);
    if (o.has("probes")) {
      const auto& arr = o.raw("probes");
      if (!arr.is_array()) throw o.error("probes", "must be a list");
      for (std::size_t i = 0; i < arr.size(); ++i) {
        ConfigReader p(arr[i], where, o.key_path("probes") + "[" + std::to_string(i) + "]");
        ProbeSpec ps;
        ps.name = p.require<std::string>("name");
        ps.point = read_vec3(p, "point");
        p.finish();
        c.output.probes.push_back(ps);
      }
    }
    o.finish();
  }
  root.finish();

  return c;
}

nlohmann::json effective_case_json(const CaseConfig& c) {
  using nlohmann::json;
  auto v3 = [](const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); };
  json doc = {
      {"name", c.name},
      {"description", c.description},
      {"model", c.model},
      {"mesh",
       {{"file", c.mesh.file}, {"scale", c.mesh.scale}, {"repair_orientation", c.mesh.repair_orientation}}}};
  json material = {{"law", c.material.law},
                   {"E", c.material.young},
                   {"nu", c.material.poisson},
                   {"density", c.material.density}};
  const ViscoelasticSpec& vs = c.material.viscoelastic;
  if (vs.enabled) {
    json terms = json::array();
    for (std::size_t k = 0; k < vs.weights.size(); ++k)
      terms.push_back({{"weight", vs.weights[k]}, {"tau", vs.taus[k]}});
    material["viscoelastic"] = {{"history", vs.history},
                                {"integration", vs.integration},
                                {"relaxation", vs.relaxation},
                                {"prony", {{"convention", vs.convention}, {"terms", terms}}}};
  }
  doc["material"] = material;
  json boundary = json::array();
  for (const BoundarySpec& b : c.boundary) {
    std::string comps;
    for (int k = 0; k < 3; ++k)
      if (b.components[static_cast<std::size_t>(k)]) comps += "xyz"[k];
    boundary.push_back({{"name", b.name},
                        {"nodes", b.nodes.to_json()},
                        {"components", comps},
                        {"value", v3(b.value)},
                        {"function", b.function.to_json()}});
  }
  doc["boundary"] = boundary;
  json loads = json::array();
  for (const LoadSpec& l : c.loads) {
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
    loads.push_back(j);
  }
  doc["loads"] = loads;
  const SolverSpec& sv = c.solver;
  json solver = {{"t_end", sv.t_end}};
  if (sv.type == SolverSpec::Type::Static) {
    solver["type"] = "static";
    solver["steps"] = sv.steps;
  } else {
    solver["type"] = sv.type == SolverSpec::Type::Explicit ? "explicit" : "implicit";
    solver["dt"] = sv.dt;
    if (sv.type == SolverSpec::Type::Implicit)
      solver["scheme"] = sv.scheme;
    else
      solver["check_stability"] = sv.check_stability;
    solver["damping"] = {{"alpha", sv.damping_alpha}, {"beta", sv.damping_beta}};
  }
  if (sv.type != SolverSpec::Type::Explicit) {
    solver["newton"] = {{"max_iterations", sv.max_iterations},
                        {"rtol", sv.rtol},
                        {"atol", sv.atol},
                        {"line_search", to_string(sv.line_search)},
                        {"max_cutbacks", sv.max_cutbacks}};
  }
  doc["solver"] = solver;
  json probes = json::array();
  for (const ProbeSpec& p : c.output.probes) probes.push_back({{"name", p.name}, {"point", v3(p.point)}});
  doc["output"] = {{"every", c.output.every},
                   {"vtu", c.output.vtu},
                   {"xdmf", c.output.xdmf},
                   {"plots", c.output.plots},
                   {"probes", probes}};
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
