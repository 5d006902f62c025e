// The inversion depth of each law under the paper's sphere indentation (depth_limit.hpp).
#include "studies/depth_limit/depth_limit.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/interrupt.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "tensormass/contact/contact_solver.hpp"
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/materials/law_factory.hpp"
#include "tensormass/system/dirichlet.hpp"
#include "tensormass/system/external_loads.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

namespace tmlab::tm {

namespace {

constexpr double kDensity = 1000.0;  // kg/m^3: the masses are unused by the static solve

/// Smallest det F over all tets (the deformed / rest volume ratio of a P1 tet) and where.
std::pair<double, Index> min_volume_ratio(const Mesh& mesh, const VecX& u) {
  double jmin = std::numeric_limits<double>::infinity();
  Index where = -1;
  for (Index t = 0; t < mesh.num_tets(); ++t) {
    Vec3 X[4], x[4];
    for (int a = 0; a < 4; ++a) {
      const Index n = mesh.tets[static_cast<std::size_t>(t)][static_cast<std::size_t>(a)];
      X[a] = mesh.points[static_cast<std::size_t>(n)];
      x[a] = X[a] + u.segment<3>(3 * n);
    }
    const double v0 = (X[1] - X[0]).dot((X[2] - X[0]).cross(X[3] - X[0]));
    const double v = (x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0]));
    if (v / v0 < jmin) {
      jmin = v / v0;
      where = t;
    }
  }
  return {jmin, where};
}

Vec3 centroid(const Mesh& mesh, Index t) {
  Vec3 c = Vec3::Zero();
  for (Index n : mesh.tets[static_cast<std::size_t>(t)]) c += mesh.points[static_cast<std::size_t>(n)];
  return 0.25 * c;
}

/// Rollers on x = 0 and y = 0, the bottom z = 0 clamped (a DOF two of them prescribe is zero in both).
DirichletSet quarter_supports(const Mesh& mesh, double W) {
  const double tol = 1e-12 * W;
  DirichletCondition sx{"symmetry_x", {}, {true, false, false}, Vec3::Zero(), TimeFunction::constant()};
  DirichletCondition sy{"symmetry_y", {}, {false, true, false}, Vec3::Zero(), TimeFunction::constant()};
  DirichletCondition bottom{"bottom", {}, {true, true, true}, Vec3::Zero(), TimeFunction::constant()};
  for (Index i = 0; i < mesh.num_points(); ++i) {
    const Vec3& x = mesh.points[static_cast<std::size_t>(i)];
    if (std::abs(x.x()) <= tol) sx.nodes.push_back(i);
    if (std::abs(x.y()) <= tol) sy.nodes.push_back(i);
    if (std::abs(x.z()) <= tol) bottom.nodes.push_back(i);
  }
  return DirichletSet(mesh.num_points(), {sx, sy, bottom});
}

void check_options(const DepthLimitOptions& o) {
  auto positive = [](double v, const char* key) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw Error(std::string("depth-limit study: ") + key + " must be > 0");
  };
  positive(o.radius, "radius");
  positive(o.half_width, "half_width");
  positive(o.height, "height");
  positive(o.young, "young");
  positive(o.max_depth, "max_depth");
  positive(o.increment, "increment");
  if (!(o.grading >= 1.0)) throw Error("depth-limit study: grading must be >= 1");
  if (!(o.poisson > -1.0 && o.poisson < 0.5)) throw Error("depth-limit study: poisson must be in (-1, 0.5)");
  if (o.increment > o.max_depth) throw Error("depth-limit study: increment must be <= max_depth");
  if (o.max_depth >= o.height) throw Error("depth-limit study: max_depth must be below the block height");
  if (o.cells.empty()) throw Error("depth-limit study: no mesh (cells is empty)");
  for (int n : o.cells)
    if (n < 2) throw Error("depth-limit study: cells must be >= 2 (got " + std::to_string(n) + ")");
}

