// Work-precision study of the viscoelastic tensor-mass dynamics (issue 5): error against CPU time
// for the fixed-step solvers of tmlab (explicit central difference and implicit Newmark, each with
// ViscoelasticStVK's midpoint and exact_linear recursions) and the error-controlled SUNDIALS
// integrators of the semi-discrete ODE (CVODE BDF with preconditioned and plain SPGMR, ARKStep DIRK
// with preconditioned SPGMR, ARKStep ImEx), all against one CVODE reference at a tight tolerance.
// `tmlab workprecision` (apps/tmlab/cmd_workprecision.cpp) runs it; docs/work-precision.md reports it.
//
// Error of a run: max over the output times t_k of |u(t_k) - u_ref(t_k)|_inf, divided by
// max over t_k of |u_ref(t_k)|_inf (u the nodal displacements, metres). CPU time: process CPU time
// (std::clock) of the run, set-up of the model included, the reference excluded.
#pragma once

#include "core/results/checkpoint.hpp"
#include "tensormass/kernels/elastic_model.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace tmlab::tm {

struct WorkPrecisionOptions {
  /// "liver" (meshes/liver.msh, cases/paper/xu2011_liver.json) and/or "incompressible" (nu = 0.49 beam).
  std::vector<std::string> problems{"liver", "incompressible"};
  bool quick = false;             ///< a small subset (coarse beam, few points): for the smoke test
  std::string tmlab_root = ".";   ///< where meshes/ and cases/ are
  double reference_rtol = 1e-10;  ///< CVODE rtol of the reference
  std::ostream* log = nullptr;    ///< one progress line per run (nullptr: silent)
  /// Checkpoints (issue 12; empty: none): after the reference and after every run, everything
  /// finished so far (points, each problem's reference trajectory) is written to this file, with
  /// `fingerprint` (the effective options), and SIGINT/SIGTERM stop the study there.
  std::filesystem::path checkpoint;
  nlohmann::json fingerprint = nlohmann::json::object();
  /// --resume: a checkpoint read back (read_checkpoint kind "workprecision"); its finished runs are
  /// taken from it instead of run again (their CPU times are those of the interrupted run).
  std::optional<CheckpointData> resume;
};

/// One run of one method.
struct WorkPrecisionPoint {
  std::string method;     ///< e.g. "explicit + midpoint", "CVODE BDF + spgmr+prec"
  std::string family;     ///< "explicit", "implicit" or "sundials"
  std::string parameter;  ///< "dt" (fixed step, s) or "rtol"
  double value = 0.0;
  double error = std::numeric_limits<double>::quiet_NaN();  ///< NaN when the run failed
  double cpu_seconds = 0.0, wall_seconds = 0.0;
  long steps = 0;
  long rhs_evals = 0;  ///< force evaluations: explicit 1 per step; implicit 2 per step + Newton iterations +
                       ///< line-search trials; SUNDIALS f evaluations (ImEx: f_E + f_I)
  long newton_iterations = 0, linear_iterations = 0, preconditioner_setups = 0;
  std::string failure;  ///< why the run failed (empty when it did not)
};

struct WorkPrecisionProblem {
  std::string name, description;
  Index nodes = 0, tets = 0, ode_size = 0;
  double t_end = 0.0, output_interval = 0.0;
  double dt_critical = 0.0;       ///< explicit stability limit (estimate_critical_time_step)
  double max_displacement = 0.0;  ///< max over output times of |u_ref|_inf, m
  WorkPrecisionPoint reference;   ///< the reference run (error 0 by definition)
  std::vector<WorkPrecisionPoint> points;
};

/// Runs the study. Throws tmlab::Error for an unknown problem name or a failing reference; a failing
/// method run is recorded in its point (failure) and the study goes on.
std::vector<WorkPrecisionProblem> run_work_precision(const WorkPrecisionOptions& options);

/// workprecision.h5: per problem a group /<problem> (attributes: description, t_end, output_interval,
/// dt_critical, max_displacement, reference method, rtol and statistics) and per method a group
/// /<problem>/<method slug> (attributes method, family, parameter) with 1-D datasets value, error,
/// cpu_seconds, wall_seconds, steps, rhs_evals, newton_iterations, linear_iterations,
/// preconditioner_setups (one entry per run; error NaN for a failed run).
void write_work_precision_h5(const std::vector<WorkPrecisionProblem>& problems, const std::string& path);
/// A markdown table per problem (method, dt or rtol, error, CPU s, steps, f evals, Newton, linear, prec
/// setups).
std::string work_precision_table(const std::vector<WorkPrecisionProblem>& problems);
/// The result of `tmlab workprecision` in `dir`: workprecision.h5, workprecision.md (the tables under a
/// heading quoting `command_line`) and, when `plots`, workprecision_<problem>.png drawn by
/// python/tmlab_workprecision_plot.py (its output in plots.log). A failing plot script is not an error
/// (the numbers are in workprecision.h5): the summary says so and a warning goes to `warn` (may be
/// null). Returns the summary (for summary.json).
nlohmann::json write_work_precision(const std::vector<WorkPrecisionProblem>& problems,
                                    const std::string& command_line, const std::filesystem::path& dir,
                                    bool plots, const std::string& tmlab_root, std::ostream* warn);
/// "cvode_bdf_spgmr_prec" from "CVODE BDF + spgmr+prec".
std::string method_slug(const std::string& method);

}  // namespace tmlab::tm
