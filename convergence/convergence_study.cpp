#include "convergence/convergence_study.hpp"

#include "core/base/error.hpp"
#include "core/base/interrupt.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/mesh/gmsh_reader.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/mesh/mesh_quality.hpp"
#include "core/mesh/mesh_refine.hpp"
#include "core/results/result_dir.hpp"
#include "core/results/run_output.hpp"
#include "core/results/series_names.hpp"
#include "core/results/unit_checkpoint.hpp"
#include "runner/case_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <unistd.h>

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

/// What makes a rig's state depend on its load steps (time_dependence() of its case, from the
/// case document: the mesh is not needed).
std::string rig_time_dependence(const nlohmann::json& doc) {
  std::vector<std::string> why;
  if (parse_material_section(doc.at("material"), "the rig's --material").viscoelastic.enabled)
    why.push_back("a viscoelastic material");
  if (doc.contains("contact"))
    for (const auto& b : doc["contact"].value("bodies", nlohmann::json::array()))
      if (b.value("mode", "frictionless") == "bonded")
        why.push_back("bonded contact (body " + b.value("name", std::string("?")) + ")");
  std::string s;
  for (const std::string& w : why) s += (s.empty() ? "" : "; ") + w;
  return s;
}

/// The steps of a rig level refined in time: steps_per_sample times ratio^(k-1), rounded.
rigs::RigSpec rig_time_level(const rigs::RigSpec& base, double ratio, int level) {
  rigs::RigSpec s = base;
  s.steps_per_sample =
      static_cast<int>(std::lround(static_cast<double>(base.steps_per_sample) * std::pow(ratio, level - 1)));
  s.name = level_name(level);
  return s;
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

std::string to_string(Refine r) { return r == Refine::Time ? "time" : "space"; }

std::string time_dependence(const CaseConfig& c) {
  std::vector<std::string> why;
  if (c.solver.type != SolverSpec::Type::Static)
    why.push_back(std::string("dynamics (solver ") +
                  (c.solver.type == SolverSpec::Type::Explicit ? "explicit" : "implicit") + ")");
  if (c.material.viscoelastic.enabled) why.push_back("a viscoelastic material");
  if (c.contact.enabled)
    for (const ContactBodySpec& b : c.contact.bodies)
      if (b.mode == ContactBodyMode::Bonded) why.push_back("bonded contact (body " + b.name + ")");
  std::string s;
  for (const std::string& w : why) s += (s.empty() ? "" : "; ") + w;
  return s;
}

namespace {

/// The levels of a rig refined in time (plan_study's four kinds of study each fill `plan.levels`,
/// `names` and `plan.t_end`, and return the end of the loading).
double plan_rig_in_time(const StudyOptions& o, StudyPlan& plan, CaseNames& names) {
  plan.kind = "rig";
  plan.name = o.rig->name;
  for (int k = 1; k <= o.levels; ++k) {
    LevelPlan l;
    l.level = k;
    l.rig = rig_time_level(*o.rig, o.ratio, k);
    l.cells = l.rig.cells;
    l.layers = l.rig.layers;
    try {
      rigs::validate(l.rig);
    } catch (const Error& e) {
      throw Error("level " + std::to_string(k) + " of " + std::to_string(o.levels) + " (" +
                  std::to_string(l.rig.steps_per_sample) + " steps per segment): " + e.what() +
                  " (fewer --levels or fewer --steps-per-segment)");
    }
    l.steps = static_cast<long>(rigs::rig_load_steps(l.rig));
    l.dt = l.rig.history.t.back() / static_cast<double>(l.steps);
    if (k > 1 && l.steps <= plan.levels.back().steps)
      throw Error("--ratio " + number(o.ratio) + ": level " + std::to_string(k) + " (" +
                  std::to_string(l.steps) + " load steps) does not refine level " + std::to_string(k - 1) +
                  " (" + std::to_string(plan.levels.back().steps) +
                  " load steps): give a larger ratio or more --steps-per-segment");
    plan.levels.push_back(l);
    if (k == 1) {  // validated: its case can be written
      plan.time_dependence = rig_time_dependence(rigs::rig_case(l.rig, "mesh.msh"));
      if (plan.time_dependence.empty())
        throw Error("--refine-in time: the rig '" + plan.name +
                    "' does not depend on its load steps (static, elastic and frictionless: its state at "
                    "a time is the same whatever the steps); a time-step study needs a viscoelastic "
                    "material (--material with a viscoelastic section), bonded contact "
                    "(--indenter-contact bonded) or a case with dynamics");
    }
  }
  names = names_of(rigs::rig_case(plan.levels.front().rig, "mesh.msh"));
  plan.t_end = o.rig->history.t.back();
  return loading_end(o.rig->history);
}

/// The levels of a case refined in time.
double plan_case_in_time(const StudyOptions& o, StudyPlan& plan, CaseNames& names) {
  plan.kind = "case";
  plan.base = *o.case_config;
  plan.name = plan.base.name;
  plan.time_dependence = time_dependence(plan.base);
  if (plan.time_dependence.empty())
    throw Error("--refine-in time: the case '" + plan.name +
                "' does not depend on its load steps (a static solve of an elastic material without "
                "bonded contact: its state at a time is the same whatever solver.steps); a time-step "
                "study needs dynamics (solver explicit or implicit), a viscoelastic material or bonded "
                "contact");
  const SolverSpec& sv = plan.base.solver;
  const bool dynamic = sv.type != SolverSpec::Type::Static;
  for (int k = 1; k <= o.levels; ++k) {
    LevelPlan l;
    l.level = k;
    const double f = std::pow(o.ratio, k - 1);
    const double steps = dynamic ? std::ceil(sv.t_end / (sv.dt / f) - 1e-9) : std::round(sv.steps * f);
    const double limit = dynamic ? kMaxDynamicSteps : kMaxStaticSteps;
    if (steps > limit)
      throw Error("--levels " + std::to_string(o.levels) + ": level " + std::to_string(k) + " of " +
                  plan.base.file + " would take " + number(steps) + (dynamic ? " time" : " load") +
                  " steps, beyond the limit of " + number(limit) + ": give fewer levels or a smaller ratio");
    l.steps = static_cast<long>(steps);
    l.dt = dynamic ? sv.dt / f : sv.t_end / steps;
    if (k > 1 && !(l.dt < plan.levels.back().dt && l.steps > plan.levels.back().steps))
      throw Error("--ratio " + number(o.ratio) + ": level " + std::to_string(k) + " (" +
                  std::to_string(l.steps) + " steps) does not refine level " + std::to_string(k - 1) + " (" +
                  std::to_string(plan.levels.back().steps) + " steps): give a larger ratio");
    plan.levels.push_back(l);
  }
  names = names_of(plan.base);
  plan.t_end = sv.t_end;
  return plan.t_end;
}

/// The levels of a rig refined in space.
double plan_rig_in_space(const StudyOptions& o, StudyPlan& plan, CaseNames& names) {
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
      const std::string size =
          l.cells > 0 ? std::to_string(l.cells) + " cells, " + std::to_string(l.layers) + " layers"
                      : "refinement " + number(l.rig.refinement);
      throw Error("level " + std::to_string(k) + " of " + std::to_string(o.levels) + " (" + size +
                  "): " + e.what() + " (fewer --levels or a coarser first level)");
    }
    l.steps = static_cast<long>(rigs::rig_load_steps(l.rig));
    l.dt = l.rig.history.t.back() / static_cast<double>(l.steps);
    plan.levels.push_back(l);
  }
  const nlohmann::json doc = rigs::rig_case(plan.levels.front().rig, "level-1.msh");
  names = names_of(doc);
  plan.t_end = o.rig->history.t.back();
  return loading_end(o.rig->history);
}

