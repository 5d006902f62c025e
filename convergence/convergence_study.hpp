// A convergence study (issue 28, `tmlab converge`; docs/convergence.md): one rig or case run on a
// sequence of refined meshes (--refine-in space, the default) or time steps (--refine-in time)
// through the fast model's runner (runner/case_runner.hpp), the chosen quantities read from each
// level's timeseries.h5 at the chosen times, and each quantity's observed order, Richardson
// extrapolation, estimated errors and GCI (grid_convergence.hpp).
//
// The levels in space:
//   rig   (calibration/rigs): level k (1-based) has round(cells r^(k-1)) cells and
//         round(layers r^(k-1)) layers, every other field (the grading power among them) as given:
//         the whole graded mesh refined in its parameter space. With r = 2 the counts are exact; any
//         other r is rounded and the actual ratios of h are used (the non-constant-ratio order).
//   case  (a case file with a mesh file): level 1 is the case's mesh, level k its uniform
//         ("red") refinement k-1 times (core/mesh/mesh_refine.hpp): r = 2 exactly.
// The size of a level is the representative h = (V / tets)^(1/3) (V the mesh volume; Celik et al.
// 2008): for both kinds of refinement it scales exactly with the spacing, and it needs no notion of
// "the" cell size of a graded or unstructured mesh.
//
// The quantities are series of the runner's timeseries.h5 (core/results/series_names.hpp), e.g.
// contact_indenter_force_z, contact_indenter_radius, reaction_top_platen_z, probe_tip_norm,
// elastic_energy, each taken at each time by linear interpolation between recorded steps.
//
// The levels in time (the mesh fixed; its size h is the time step dt):
//   rig   level k has round(steps_per_sample r^(k-1)) load steps across the shortest history
//         segment (--steps-per-segment), so every step of the static history is divided by about r;
//         dt = t_end / (the rig's load steps).
//   case  static: round(solver.steps r^(k-1)) load steps, dt = t_end / steps; dynamics (explicit,
//         implicit): solver.dt / r^(k-1), dt that step.
// Only a problem whose state at a time depends on the step is accepted: dynamics, a viscoelastic
// material (the Prony recursion integrates over the steps) or bonded contact (a node sticks where it
// first touches); a static elastic frictionless problem gives the same state at a time whatever
// its load steps, and is refused naming --refine-in.
//
// Resuming (--resume; check_resume): the level runs are complete result folders of the runner's
// protocol (levels/level-<k>/summary.json, written last, marks a complete run). A complete level
// is reused when its manifest's effective case and the hash of its mesh are those this plan would
// run; an interrupted level with its checkpoint is continued from it on the same condition; any
// other level (absent, FAILED, killed) runs again. A level of another plan is refused, naming
// the first difference, before anything is written.
//
// Everything is checked before anything runs or is written (plan_study): the level count, that the
// levels refine, each level's rig against the rigs' limits, the mesh sizes, the quantities against
// the series the case records, the times against the case's time span.
#pragma once

#include "calibration/rigs/rig.hpp"
#include "convergence/grid_convergence.hpp"
#include "core/config/case_config.hpp"

#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace tmlab::convergence {

/// The largest number of levels (each costs about r^3 times the previous one).
inline constexpr int kMaxLevels = 8;
/// The largest mesh of a case-file level (the rigs' own limit, rigs::kMaxRigTets).
inline constexpr double kMaxLevelTets = rigs::kMaxRigTets;

/// The largest number of load steps of a static level (the rigs' limit, rigs::kMaxLoadSteps) and
/// of time steps of a dynamic one (the case files' limit).
inline constexpr double kMaxStaticSteps = static_cast<double>(rigs::kMaxLoadSteps);
inline constexpr double kMaxDynamicSteps = 1e8;

/// What the levels refine (--refine-in).
enum class Refine { Space, Time };
std::string to_string(Refine r);

struct StudyOptions {
  /// Exactly one source: a rig (level 1's spec) or a parsed case file (core/config load_case).
  std::optional<rigs::RigSpec> rig;
  std::optional<CaseConfig> case_config;
  std::string tmlab_root = ".";  ///< for the level runs
  int levels = 3;                ///< >= 3
  Refine refine = Refine::Space;
  /// Space: a rig's multiplier of cells and layers per level; a case: 2 only. Time: the divisor of
  /// the time step (the multiplier of the steps) per level.
  double ratio = 2.0;
  std::vector<std::string> quantities;  ///< series names; empty: default_quantities()
  std::vector<double> times;            ///< s; empty: default_times()
  /// The levels' solver.linear ("ldlt" | "cholmod"; empty: the case's or the rig's own, ldlt).
  std::string linear;
  /// Level runs' own progress and report (the runner's log; nullptr: silent).
  std::ostream* run_log = nullptr;
  std::function<void(const std::string&)> log;  ///< one line per level (may be empty)
  std::vector<std::string> command_line;        ///< for the level runs' manifests
};

