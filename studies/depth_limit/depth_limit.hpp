// How deep can a rigid sphere go before a tet inverts? (issue 13, `tmlab depth-limit`; docs/contact.md,
// section "Inversion depth of each law")
//
// The paper's indentation: a rigid sphere of radius R = 5 mm pressed into the centre of the top of a
// thick block (40 x 40 x 20 mm, bottom bonded). By symmetry the quarter [0, W]^2 x [0, H] (W = 20 mm,
// H = 20 mm) with rollers on x = 0 (u_x = 0) and y = 0 (u_y = 0) and the bottom z = 0 clamped. The
// mesh is make_box_mesh of the unit cube with n cells per axis, graded towards the indentation point
// (x = W xi^p, y = W eta^p, z = H (1 - (1 - zeta)^p)): every cell stays an axis-aligned box, so the
// Kuhn split stays valid, and the smallest spacing at the indentation point is W / n^p.
//
// Every law runs on the F-based kernel (HyperelasticTL; for St VK it equals the tensor-mass kernel to
// round-off, tensormass/kernels/tests/test_hyperelastic_tl.cpp) with the same small-strain moduli
// (E, nu), through the fast model's contact (ContactStaticSolver, augmented Lagrangian, default
// options). The sphere moves down in equal increments of `increment` to `max_depth`; after each
// accepted increment the smallest volume ratio J = det F over all tets is recorded. A run ends:
//   inverted       a converged state has min J <= 0. The inversion depth is where min J reaches 0 by
//                  linear interpolation between that state and the previous one (bracketed by the two
//                  depths). Only St VK can get there: its energy is finite for det F <= 0;
//   solver_failed  the contact solve fails after its cut-backs (ContactStaticSolver::advance throws).
//                  For the laws whose energy -> +inf as J -> 0 (HyperelasticTL returns +inf for
//                  J <= 0, so the Newton line search never accepts an inverted tet) this is where the
//                  discrete problem stops having a solution the solver finds: the mesh "locks up"
//                  instead of inverting; the last converged depth and its min J are recorded;
//   max_depth      max_depth is reached with every tet positive.
#pragma once

#include "core/mesh/mesh.hpp"
#include "core/results/checkpoint.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace tmlab::tm {

/// One law of the study: its name (tensormass/materials/law_factory.hpp) and parameter object.
struct DepthLimitLaw {
  std::string name;
  nlohmann::json parameters;
};

/// Every law of the fast model with the small-strain moduli (E, nu): stvk, neo_hookean (young,
/// poisson), and with G = E / (2 (1 + nu)), kappa = E / (3 (1 - 2 nu)): mooney_rivlin c10 = 0.4 G,
/// c01 = 0.1 G; yeoh c10 = G/2, c20 = G/20; ogden one term alpha = 5, mu = 2 G / 5;
/// veronda_westmann c1 = G, c2 = 1.
std::vector<DepthLimitLaw> default_depth_limit_laws(double E, double nu);

struct DepthLimitOptions {
  double radius = 0.005;                        ///< sphere R, m
  double half_width = 0.02;                     ///< W: the quarter block's side (the block is 2W x 2W x H), m
  double height = 0.02;                         ///< H, m
  double young = 3000.0;                        ///< small-strain modulus of every law, Pa
  double poisson = 0.45;                        ///< small-strain Poisson ratio
  double grading = 2.0;                         ///< p of the graded map (1 = uniform)
  double max_depth = 0.008;                     ///< m
  double increment = 0.5e-3;                    ///< depth increment, m
  std::vector<DepthLimitLaw> laws;              ///< empty: default_depth_limit_laws(young, poisson)
  std::vector<int> cells = {4, 6, 9};           ///< cells per axis of the quarter block (>= 2 each)
  std::function<void(const std::string&)> log;  ///< progress lines (may be empty)
  /// Checkpoints (empty: none): after every finished (law, mesh) run the finished runs are written
  /// to this file (kind "depth_limit") with `fingerprint` (the effective options), and SIGINT/SIGTERM
  /// stop the study there. A run interrupted half-way runs again from its start on --resume.
  std::filesystem::path checkpoint;
  nlohmann::json fingerprint = nlohmann::json::object();
  /// --resume: a checkpoint read back (read_checkpoint kind "depth_limit"); its finished runs are
  /// taken from it instead of run again.
  std::optional<CheckpointData> resume;
};

/// One accepted increment.
struct DepthLimitSample {
  double depth = 0.0;    ///< m
  double min_j = 1.0;    ///< smallest det F over all tets
  Index worst_tet = -1;  ///< where
  double force = 0.0;    ///< full-block force on the sphere (4 x the quarter's), N
  int active_nodes = 0;  ///< in the quarter
};

struct DepthLimitRun {
  std::string law;
  int cells = 0;
  Index tets = 0;       ///< of the quarter
  double h_min = 0.0;   ///< the spacing at the indentation point, W / n^p, m
  std::string outcome;  ///< inverted | solver_failed | max_depth
  double inversion_depth = std::numeric_limits<double>::quiet_NaN();  ///< interpolated (inverted only)
  /// inverted: the last depth with min J > 0 and the first with min J <= 0; solver_failed: the
  /// deepest converged depth and the depth of the increment that failed.
  double bracket_low = std::numeric_limits<double>::quiet_NaN();
  double bracket_high = std::numeric_limits<double>::quiet_NaN();
  /// The depth at which the run ended: the inversion depth (inverted) or the deepest converged depth
  /// (solver_failed: the failing increment lies within one increment beyond it); NaN for max_depth.
  double limit_depth = std::numeric_limits<double>::quiet_NaN();
  double deepest = 0.0;  ///< deepest converged depth, m
  double deepest_min_j = 1.0;
  /// The worst tet at the end (inverted: the first inverted one): its centroid's depth below the top
  /// and its distance from the indenter's axis, m.
  double worst_depth_below_top = 0.0, worst_radius = 0.0;
  std::string message;  ///< the solver's error (solver_failed)
  std::vector<DepthLimitSample> samples;
};

/// The graded quarter block with n cells per axis (see the file comment).
Mesh inversion_block(const DepthLimitOptions& options, int cells);

/// Runs one law on one mesh. Throws tmlab::Error for bad options or law parameters (not for a
/// failing solve, which is an outcome).
DepthLimitRun run_inversion(const DepthLimitOptions& options, const DepthLimitLaw& law, int cells);

/// The effective options as JSON: geometry, moduli, depths, grading, cells and the laws with their
/// parameters (what a --resume must match; also the "options" of depth_limit.json).
nlohmann::json depth_limit_fingerprint(const DepthLimitOptions& options);

/// Runs every law on every mesh (laws outer, meshes inner), taking the finished runs of
/// `options.resume` from it and checkpointing after every run when `options.checkpoint` is set.
std::vector<DepthLimitRun> run_depth_limit_study(const DepthLimitOptions& options);

/// The study as JSON (options, and per run the outcome and samples) and as a markdown table.
nlohmann::json depth_limit_json(const DepthLimitOptions& options, const std::vector<DepthLimitRun>& runs);
std::string depth_limit_markdown(const DepthLimitOptions& options, const std::vector<DepthLimitRun>& runs,
                                 const std::string& command_line);

}  // namespace tmlab::tm