/// The study's checkpoint: every finished (law, mesh) run by key "<law>.n<cells>", written after
/// each; on --resume those of the interrupted study are taken from here. Every field of the run is
/// stored as it is (doubles exactly, NaN included), so a resumed study's output equals an
/// uninterrupted one's.
class DepthLimitCheckpoint {
 public:
  explicit DepthLimitCheckpoint(const DepthLimitOptions& o) : o_(o) {
    if (o.resume) d_ = *o.resume;
  }

  std::optional<DepthLimitRun> restore(const std::string& key) const {
    if (!d_.has(key + ".num")) return std::nullopt;
    const std::vector<double>& v = d_.doubles(key + ".num");
    const nlohmann::json t = nlohmann::json::parse(d_.text(key + ".text"));
    const std::vector<double>& depth = d_.doubles(key + ".depth");
    const std::vector<double>& min_j = d_.doubles(key + ".min_j");
    const std::vector<double>& force = d_.doubles(key + ".force");
    const std::vector<std::int64_t>& worst = d_.ints(key + ".worst_tet");
    const std::vector<std::int64_t>& active = d_.ints(key + ".active_nodes");
    const std::size_t n = depth.size();
    if (v.size() != 12 || t.size() != 3 || min_j.size() != n || force.size() != n || worst.size() != n ||
        active.size() != n)
      throw Error(d_.source() + ": inconsistent entry " + key + "; run without --resume");
    DepthLimitRun r;
    r.law = t[0], r.outcome = t[1], r.message = t[2];
    r.cells = static_cast<int>(v[0]), r.tets = static_cast<Index>(v[1]), r.h_min = v[2];
    r.inversion_depth = v[3], r.bracket_low = v[4], r.bracket_high = v[5], r.limit_depth = v[6];
    r.deepest = v[7], r.deepest_min_j = v[8], r.worst_depth_below_top = v[9], r.worst_radius = v[10];
    if (v[11] != static_cast<double>(n))
      throw Error(d_.source() + ": inconsistent entry " + key + "; run without --resume");
    for (std::size_t i = 0; i < n; ++i)
      r.samples.push_back(
          {depth[i], min_j[i], static_cast<Index>(worst[i]), force[i], static_cast<int>(active[i])});
    return r;
  }

  /// Stores a finished run, writes the checkpoint (when the study has one), then stops here if a
  /// signal is pending.
  void store(const std::string& key, const DepthLimitRun& r) {
    if (o_.checkpoint.empty()) return;
    std::vector<double> depth, min_j, force;
    std::vector<std::int64_t> worst, active;
    for (const DepthLimitSample& s : r.samples) {
      depth.push_back(s.depth), min_j.push_back(s.min_j), force.push_back(s.force);
      worst.push_back(s.worst_tet), active.push_back(s.active_nodes);
    }
    d_.put(key + ".num",
           std::vector<double>{static_cast<double>(r.cells), static_cast<double>(r.tets), r.h_min,
                               r.inversion_depth, r.bracket_low, r.bracket_high, r.limit_depth, r.deepest,
                               r.deepest_min_j, r.worst_depth_below_top, r.worst_radius,
                               static_cast<double>(r.samples.size())});
    d_.put_text(key + ".text", nlohmann::json::array({r.law, r.outcome, r.message}).dump());
    d_.put(key + ".depth", std::move(depth));
    d_.put(key + ".min_j", std::move(min_j));
    d_.put(key + ".force", std::move(force));
    d_.put(key + ".worst_tet", std::move(worst));
    d_.put(key + ".active_nodes", std::move(active));
    write_checkpoint(o_.checkpoint, "depth_limit", o_.fingerprint, d_);
    check_interrupt("after the run " + key + "; the finished runs are in the checkpoint " +
                    o_.checkpoint.string() + ": continue with the same command and --resume");
  }

 private:
  const DepthLimitOptions& o_;
  CheckpointData d_;
};

