#include "convergence/convergence_report.hpp"

#include "core/base/format.hpp"
#include "core/results/json_number.hpp"

#include <cmath>
#include <sstream>

namespace tmlab::convergence {

namespace {

using nlohmann::json;

const char* kHDefinition = "(V / tets)^(1/3): the mesh volume per tet, as a length (Celik et al. 2008)";
const char* kDtDefinition =
    "the time step: t_end / steps (static load steps) or solver.dt (dynamics); the mesh is fixed";

bool in_time(const StudyPlan& plan) { return plan.refine == Refine::Time; }
/// The key of the level size in converge.json: h_m in space, dt_s in time.
const char* size_key(const StudyPlan& plan) { return in_time(plan) ? "dt_s" : "h_m"; }
/// The level size as shown in converge.md: h in mm, dt in s.
std::string size_header(const StudyPlan& plan) { return in_time(plan) ? "dt (s)" : "h (mm)"; }
std::string size_cell(const StudyPlan& plan, double size) {
  return significant(in_time(plan) ? size : 1e3 * size, 4);
}

std::string order_method(const ConvergenceAnalysis& a) {
  return a.constant_ratio
             ? "constant ratio: p = ln((f_k - f_k-1) / (f_k+1 - f_k)) / ln r"
             : "ratios differ: p solves (f_k - f_k-1) / (f_k+1 - f_k) = (r_k^p - 1) / (1 - r_k+1^-p)";
}

/// A number for a table cell ("-" when it does not exist).
std::string cell(double v, int digits = 6) { return std::isfinite(v) ? significant(v, digits) : "-"; }
std::string percent(double v) { return std::isfinite(v) ? significant(100.0 * v, 3) + " %" : "-"; }

std::string quantity_label(const QuantityResult& q) {
  return q.quantity + " at t = " + significant(q.time, 6) + " s" +
         (q.unit.empty() ? "" : " (" + q.unit + ")");
}

}  // namespace

json plan_json(const StudyPlan& plan) {
  json j = {{"kind", plan.kind},
            {"name", plan.name},
            {"refine", to_string(plan.refine)},
            {"levels", plan.levels.size()},
            {"ratio", plan.ratio},
            {"quantities", plan.quantities},
            {"times_s", plan.times},
            {"t_end_s", plan.t_end}};
  if (plan.kind == "rig") {
    const rigs::RigSpec& s = plan.levels.front().rig;
    j["rig"] = {{"test", rigs::rig_test_name(s.test)},
                {"cells", s.cells},
                {"layers", s.layers},
                {"grading", s.grading},
                {"steps_per_sample", s.steps_per_sample},
                {"level_1_case", rigs::rig_case(s, "level-1.msh")}};
  } else {
    j["case_file"] = plan.base.file;
    j["mesh_file"] = plan.base.mesh.file;
  }
  if (in_time(plan)) {
    j["time_dependence"] = plan.time_dependence;
    json steps = json::array();
    for (const LevelPlan& l : plan.levels) steps.push_back(l.steps);
    j["steps"] = steps;
  }
  return j;
}

json study_json(const StudyPlan& plan, const StudyResult& result) {
  json levels = json::array();
  for (const LevelResult& l : result.levels) {
    json e = {{"level", l.level}};
    if (plan.kind == "rig") {
      e["cells"] = l.cells;
      e["layers"] = l.layers;
    } else {
      e["refinements"] = l.refinements;
    }
    e["points"] = l.points;
    e["tets"] = l.tets;
    e["dofs"] = l.dofs;
    e["volume_m3"] = l.volume;
    e["h_m"] = l.h;
    e["steps"] = l.steps;
    e["dt_s"] = l.dt;
    e["wall_seconds"] = l.wall_seconds;
    e["dir"] = l.dir;
    e["run"] = l.run;
    levels.push_back(e);
  }
  json quantities = json::array();
  for (const QuantityResult& q : result.quantities) {
    const ConvergenceAnalysis& a = q.analysis;
    json orders = json::array();
    for (const TripleOrder& t : a.triples)
      orders.push_back({{"levels", {t.first + 1, t.first + 2, t.first + 3}},
                        {"order", finite_or_null(t.order)},
                        {"problem", t.problem.empty() ? json(nullptr) : json(t.problem)}});
    json per_level = json::array();
    for (std::size_t k = 0; k < a.value.size(); ++k)
      per_level.push_back({{"level", k + 1},
                           {size_key(plan), a.h[k]},
                           {"value", a.value[k]},
                           {"relative_error", finite_or_null(a.relative_error[k])},
                           {"gci", finite_or_null(a.gci[k])}});
    json ratios = json::array();
    for (std::size_t k = 1; k < a.ratio.size(); ++k) ratios.push_back(a.ratio[k]);
    quantities.push_back(
        {{"name", q.quantity},
         {"unit", q.unit},
         {"time_s", q.time},
         {"values", a.value},
         {size_key(plan), a.h},
         {"ratios", ratios},
         {"constant_ratio", a.constant_ratio},
         {"order_method", order_method(a)},
         {"observed_orders", orders},
         {"order_spread", finite_or_null(a.order_spread)},
         {"max_order_spread", kMaxOrderSpread},
         {"verdict", a.verdict},
         {"reason", a.reason.empty() ? json(nullptr) : json(a.reason)},
         {"note", a.note.empty() ? json(nullptr) : json(a.note)},
         {"order", finite_or_null(a.order)},
         {"extrapolated", finite_or_null(a.extrapolated)},
         {"extrapolation_note", a.asymptotic
                                    ? "Richardson from the two finest levels with the finest triple's order"
                                    : "none: " + a.reason},
         {"safety_factor", kSafetyFactor},
         {"levels", per_level}});
  }
  return {{"format", "tmlab-converge/1"},
          {"options", plan_json(plan)},
          {in_time(plan) ? "dt_definition" : "h_definition", in_time(plan) ? kDtDefinition : kHDefinition},
          {"levels", levels},
          {"quantities", quantities}};
}

std::string study_markdown(const StudyPlan& plan, const StudyResult& result,
                           const std::string& command_line) {
  std::ostringstream md;
  md << "# Convergence study in " << (in_time(plan) ? "time" : "space") << ": " << plan.kind << " "
     << plan.name << "\n\n"
     << "`" << command_line << "`\n\n"
     << (in_time(plan)
             ? std::string("dt = ") + kDtDefinition + " (time dependence: " + plan.time_dependence + ")"
             : std::string("h = ") + kHDefinition)
     << ". Observed order from each level triple, Richardson extrapolation from the "
     << "two finest levels, estimated error |f_k - f_inf| / |f_inf|, GCI_k = 1.25 |f_k - f_k-1| / |f_k| / "
     << "(r_k^p - 1) (docs/convergence.md).\n\n";
  if (in_time(plan)) {
    md << "| level | steps | dt (s) | tets | nodes | wall (s) | run |\n|---|---|---|---|---|---|---|\n";
    for (const LevelResult& l : result.levels)
      md << "| " << l.level << " | " << l.steps << " | " << significant(l.dt, 4) << " | " << l.tets << " | "
         << l.points << " | " << significant(l.wall_seconds, 3) << " | " << l.run << " |\n";
  } else {
    md << "| level | " << (plan.kind == "rig" ? "cells x layers" : "refinements")
       << " | tets | nodes | h (mm) | wall (s) | run |\n"
       << "|---|---|---|---|---|---|---|\n";
    for (const LevelResult& l : result.levels)
      md << "| " << l.level << " | "
         << (plan.kind == "rig" ? std::to_string(l.cells) + " x " + std::to_string(l.layers)
                                : std::to_string(l.refinements))
         << " | " << l.tets << " | " << l.points << " | " << significant(1e3 * l.h, 4) << " | "
         << significant(l.wall_seconds, 3) << " | " << l.run << " |\n";
  }
  for (const QuantityResult& q : result.quantities) {
    const ConvergenceAnalysis& a = q.analysis;
    md << "\n## " << quantity_label(q) << "\n\n"
       << "| level | " << size_header(plan) << " | value | est. error | GCI |\n|---|---|---|---|---|\n";
    for (std::size_t k = 0; k < a.value.size(); ++k)
      md << "| " << k + 1 << " | " << size_cell(plan, a.h[k]) << " | " << cell(a.value[k], 8) << " | "
         << percent(a.relative_error[k]) << " | " << percent(a.gci[k]) << " |\n";
    md << "\nobserved orders:";
    for (const TripleOrder& t : a.triples)
      md << " levels " << t.first + 1 << "-" << t.first + 3 << ": "
         << (t.problem.empty() ? significant(t.order, 4) : "none (" + t.problem + ")") << ";";
    md << (a.constant_ratio ? " (constant ratio " + significant(a.ratio[1], 4) + ")" : " (ratios differ)")
       << "\n\n";
    if (a.asymptotic) {
      md << "**asymptotic**: order p = " << significant(a.order, 4) << ", extrapolated value "
         << cell(a.extrapolated, 8) << (q.unit.empty() ? "" : " " + q.unit) << "\n";
      if (!a.note.empty()) md << "(" << a.note << ")\n";
    } else {
      md << "**not asymptotic**: " << a.reason << "; no extrapolation\n";
    }
  }
  return md.str();
}

nlohmann::json study_summary(const StudyResult& result) {
  json q = json::array();
  for (const QuantityResult& r : result.quantities)
    q.push_back({{"name", r.quantity},
                 {"time_s", r.time},
                 {"verdict", r.analysis.verdict},
                 {"order", finite_or_null(r.analysis.order)},
                 {"extrapolated", finite_or_null(r.analysis.extrapolated)},
                 {"finest", r.analysis.value.back()}});
  return {{"levels", result.levels.size()}, {"quantities", q}};
}

ProcessStatus draw_plot(const std::string& tmlab_root, const std::filesystem::path& dir) {
  const std::filesystem::path script =
      std::filesystem::path(tmlab_root) / "convergence" / "python" / "tmlab_converge_plot.py";
  return run_python(script, {dir.string()}, ProcessOutput::to_file(dir / "plot.log"));
}

}  // namespace tmlab::convergence