/// The levels of a case refined in space (uniform refinement of its mesh).
double plan_case_in_space(const StudyOptions& o, StudyPlan& plan, CaseNames& names) {
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
                " (" + std::to_string(mesh.num_tets()) + " tets x 8^" + std::to_string(o.levels - 1) + " = " +
                number(finest) + " tets) exceeds the limit of " + number(kMaxLevelTets) +
                " tets: give fewer levels");
  for (int k = 1; k <= o.levels; ++k) {
    LevelPlan l;
    l.level = k;
    l.refinements = k - 1;
    l.steps = plan.base.solver.steps;
    l.dt = plan.base.solver.type == SolverSpec::Type::Static ? plan.base.solver.t_end / plan.base.solver.steps
                                                             : plan.base.solver.dt;
    plan.levels.push_back(l);
  }
  names = names_of(plan.base);
  plan.t_end = plan.base.solver.t_end;
  return plan.t_end;
}

}  // namespace

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
  plan.refine = o.refine;
  const bool in_time = o.refine == Refine::Time;
  CaseNames names;
  const double loading =
      o.rig ? (in_time ? plan_rig_in_time(o, plan, names) : plan_rig_in_space(o, plan, names))
            : (in_time ? plan_case_in_time(o, plan, names) : plan_case_in_space(o, plan, names));
  if (!o.linear.empty()) {
    if (!linear_solver_from_string(o.linear))
      throw Error("--linear " + o.linear + ": must be auto, ldlt or cholmod");
    if (plan.kind == "case" && plan.base.solver.type == SolverSpec::Type::Explicit)
      throw Error("--linear " + o.linear + ": the case '" + plan.name +
                  "' runs the explicit solver, which makes no linear solves");
    plan.linear = o.linear;
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

namespace {

/// One level's case, built as the run needs it: its mesh (written into the level's mesh folder
/// when it is not the case's own) and its case, the level's name, no fields, no plots.
struct LevelCase {
  Mesh mesh;
  CaseConfig cfg;
};

/// Builds the levels of a plan in order (a case's refined mesh comes from the previous level's).
class LevelBuilder {
 public:
  LevelBuilder(const StudyPlan& plan, fs::path meshes) : plan_(plan), meshes_(std::move(meshes)) {}

  LevelCase next(const LevelPlan& l) {
    LevelCase c;
    const bool in_time = plan_.refine == Refine::Time;
    if (plan_.kind == "rig") {
      // In time every level has level 1's mesh: one file, written once.
      const fs::path mesh_file = meshes_ / (in_time ? std::string("mesh.msh") : level_name(l.level) + ".msh");
      if (!in_time || l.level == 1) {
        previous_ = rigs::rig_mesh(l.rig);
        write_gmsh22(previous_, mesh_file.string());
      }
      c.mesh = previous_;
      c.cfg = parse_case(rigs::rig_case(l.rig, mesh_file.filename().string()),
                         "the rig of convergence level " + std::to_string(l.level), {meshes_.string()});
    } else {
      c.cfg = plan_.base;
      if (l.level == 1) {
        c.mesh = read_mesh(plan_.base.mesh.file);
      } else if (in_time) {
        c.mesh = previous_;
      } else {
        c.mesh = refine_uniform(previous_);
        const fs::path mesh_file = meshes_ / (level_name(l.level) + ".msh");
        write_gmsh22(c.mesh, mesh_file.string());
        c.cfg.mesh.file = mesh_file.string();
      }
      previous_ = c.mesh;
      if (in_time) {
        c.cfg.solver.steps = static_cast<int>(l.steps);
        if (c.cfg.solver.type != SolverSpec::Type::Static) c.cfg.solver.dt = l.dt;
      }
    }
    c.cfg.name = level_name(l.level);
    c.cfg.output.vtu = false;  // the study reads timeseries.h5 only; fields of fine levels are large
    c.cfg.output.xdmf = false;
    c.cfg.output.plots = false;
    if (!plan_.linear.empty())  // checked by plan_study
      c.cfg.solver.linear =
          plan_.linear == "cholmod" ? SolverSpec::Linear::Cholmod : SolverSpec::Linear::Ldlt;
    return c;
  }

 private:
  const StudyPlan& plan_;
  fs::path meshes_;
  Mesh previous_;  ///< the previous level's mesh (rig in time: the one mesh)
};

/// A temporary folder of this process (the candidate meshes check_resume compares), removed with
/// everything in it (all of it written here) when it goes.
class ScratchDir {
 public:
  ScratchDir() {
    std::string templ = (fs::temp_directory_path() / "tmlab-converge-XXXXXX").string();
    if (!::mkdtemp(templ.data())) throw Error(templ + ": cannot create a temporary folder");
    path_ = templ;
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

/// The first place two JSON documents differ, as "key 'a.b[2]': X there, Y here" ("" when equal).
std::string first_difference(const nlohmann::json& was, const nlohmann::json& now, const std::string& at) {
  if (was == now) return "";
  if (was.is_object() && now.is_object()) {
    for (auto it = now.begin(); it != now.end(); ++it) {
      const std::string key = at.empty() ? it.key() : at + "." + it.key();
      if (!was.contains(it.key())) return "key '" + key + "': absent there, " + it.value().dump() + " here";
      if (std::string d = first_difference(was.at(it.key()), it.value(), key); !d.empty()) return d;
    }
    for (auto it = was.begin(); it != was.end(); ++it)
      if (!now.contains(it.key()))
        return "key '" + (at.empty() ? it.key() : at + "." + it.key()) + "': " + it.value().dump() +
               " there, absent here";
  }
  if (was.is_array() && now.is_array() && was.size() == now.size())
    for (std::size_t k = 0; k < now.size(); ++k)
      if (std::string d = first_difference(was.at(k), now.at(k), at + "[" + std::to_string(k) + "]");
          !d.empty())
        return d;
  std::string a = was.dump(), b = now.dump();
  if (a.size() > 120) a = a.substr(0, 117) + "...";
  if (b.size() > 120) b = b.substr(0, 117) + "...";
  return "key '" + at + "': " + a + " there, " + b + " here";
}

constexpr const char* kRestart =
    "; run without --resume to start the study again (its level runs are replaced), or write elsewhere "
    "with --out";

/// Refuses (tmlab::Error) a level run whose manifest is not of `cfg` on a mesh of hash `mesh_hash`.
void check_same_run(const fs::path& manifest_file, const std::string& level, const CaseConfig& cfg,
                    const std::string& mesh_hash) {
  nlohmann::json m;
  try {
    std::ifstream in(manifest_file);
    if (!in) throw Error("cannot open");
    m = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw Error("--resume: " + level + ": its manifest " + manifest_file.string() + " is unreadable (" +
                e.what() + ")" + kRestart);
  }
  if (!m.contains("config") || !m["config"].is_object() || !m.contains("inputs"))
    throw Error("--resume: " + level + ": " + manifest_file.string() + " has no config or inputs" + kRestart);
  nlohmann::json was = m["config"], now = effective_case_json(cfg);
  // The mesh is compared by its bytes (below); where it lay does not matter.
  const std::string was_mesh = was.contains("mesh") ? was["mesh"].value("file", std::string()) : "";
  for (nlohmann::json* j : {&was, &now})
    if (j->contains("mesh") && (*j)["mesh"].is_object()) (*j)["mesh"].erase("file");
  if (const std::string d = first_difference(was, now, ""); !d.empty())
    throw Error("--resume: " + level + " was run from another plan (its case differs at " + d + ")" +
                kRestart);
  // The manifest names its inputs by absolute path (make_manifest).
  const std::string mesh_path = fs::absolute(fs::path(was_mesh)).lexically_normal().string();
  std::string hash;
  for (const auto& in : m["inputs"])
    if (in.value("path", std::string()) == mesh_path) hash = in.value("fnv1a64", std::string());
  if (hash != mesh_hash)
    throw Error("--resume: " + level + " was run from another plan (its mesh " + was_mesh + " has hash " +
                (hash.empty() ? std::string("(none recorded)") : hash) + ", this plan's mesh " + mesh_hash +
                ")" + kRestart);
}

/// The Interrupted of a level, saying how to continue the study.
Interrupted study_stopped(const Interrupted& e, int level, int levels) {
  return Interrupted(e.signal(), std::string(e.what()) + " (convergence level " + std::to_string(level) +
                                     " of " + std::to_string(levels) + ", " + std::to_string(level - 1) +
                                     " finished): continue the study with the same command and --resume");
}

}  // namespace

std::vector<LevelAction> check_resume(const StudyPlan& plan, const fs::path& staging) {
  const int n = static_cast<int>(plan.levels.size());
  std::vector<LevelAction> actions(plan.levels.size(), LevelAction::Run);
  const fs::path levels = staging / "levels";
  std::error_code ec;
  if (!fs::is_directory(levels, ec)) return actions;
  // A level folder this plan does not have: the study was planned otherwise.
  for (const auto& e : fs::directory_iterator(levels, ec)) {
    const std::string name = e.path().filename().string();
    int k = 0;
    if (name.rfind("level-", 0) == 0) k = std::atoi(name.c_str() + 6);
    if (k < 1 || k > n || name != level_name(k))
      throw Error("--resume: levels/" + name + " is not a level of this study (" + std::to_string(n) +
                  " levels): it was planned with other options" + kRestart);
  }
  const ScratchDir scratch;
  LevelBuilder builder(plan, scratch.path());
  for (const LevelPlan& l : plan.levels) {
    const LevelCase c = builder.next(l);
    const fs::path dir = levels / level_name(l.level);
    const std::string label = "levels/" + level_name(l.level);
    if (fs::exists(dir / RunOutput::kSummary)) {
      check_same_run(dir / "manifest.json", label, c.cfg, file_hash(c.cfg.mesh.file));
      actions[static_cast<std::size_t>(l.level - 1)] = LevelAction::Reuse;
    } else if (fs::exists(dir / RunOutput::kInterrupted) &&
               fs::exists(dir / RunOutput::kStaging / "checkpoint.h5")) {
      check_same_run(dir / RunOutput::kStaging / "manifest.json", label, c.cfg, file_hash(c.cfg.mesh.file));
      actions[static_cast<std::size_t>(l.level - 1)] = LevelAction::Continue;
    }
  }
  return actions;
}

StudyResult run_study(const StudyPlan& plan, const StudyOptions& o, const fs::path& dir,
                      const std::vector<LevelAction>& resume) {
  StudyResult result;
  const fs::path meshes = dir / "meshes", levels = dir / "levels";
  fs::create_directories(meshes);
  fs::create_directories(levels);
  std::vector<std::string> units;
  LevelBuilder builder(plan, meshes);
  const int n = static_cast<int>(plan.levels.size());
  const bool in_time = plan.refine == Refine::Time;
  for (const LevelPlan& l : plan.levels) {
    try {
      check_interrupt("between convergence levels");
    } catch (const Interrupted& e) {
      throw study_stopped(e, l.level, n);
    }
    const LevelAction action =
        resume.empty() ? LevelAction::Run : resume.at(static_cast<std::size_t>(l.level - 1));
    const auto wall0 = std::chrono::steady_clock::now();
    const LevelCase c = builder.next(l);
    const CaseConfig& cfg = c.cfg;
    LevelResult r;
    r.level = l.level;
    r.cells = l.cells;
    r.layers = l.layers;
    r.refinements = l.refinements;
    r.points = static_cast<long>(c.mesh.num_points());
    r.tets = static_cast<long>(c.mesh.num_tets());
    r.dofs = 3 * r.points;
    r.volume = mesh_volume(c.mesh) * std::pow(cfg.mesh.scale, 3);
    r.h = std::cbrt(r.volume / static_cast<double>(r.tets));
    r.steps = l.steps;
    r.dt = l.dt;
    r.size = in_time ? r.dt : r.h;
    r.run = action == LevelAction::Reuse ? "reused" : action == LevelAction::Continue ? "continued" : "new";
    if (o.log) {
      std::ostringstream os;
      os << "level " << l.level << "/" << n << ": ";
      if (in_time)
        os << l.steps << " steps, dt = " << number(l.dt) << " s";
      else if (plan.kind == "rig" && l.cells > 0)
        os << l.cells << " cells, " << l.layers << " layers";
      else if (plan.kind == "rig")  // the mesh rule's form: every cell count of the graded mesh scaled
        os << "refinement " << number(l.rig.refinement);
      else
        os << l.refinements << " refinement" << (l.refinements == 1 ? "" : "s");
      if (!in_time) os << ", " << r.tets << " tets, " << r.points << " nodes, h = " << number(r.h) << " m";
      os << (action == LevelAction::Reuse      ? ": reused (its run was complete)"
             : action == LevelAction::Continue ? ": continuing its interrupted run from its checkpoint"
                                               : ": running");
      o.log(os.str());
    }
    fs::path run_dir = levels / cfg.name;
    if (action == LevelAction::Reuse) {
      std::ifstream in(run_dir / RunOutput::kSummary);
      const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
      r.wall_seconds = summary.is_object() ? summary.value("wall_seconds", 0.0) : 0.0;
    } else {
      RunOptions ro;
      ro.results_root = levels.string();
      ro.tmlab_root = o.tmlab_root;
      ro.command_line = o.command_line;
      ro.plots = false;
      ro.log = o.run_log;
      ro.resume = action == LevelAction::Continue;
      try {
        run_dir = tm::run_case(cfg, ro).dir;
      } catch (const Interrupted& e) {
        throw study_stopped(e, l.level, n);
      }
    }
    r.dir = (fs::path("levels") / cfg.name).string();
    r.values = read_values(run_dir, plan, units.empty() ? &units : nullptr);
    if (action != LevelAction::Reuse)
      r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    if (o.log) {
      std::ostringstream os;
      os << "level " << l.level << "/" << n << ": "
         << (action == LevelAction::Reuse ? "its run took " : "done in ") << number(r.wall_seconds) << " s:";
      for (std::size_t q = 0; q < plan.quantities.size(); ++q)
        for (std::size_t t = 0; t < plan.times.size(); ++t)
          os << " " << plan.quantities[q] << "(t=" << number(plan.times[t])
             << ") = " << number(r.values[q][t]);
      o.log(os.str());
    }
    result.levels.push_back(r);
    if (action != LevelAction::Reuse) note_progress_point();  // a finished level is what --resume reuses
  }
  std::vector<double> h;
  for (const LevelResult& r : result.levels) h.push_back(r.size);
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