/// Where a stop request inside a run lands, and how to continue.
std::string interrupt_where(const DepthLimitOptions& o, const std::string& law, int cells) {
  std::string w = "during the run " + law + ".n" + std::to_string(cells);
  if (!o.checkpoint.empty())
    w += " (it starts again on resuming; the finished runs are in the checkpoint " + o.checkpoint.string() +
         "): continue with the same command and --resume";
  return w;
}

std::string fmt_mm(double metres, int digits = 2) {
  if (!std::isfinite(metres)) return "-";
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << 1e3 * metres;
  return s.str();
}

}  // namespace

std::vector<DepthLimitLaw> default_depth_limit_laws(double E, double nu) {
  const double G = E / (2.0 * (1.0 + nu)), kappa = E / (3.0 * (1.0 - 2.0 * nu));
  using nlohmann::json;
  return {
      {"stvk", json{{"young", E}, {"poisson", nu}}},
      {"neo_hookean", json{{"young", E}, {"poisson", nu}}},
      {"mooney_rivlin", json{{"c10", 0.4 * G}, {"c01", 0.1 * G}, {"kappa", kappa}}},
      {"yeoh", json{{"c10", 0.5 * G}, {"c20", 0.05 * G}, {"kappa", kappa}}},
      {"ogden", json{{"mu", json::array({2.0 * G / 5.0})}, {"alpha", json::array({5.0})}, {"kappa", kappa}}},
      {"veronda_westmann", json{{"c1", G}, {"c2", 1.0}, {"kappa", kappa}}},
  };
}

Mesh inversion_block(const DepthLimitOptions& o, int cells) {
  check_options(o);
  Mesh mesh = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), cells, cells, cells);
  const double p = o.grading;
  for (Vec3& x : mesh.points) {
    x.x() = o.half_width * std::pow(x.x(), p);
    x.y() = o.half_width * std::pow(x.y(), p);
    x.z() = o.height * (1.0 - std::pow(1.0 - x.z(), p));
  }
  return mesh;
}

DepthLimitRun run_inversion(const DepthLimitOptions& o, const DepthLimitLaw& law, int cells) {
  check_options(o);
  const Mesh mesh = inversion_block(o, cells);
  HyperelasticTL model(mesh, make_law(law.name, law.parameters, "depth-limit study: law " + law.name));
  const VecX node_mass = lumped_node_mass(mesh, kDensity);
  MechanicalSystem system(model, lumped_dof_mass(node_mass), quarter_supports(mesh, o.half_width),
                          ExternalLoads(mesh, node_mass));

  DepthLimitRun run;
  run.law = law.name;
  run.cells = cells;
  run.tets = mesh.num_tets();
  run.h_min = o.half_width * std::pow(1.0 / cells, o.grading);

  // The sphere touches the top at the origin at t = 0 and moves down by max_depth t.
  RigidBody sphere = RigidBody::sphere("indenter", Vec3(0, 0, o.height + o.radius), o.radius);
  sphere.displacement = Vec3(0, 0, -o.max_depth);
  sphere.function = TimeFunction::ramp(0.0, 1.0);
  VecX u = VecX::Zero(3 * mesh.num_points());
  ContactStaticSolver solver(system, mesh, {sphere}, ContactOptions{}, NewtonOptions{}, 0.0, u);

  const int steps = static_cast<int>(std::ceil(o.max_depth / o.increment - 1e-9));
  double j_prev = 1.0, d_prev = 0.0;
  run.outcome = "max_depth";
  for (int k = 1; k <= steps; ++k) {
    const double t0 = double(k - 1) / steps, t1 = double(k) / steps;
    try {
      solver.advance(t0, t1, u);
    } catch (const Interrupted&) {
      throw;  // SIGINT / SIGTERM: not an outcome
    } catch (const Error& e) {
      run.outcome = "solver_failed";
      run.message = e.what();
      run.bracket_low = d_prev;
      run.bracket_high = t1 * o.max_depth;
      run.limit_depth = d_prev;
      break;
    }
    check_interrupt(interrupt_where(o, law.name, cells));  // safe point
    const auto [jmin, worst] = min_volume_ratio(mesh, u);
    DepthLimitSample s;
    s.depth = t1 * o.max_depth;
    s.min_j = jmin;
    s.worst_tet = worst;
    s.force = 4.0 * solver.state().front().force.z();
    s.active_nodes = solver.state().front().active_nodes;
    run.samples.push_back(s);
    run.deepest = s.depth;
    run.deepest_min_j = jmin;
    const Vec3 c = centroid(mesh, worst);
    run.worst_depth_below_top = o.height - c.z();
    run.worst_radius = std::hypot(c.x(), c.y());
    if (o.log) {
      std::ostringstream m;
      m << law.name << " n=" << cells << ": d = " << fmt_mm(s.depth, 3) << " mm, min J = " << jmin
        << ", F = " << s.force << " N";
      o.log(m.str());
    }
    if (!(jmin > 0.0)) {
      run.outcome = "inverted";
      run.bracket_low = d_prev;
      run.bracket_high = s.depth;
      // min J is smooth in the depth between two converged states: the linear zero crossing.
      run.inversion_depth = d_prev + (s.depth - d_prev) * j_prev / (j_prev - jmin);
      run.limit_depth = run.inversion_depth;
      break;
    }
    j_prev = jmin;
    d_prev = s.depth;
  }
  if (o.log) o.log(law.name + " n=" + std::to_string(cells) + ": " + run.outcome);
  return run;
}

