// Differences between two result directories of the same case run by two models (the tensor-mass
// model and the deal.II reference): nodal displacements (displacement.h5), reaction forces,
// elastic energy and, for runs with rigid contact bodies, each body's contact force, contact area
// and active-node count (timeseries.h5). Model-agnostic: it reads only the files both runners write.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <vector>

namespace tmlab {

struct ComparisonSeries {
  std::vector<double> time;              ///< of the displacement frames
  std::vector<double> step_time;         ///< of the steps (reaction and energy series)
  std::vector<double> rel_displacement;  ///< |u_a - u_b| / |u_b| per frame (absolute when |u_b| = 0)
  std::vector<double> rel_reaction;      ///< max over conditions of |R_a - R_b| / max_{c,t} |R_b|, per step
  std::vector<double> rel_energy;        ///< |W_a - W_b| / max_t |W_b|, per step
  /// Contact (runs with rigid bodies only, else empty), per step, max over bodies:
  std::vector<double> rel_contact_force;  ///< |F_a - F_b| / max_{body,t} |F_b|
  std::vector<double> rel_contact_area;   ///< |A_a - A_b| / max_{body,t} A_b
};

/// Compares run `a` against run `b` (b is the reference). Throws tmlab::Error naming the file when
/// a result is missing or the two runs are not comparable (different node counts or steps).
/// Returns {"rel_diff_displacement", "rel_diff_reaction", "rel_diff_energy"} (max over steps) and
/// details per condition; with contact bodies (contact_<body>_force_x in run b) also
/// "rel_diff_contact_force", "rel_diff_contact_area", "max_diff_active_nodes" and a "contact" object
/// per body (a body missing from run a is an error). `series` receives the per-step values when not null.
nlohmann::json compare_results(const std::filesystem::path& a, const std::filesystem::path& b,
                               ComparisonSeries* series = nullptr);

}  // namespace tmlab
