// The files of a convergence study (`tmlab converge`; docs/convergence.md): converge.json (the
// numbers, read by python/tmlab_converge_plot.py), converge.md (readable tables) and the
// effective options of the manifest. Numbers that do not exist (an extrapolation of a sequence
// that is not asymptotic, the GCI of the coarsest level) are JSON null, with the reason beside.
#pragma once

#include "convergence/convergence_study.hpp"
#include "core/base/process.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace tmlab::convergence {

/// The effective options of the study (manifest.json's config): the source (the rig's spec or
/// the case file), what the levels refine, levels, ratio, quantities, times (time: the time
/// dependence and each level's steps).
nlohmann::json plan_json(const StudyPlan& plan);

/// converge.json: "options" (plan_json; "refine": space | time), "h_definition" (time:
/// "dt_definition"), "levels" (level, cells / layers or refinements, points, tets, dofs, volume_m3,
/// h_m, steps, dt_s, wall_seconds, dir, run: new | reused | continued) and "quantities": per quantity
/// and time its name, unit, time_s, values, the level sizes (h_m in space, dt_s in time), ratios,
/// constant_ratio, order_method,
/// observed_orders (levels, order or null, problem), order_spread, verdict, reason, note, order,
/// extrapolated (null when not asymptotic) with extrapolation_note, and per level its value,
/// estimated relative error and GCI (null when not available).
nlohmann::json study_json(const StudyPlan& plan, const StudyResult& result);

/// converge.md: the levels and, per quantity and time, a table of the levels with the verdict.
std::string study_markdown(const StudyPlan& plan, const StudyResult& result, const std::string& command_line);

/// The short summary block of summary.json: per quantity and time the verdict, order and
/// extrapolated value.
nlohmann::json study_summary(const StudyResult& result);

/// Draws converge.png from `dir`/converge.json with convergence/python/tmlab_converge_plot.py
/// (run_python: no shell; its output to `dir`/plot.log). Returns how it ended; never throws for a
/// failing script.
ProcessStatus draw_plot(const std::string& tmlab_root, const std::filesystem::path& dir);

}  // namespace tmlab::convergence