nlohmann::json depth_limit_fingerprint(const DepthLimitOptions& o) {
  using nlohmann::json;
  const std::vector<DepthLimitLaw> laws =
      o.laws.empty() ? default_depth_limit_laws(o.young, o.poisson) : o.laws;
  json jl = json::array();
  for (const DepthLimitLaw& l : laws) jl.push_back({{"law", l.name}, {"parameters", l.parameters}});
  return {{"radius_m", o.radius},       {"half_width_m", o.half_width},
          {"height_m", o.height},       {"young_Pa", o.young},
          {"poisson", o.poisson},       {"grading", o.grading},
          {"max_depth_m", o.max_depth}, {"increment_m", o.increment},
          {"cells", o.cells},           {"laws", jl}};
}

std::vector<DepthLimitRun> run_depth_limit_study(const DepthLimitOptions& options) {
  check_options(options);
  const std::vector<DepthLimitLaw> laws =
      options.laws.empty() ? default_depth_limit_laws(options.young, options.poisson) : options.laws;
  DepthLimitCheckpoint ck(options);
  std::vector<DepthLimitRun> runs;
  for (const DepthLimitLaw& law : laws)
    for (int n : options.cells) {
      const std::string key = law.name + ".n" + std::to_string(n);
      if (std::optional<DepthLimitRun> done = ck.restore(key)) {
        if (options.log) options.log(key + ": from the checkpoint of the interrupted study");
        runs.push_back(std::move(*done));
        continue;
      }
      runs.push_back(run_inversion(options, law, n));
      ck.store(key, runs.back());
    }
  return runs;
}