/// One level as planned.
struct LevelPlan {
  int level = 0;              ///< 1-based
  int cells = 0, layers = 0;  ///< rig
  int refinements = 0;        ///< case: uniform refinements of the case's mesh
  rigs::RigSpec rig;          ///< rig: this level's spec (name "level-<k>")
  long steps = 0;             ///< load or time steps of the level's run
  double dt = 0.0;            ///< its time step, s (static: t_end / steps)
};

/// What a study will do, checked.
struct StudyPlan {
  std::string kind;  ///< "rig" | "case"
  Refine refine = Refine::Space;
  /// Time: what makes the state depend on the step ("a viscoelastic material", ...).
  std::string time_dependence;
  std::string name;  ///< the rig's or the case's name
  CaseConfig base;   ///< case: the parsed case file (rig: unset)
  std::vector<LevelPlan> levels;
  double ratio = 2.0;  ///< as requested
  std::vector<std::string> quantities;
  std::vector<double> times;
  std::vector<std::string> available;  ///< the series the case records (what --quantity accepts)
  double t_end = 0.0;
  std::string linear;  ///< the levels' solver.linear (StudyOptions::linear; empty: their own)
};

/// The series a case records per step (names of core/results/series_names.hpp): the scalars, each
/// Dirichlet condition's reaction, each probe's displacement, each contact body's outputs.
std::vector<std::string> recorded_series(const std::vector<std::string>& conditions,
                                         const std::vector<std::string>& probes,
                                         const std::vector<std::string>& bodies);

/// The default quantities: each contact body's force_z and radius; else the reaction norm of each
/// Dirichlet condition that moves (a prescribed non-zero value); each probe's displacement norm;
/// max_displacement when none of these exists.
std::vector<std::string> default_quantities(const std::vector<std::string>& moving_conditions,
                                            const std::vector<std::string>& probes,
                                            const std::vector<std::string>& bodies);

/// What makes a problem's state at a time depend on its steps: "dynamics (solver explicit)",
/// "a viscoelastic material", "bonded contact (body NAME)", joined by "; "; "" when nothing does (a
/// static, elastic, frictionless problem).
std::string time_dependence(const CaseConfig& config);

/// Checks the options and plans the levels; throws tmlab::Error naming the option ("--levels",
/// "--ratio", "--refine-in", "--quantity", "--time", the rig's field) before anything is computed
/// or written.
StudyPlan plan_study(const StudyOptions& options);

/// The value of series `values` (recorded at `time`) at time t, linear between recorded steps;
/// tmlab::Error naming `what` when t lies outside the recorded times (beyond 1e-9 of the span).
double value_at(const std::vector<double>& time, const std::vector<double>& values, double t,
                const std::string& what);

/// One level as run.
struct LevelResult {
  int level = 0;
  int cells = 0, layers = 0, refinements = 0;
  long points = 0, tets = 0, dofs = 0;  ///< dofs: 3 x points
  double volume = 0.0;                  ///< m^3
  double h = 0.0;                       ///< (volume / tets)^(1/3), m
  long steps = 0;                       ///< load or time steps
  double dt = 0.0;                      ///< s
  /// The size the analysis uses: h in space, dt in time.
  double size = 0.0;
  double wall_seconds = 0.0;  ///< of the level's run (a reused run: its own summary's)
  std::string run = "new";    ///< "new" | "reused" (complete before) | "continued" (from its checkpoint)
  std::string dir;            ///< the level's run, relative to the study folder
  std::vector<std::vector<double>> values;  ///< [quantity][time]
};

/// One quantity at one time over the levels.
struct QuantityResult {
  std::string quantity, unit;
  double time = 0.0;
  ConvergenceAnalysis analysis;
};

struct StudyResult {
  std::vector<LevelResult> levels;
  std::vector<QuantityResult> quantities;  ///< quantity-major, then time
};

/// What a resumed study does with each level.
enum class LevelAction { Run, Reuse, Continue };

/// --resume: what to do with each level run found in `staging` (the interrupted study's staging
/// folder, <dir>/.incomplete; nothing there: every level runs). Reads the folder only (the meshes
/// it compares are generated into a temporary folder of its own, removed after); throws tmlab::Error
/// ("--resume: levels/level-2 was run from another plan: ...; run without --resume ...") for a
/// level whose effective case or mesh differs from the plan's, or a level folder the plan does not
/// have.
std::vector<LevelAction> check_resume(const StudyPlan& plan, const std::filesystem::path& staging);

/// Runs the planned levels into `dir` (the study's staging folder: meshes/ and levels/level-<k>/,
/// complete runs of the runner's result protocol) and analyses every quantity. `resume` (from
/// check_resume; empty: run every level) reuses or continues levels. A stop request (SIGINT/SIGTERM)
/// between or inside level runs throws tmlab::Interrupted saying how to resume.
StudyResult run_study(const StudyPlan& plan, const StudyOptions& options, const std::filesystem::path& dir,
                      const std::vector<LevelAction>& resume = {});

}  // namespace tmlab::convergence
