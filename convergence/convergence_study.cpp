#include "convergence/convergence_study.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_quality.hpp"
#include "core/mesh/mesh_refine.hpp"
#include "core/results/series_names.hpp"
#include "runner/case_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace tmlab::convergence {

namespace {

namespace fs = std::filesystem;
namespace sn = series_names;

std::string number(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

std::string joined(const std::vector<std::string>& words) {
  std::string s;
  for (const std::string& w : words) s += (s.empty() ? "" : ", ") + w;
  return s;
}

std::string level_name(int level) { return "level-" + std::to_string(level); }

/// The names of a rig's Dirichlet conditions, the moving ones, and its contact bodies (its case
/// file as rigs::rig_case writes it; the mesh is not needed).
struct CaseNames {
  std::vector<std::string> conditions, moving, probes, bodies;
};

CaseNames names_of(const nlohmann::json& doc) {
  CaseNames n;
  for (const auto& b : doc.value("boundary", nlohmann::json::array())) {
    n.conditions.push_back(b.at("name").get<std::string>());
    if (b.contains("value"))
      for (const auto& v : b["value"])
        if (v.get<double>() != 0.0) {
          n.moving.push_back(n.conditions.back());
          break;
        }
  }
  if (doc.contains("contact"))
    for (const auto& b : doc["contact"].value("bodies", nlohmann::json::array()))
      n.bodies.push_back(b.at("name").get<std::string>());
  if (doc.contains("output"))
    for (const auto& p : doc["output"].value("probes", nlohmann::json::array()))
      n.probes.push_back(p.at("name").get<std::string>());
  return n;
}

CaseNames names_of(const CaseConfig& cfg) {
  CaseNames n;
  for (const BoundarySpec& b : cfg.boundary) {
    n.conditions.push_back(b.name);
    if (!b.value.isZero()) n.moving.push_back(b.name);
  }
  for (const ProbeSpec& p : cfg.output.probes) n.probes.push_back(p.name);
  if (cfg.contact.enabled)
    for (const ContactBodySpec& b : cfg.contact.bodies) n.bodies.push_back(b.name);
  return n;
}

/// The rig of level k (1-based). The explicit mesh form (cells > 0): cells and layers times
/// ratio^(k-1), rounded. The contact rule (cells = 0): rigs::refined(base, ratio^(k-1)), every cell
/// count of the rule's graded mesh times the ratio.
rigs::RigSpec rig_level(const rigs::RigSpec& base, double ratio, int level) {
  const double f = std::pow(ratio, level - 1);
  rigs::RigSpec s = base;
  if (base.cells > 0) {
    s.cells = static_cast<int>(std::lround(base.cells * f));
    s.layers = static_cast<int>(std::lround(base.layers * f));
  } else {
    s = rigs::refined(base, f);
  }
  s.name = level_name(level);
  return s;
}

/// The time at which a rig's history first reaches its largest |d|: the end of the loading.
double loading_end(const rigs::DisplacementHistory& h) {
  const double peak = h.peak();
  for (std::size_t k = 0; k < h.d.size(); ++k)
    if (std::abs(h.d[k]) == peak) return h.t[k];
  return h.t.back();
}

double mesh_volume(const Mesh& m) {
  double v = 0.0;
  for (Index t = 0; t < m.num_tets(); ++t) v += std::abs(tet_signed_volume(m, t));
  return v;
}

/// Reads the quantities of one level's run at the times.
std::vector<std::vector<double>> read_values(const fs::path& run_dir, const StudyPlan& plan,
                                             std::vector<std::string>* units) {
  const fs::path file = run_dir / "timeseries.h5";
  const H5File h5 = H5File::open_read(file.string());
  const std::string time_ds = std::string("/series/") + sn::kTime;
  if (!h5.exists(time_ds)) throw Error(file.string() + ": no " + time_ds);
  const std::vector<double> time = h5.read_double(time_ds);
  std::vector<std::vector<double>> values;
  for (const std::string& q : plan.quantities) {
    const std::string ds = "/series/" + q;
    if (!h5.exists(ds))
      throw Error(file.string() + ": --quantity " + q +
                  ": the run recorded no such series (its series: " + joined(h5.list("/series")) + ")");
    const std::vector<double> series = h5.read_double(ds);
    if (units) units->push_back(h5.has_attribute(ds, "unit") ? h5.string_attribute(ds, "unit") : "");
    std::vector<double> at;
    for (const double t : plan.times) at.push_back(value_at(time, series, t, file.string() + ": " + q));
    values.push_back(at);
  }
  return values;
}

}  // namespace

std::vector<std::string> recorded_series(const std::vector<std::string>& conditions,
                                         const std::vector<std::string>& probes,
                                         const std::vector<std::string>& bodies) {
  std::vector<std::string> s = {sn::kMaxDisplacement, sn::kElasticEnergy, sn::kKineticEnergy,
                                sn::kMinVolumeRatio};
  const auto vector = [&s](const std::string& base) {
    for (const char* c : sn::kComponents) s.push_back(sn::component(base, c));
  };
  for (const std::string& c : conditions) vector(sn::reaction(c));
  for (const std::string& p : probes) vector(sn::probe(p));
  for (const std::string& b : bodies) {
    for (const char* what : {"position", "force", "moment"}) vector(sn::contact(b) + "_" + what);
    for (const char* what :
         {"area", "radius", "radius_max", "active_nodes", "max_pressure", "max_penetration"})
      s.push_back(sn::contact(b) + "_" + what);
  }
  return s;
}

std::vector<std::string> default_quantities(const std::vector<std::string>& moving_conditions,
                                            const std::vector<std::string>& probes,
                                            const std::vector<std::string>& bodies) {
  std::vector<std::string> q;
  for (const std::string& b : bodies) {
    q.push_back(sn::component(sn::contact(b) + "_force", "z"));
    q.push_back(sn::contact(b) + "_radius");
  }
  if (bodies.empty())
    for (const std::string& c : moving_conditions) q.push_back(sn::component(sn::reaction(c), "norm"));
  for (const std::string& p : probes) q.push_back(sn::component(sn::probe(p), "norm"));
  if (q.empty()) q.push_back(sn::kMaxDisplacement);
  return q;
}

StudyPlan plan_study(const StudyOptions& o) {
  if (o.rig.has_value() == o.case_config.has_value())
    throw Error("converge: give either a rig or a case file (got " + std::string(o.rig ? "both" : "neither") +
                ")");
  if (o.levels < 3 || o.levels > kMaxLevels)
    throw Error("--levels " + std::to_string(o.levels) + ": a convergence study needs 3 to " +
                std::to_string(kMaxLevels) + " levels (an observed order needs three)");
  if (!std::isfinite(o.ratio) || !(o.ratio > 1.0))
    throw Error("--ratio " + number(o.ratio) + ": the refinement ratio must exceed 1 (the levels refine)");
  StudyPlan plan;
  plan.ratio = o.ratio;
  CaseNames names;
  double loading = 0.0;
  if (o.rig) {
    plan.kind = "rig";
    plan.name = o.rig->name;
    for (int k = 1; k <= o.levels; ++k) {
      LevelPlan l;
      l.level = k;
      l.rig = rig_level(*o.rig, o.ratio, k);
      l.cells = l.rig.cells;
      l.layers = l.rig.layers;
      if (k > 1) {
        const LevelPlan& prev = plan.levels.back();
        if (l.cells > 0 && (l.cells <= prev.cells || l.layers < prev.layers))
          throw Error("--ratio " + number(o.ratio) + ": level " + std::to_string(k) + " (" +
                      std::to_string(l.cells) + " cells, " + std::to_string(l.layers) +
                      " layers) does not refine level " + std::to_string(k - 1) + " (" +
                      std::to_string(prev.cells) + " cells, " + std::to_string(prev.layers) +
                      " layers): give a larger ratio or more cells");
      }
      try {
        rigs::validate(l.rig);
      } catch (const Error& e) {
        throw Error("level " + std::to_string(k) + " of " + std::to_string(o.levels) + " (" +
                    std::to_string(l.cells) + " cells, " + std::to_string(l.layers) +
                    " layers): " + e.what() + " (fewer --levels or a coarser first level)");
      }
      plan.levels.push_back(l);
    }
    const nlohmann::json doc = rigs::rig_case(plan.levels.front().rig, "level-1.msh");
    names = names_of(doc);
    plan.t_end = o.rig->history.t.back();
    loading = loading_end(o.rig->history);
  } else {
    plan.kind = "case";
    if (o.ratio != 2.0)
      throw Error("--ratio " + number(o.ratio) +
                  ": a case file's mesh is refined by splitting every tet into 8 (ratio 2); other ratios "
                  "need a rig (tmlab converge indentation|unconfined|confined|tension ...)");
    plan.base = *o.case_config;
    plan.name = plan.base.name;
    // The mesh sizes: the case's tets times 8 per level.
    const Mesh mesh = read_mesh(plan.base.mesh.file);
    const double finest = static_cast<double>(mesh.num_tets()) * std::pow(8.0, o.levels - 1);
    if (finest > kMaxLevelTets)
      throw Error("--levels " + std::to_string(o.levels) + ": the finest level of " + plan.base.mesh.file +
                  " (" + std::to_string(mesh.num_tets()) + " tets x 8^" + std::to_string(o.levels - 1) +
                  " = " + number(finest) + " tets) exceeds the limit of " + number(kMaxLevelTets) +
                  " tets: give fewer levels");
    for (int k = 1; k <= o.levels; ++k) {
      LevelPlan l;
      l.level = k;
      l.refinements = k - 1;
      plan.levels.push_back(l);
    }
    names = names_of(plan.base);
    plan.t_end = plan.base.solver.t_end;
    loading = plan.t_end;
  }
  if (!o.linear.empty()) {
    if (o.linear != "ldlt" && o.linear != "cholmod")
      throw Error("--linear " + o.linear + ": must be ldlt or cholmod");
    if (plan.kind == "case" && plan.base.solver.type == SolverSpec::Type::Explicit)
      throw Error("--linear " + o.linear + ": the case '" + plan.name +
                  "' runs the explicit solver, which makes no linear solves");
  }
  plan.available = recorded_series(names.conditions, names.probes, names.bodies);
  plan.quantities =
      o.quantities.empty() ? default_quantities(names.moving, names.probes, names.bodies) : o.quantities;
  for (std::size_t k = 0; k < plan.quantities.size(); ++k) {
    const std::string& q = plan.quantities[k];
    if (std::find(plan.available.begin(), plan.available.end(), q) == plan.available.end())
      throw Error("--quantity " + q + ": the " + plan.kind + " '" + plan.name +
                  "' records no such series (it records: " + joined(plan.available) + ")");
    if (std::find(plan.quantities.begin(), plan.quantities.begin() + static_cast<long>(k), q) !=
        plan.quantities.begin() + static_cast<long>(k))
      throw Error("--quantity " + q + ": given twice");
  }
  plan.times = o.times;
  if (plan.times.empty()) {
    plan.times.push_back(loading);
    if (plan.t_end != loading) plan.times.push_back(plan.t_end);
  }
  for (std::size_t k = 0; k < plan.times.size(); ++k) {
    const double t = plan.times[k];
    if (!std::isfinite(t) || t < 0.0 || t > plan.t_end * (1.0 + 1e-12))
      throw Error("--time " + number(t) + ": outside the " + plan.kind + "'s time span [0, " +
                  number(plan.t_end) + "] s");
    for (std::size_t j = 0; j < k; ++j)
      if (plan.times[j] == t) throw Error("--time " + number(t) + ": given twice");
  }
  return plan;
}

double value_at(const std::vector<double>& time, const std::vector<double>& values, double t,
                const std::string& what) {
  if (time.empty() || time.size() != values.size())
    throw Error(what + ": " + std::to_string(values.size()) + " values for " + std::to_string(time.size()) +
                " recorded times");
  const double span = time.back() - time.front();
  const double slack = 1e-9 * std::max(std::abs(span), std::abs(time.back()));
  if (t < time.front() - slack || t > time.back() + slack)
    throw Error(what + ": --time " + number(t) + " lies outside the recorded times [" + number(time.front()) +
                ", " + number(time.back()) + "] s");
  if (t <= time.front()) return values.front();
  if (t >= time.back()) return values.back();
  const auto hi = static_cast<std::size_t>(std::upper_bound(time.begin(), time.end(), t) - time.begin());
  const std::size_t lo = hi - 1;
  if (time[lo] == t || time[hi] == time[lo]) return values[lo];
  const double w = (t - time[lo]) / (time[hi] - time[lo]);
  return (1.0 - w) * values[lo] + w * values[hi];
}

StudyResult run_study(const StudyPlan& plan, const StudyOptions& o, const fs::path& dir) {
  StudyResult result;
  const fs::path meshes = dir / "meshes", levels = dir / "levels";
  fs::create_directories(meshes);
  fs::create_directories(levels);
  std::vector<std::string> units;
  Mesh refined;  // case: the previous level's mesh, refined once more for the next
  const int n = static_cast<int>(plan.levels.size());
  for (const LevelPlan& l : plan.levels) {
    check_interrupt("between convergence levels");
    const auto wall0 = std::chrono::steady_clock::now();
    CaseConfig cfg;
    Mesh mesh;
    const fs::path mesh_file = meshes / (level_name(l.level) + ".msh");
    if (plan.kind == "rig") {
      mesh = rigs::rig_mesh(l.rig);
      write_gmsh22(mesh, mesh_file.string());
      cfg = parse_case(rigs::rig_case(l.rig, mesh_file.filename().string()),
                       "the rig of convergence level " + std::to_string(l.level), {meshes.string()});
    } else {
      cfg = plan.base;
      if (l.refinements == 0) {
        mesh = read_mesh(plan.base.mesh.file);
      } else {
        mesh = refine_uniform(refined);
        write_gmsh22(mesh, mesh_file.string());
        cfg.mesh.file = mesh_file.string();
      }
      refined = mesh;
    }
    cfg.name = level_name(l.level);
    cfg.output.vtu = false;  // the study reads timeseries.h5 only; fields of fine levels are large
    cfg.output.xdmf = false;
    cfg.output.plots = false;
    if (!o.linear.empty())  // checked by plan_study
      cfg.solver.linear = o.linear == "cholmod" ? SolverSpec::Linear::Cholmod : SolverSpec::Linear::Ldlt;
    LevelResult r;
    r.level = l.level;
    r.cells = l.cells;
    r.layers = l.layers;
    r.refinements = l.refinements;
    r.points = static_cast<long>(mesh.num_points());
    r.tets = static_cast<long>(mesh.num_tets());
    r.dofs = 3 * r.points;
    r.volume = mesh_volume(mesh) * std::pow(cfg.mesh.scale, 3);
    r.h = std::cbrt(r.volume / static_cast<double>(r.tets));
    if (o.log) {
      std::ostringstream os;
      os << "level " << l.level << "/" << n << ": ";
      if (plan.kind == "rig")
        os << l.cells << " cells, " << l.layers << " layers";
      else
        os << l.refinements << " refinement" << (l.refinements == 1 ? "" : "s");
      os << ", " << r.tets << " tets, " << r.points << " nodes, h = " << number(r.h) << " m: running";
      o.log(os.str());
    }
    RunOptions ro;
    ro.results_root = levels.string();
    ro.tmlab_root = o.tmlab_root;
    ro.command_line = o.command_line;
    ro.plots = false;
    ro.log = o.run_log;
    const RunResult run = tm::run_case(cfg, ro);
    r.dir = (fs::path("levels") / cfg.name).string();
    r.values = read_values(run.dir, plan, units.empty() ? &units : nullptr);
    r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    if (o.log) {
      std::ostringstream os;
      os << "level " << l.level << "/" << n << ": done in " << number(r.wall_seconds) << " s:";
      for (std::size_t q = 0; q < plan.quantities.size(); ++q)
        for (std::size_t t = 0; t < plan.times.size(); ++t)
          os << " " << plan.quantities[q] << "(t=" << number(plan.times[t])
             << ") = " << number(r.values[q][t]);
      o.log(os.str());
    }
    result.levels.push_back(r);
    note_progress_point();
  }
  std::vector<double> h;
  for (const LevelResult& r : result.levels) h.push_back(r.h);
  for (std::size_t q = 0; q < plan.quantities.size(); ++q)
    for (std::size_t t = 0; t < plan.times.size(); ++t) {
      QuantityResult qr;
      qr.quantity = plan.quantities[q];
      qr.unit = units[q];
      qr.time = plan.times[t];
      std::vector<double> v;
      for (const LevelResult& r : result.levels) v.push_back(r.values[q][t]);
      qr.analysis = analyse_convergence(h, v);
      result.quantities.push_back(qr);
    }
  return result;
}

}  // namespace tmlab::convergence