nlohmann::json depth_limit_json(const DepthLimitOptions& o, const std::vector<DepthLimitRun>& runs) {
  using nlohmann::json;
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  const std::vector<DepthLimitLaw> laws =
      o.laws.empty() ? default_depth_limit_laws(o.young, o.poisson) : o.laws;
  json jl = json::array();
  for (const DepthLimitLaw& l : laws) jl.push_back({{"law", l.name}, {"parameters", l.parameters}});
  json out = {{"geometry",
               {{"radius_m", o.radius},
                {"block_m", {2.0 * o.half_width, 2.0 * o.half_width, o.height}},
                {"model", "quarter [0, W]^2 x [0, H], rollers on x = 0 and y = 0, bottom clamped"},
                {"grading", o.grading}}},
              {"young_Pa", o.young},
              {"poisson", o.poisson},
              {"max_depth_m", o.max_depth},
              {"increment_m", o.increment},
              {"cells", o.cells},
              {"laws", jl},
              {"runs", json::array()}};
  for (const DepthLimitRun& r : runs) {
    json s = {{"depth_m", json::array()},
              {"min_J", json::array()},
              {"force_N", json::array()},
              {"active_nodes", json::array()}};
    for (const DepthLimitSample& x : r.samples) {
      s["depth_m"].push_back(x.depth);
      s["min_J"].push_back(x.min_j);
      s["force_N"].push_back(x.force);
      s["active_nodes"].push_back(x.active_nodes);
    }
    out["runs"].push_back({{"law", r.law},
                           {"cells", r.cells},
                           {"tets", r.tets},
                           {"h_min_m", r.h_min},
                           {"outcome", r.outcome},
                           {"inversion_depth_m", num(r.inversion_depth)},
                           {"limit_depth_m", num(r.limit_depth)},
                           {"bracket_m", {num(r.bracket_low), num(r.bracket_high)}},
                           {"deepest_converged_m", r.deepest},
                           {"deepest_min_J", r.deepest_min_j},
                           {"worst_tet_depth_below_top_m", r.worst_depth_below_top},
                           {"worst_tet_radius_m", r.worst_radius},
                           {"message", r.message},
                           {"samples", s}});
  }
  return out;
}

std::string depth_limit_markdown(const DepthLimitOptions& o, const std::vector<DepthLimitRun>& runs,
                                 const std::string& command_line) {
  std::ostringstream m;
  m << "# Inversion depth of each law under a sphere indentation\n\n"
    << "Sphere R = " << fmt_mm(o.radius, 1) << " mm into a " << fmt_mm(2 * o.half_width, 0) << " x "
    << fmt_mm(2 * o.half_width, 0) << " x " << fmt_mm(o.height, 0)
    << " mm block (quarter model, bottom clamped), frictionless augmented-Lagrangian contact, F-based "
       "kernel, small-strain E = "
    << o.young << " Pa, nu = " << o.poisson << "; depth increments of " << fmt_mm(o.increment, 3) << " mm to "
    << fmt_mm(o.max_depth, 1) << " mm; mesh graded with p = " << o.grading << ".\n\n";
  if (!command_line.empty()) m << "Command: `" << command_line << "`\n\n";
  m << "| law | cells | tets | h at the tip (mm) | outcome | limit depth (mm) | bracket (mm) | deepest "
       "converged (mm) | min J there | worst tet: depth, radius (mm) |\n"
    << "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const DepthLimitRun& r : runs) {
    m << "| " << r.law << " | " << r.cells << " | " << r.tets << " | " << fmt_mm(r.h_min, 3) << " | "
      << r.outcome << " | " << fmt_mm(r.limit_depth) << " | ";
    if (r.outcome != "max_depth")
      m << fmt_mm(r.bracket_low) << " - " << fmt_mm(r.bracket_high);
    else
      m << "-";
    m << " | " << fmt_mm(r.deepest) << " | " << scientific(r.deepest_min_j, 2) << " | "
      << fmt_mm(r.worst_depth_below_top) << ", " << fmt_mm(r.worst_radius) << " |\n";
  }
  m << "\nOutcomes: `inverted` (a converged state with min det F <= 0; the depth is the linear zero "
       "crossing of min J between the last two increments), `solver_failed` (the contact solve fails "
       "after its cut-backs within the bracket; every converged state has det F > 0; the limit depth is "
       "the deepest converged one), `max_depth` (neither within the range).\n";
  for (const DepthLimitRun& r : runs)
    if (!r.message.empty()) m << "\n- " << r.law << ", " << r.cells << " cells: " << r.message << "\n";
  return m.str();
}

}  // namespace tmlab::tm
