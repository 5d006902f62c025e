// The recorder of one run: the per-step scalar series every runner writes (names from
// series_names.hpp), the nodal displacement frames (displacement.h5), timeseries.h5, the standard
// plots.json and the summary blocks that both runners (the tensor-mass model and the deal.II
// reference) write alike. What a runner adds on its own (model-specific energies, the solver's
// history, the discretisation) it passes in or adds to the summary itself.
//
//   Recorder rec(conditions, probe_names, probe_nodes);
//   rec.open_displacements(out.file("displacement.h5"));   // the writing rank only
//   rec.record(values);                                     // every recorded step
//   rec.add_field_frame(t, U);                              // the steps with field output
//   rec.write_timeseries(out.file("timeseries.h5"), {{"case", name}});
//   rec.close_displacements("");
//   summary.update(rec.summary_blocks());
#pragma once

#include "core/io/hdf5_file.hpp"
#include "core/mesh/mesh.hpp"
#include "core/results/series_names.hpp"
#include "core/results/series_table.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace tmlab {

/// Writes every series of `table` to `path` as /series/<name> (one 1-D dataset each, with its unit
/// as the attribute "unit" unless the unit is empty), then the root attributes in the order given.
void write_series_file(const std::filesystem::path& path, const SeriesTable& table,
                       const std::vector<std::pair<std::string, std::string>>& root_attributes = {});

class Recorder {
 public:
  /// A model-specific scalar series recorded between elastic_energy and kinetic_energy.
  struct Extra {
    const char* name;
    const char* unit;
    double value;
  };
  /// The values of one recorded step. `reactions` holds one (x, y, z) per Dirichlet condition and
  /// `probes` one displacement per probe, in the order given to the constructor.
  struct StepValues {
    double time = 0.0;
    double max_displacement = 0.0;  ///< m
    double elastic_energy = 0.0;    ///< J, the stored energy
    std::vector<Extra> extras;
    double kinetic_energy = 0.0;    ///< J
    double min_volume_ratio = 1.0;  ///< smallest deformed/rest volume ratio of the step
    int newton_iterations = 0;
    std::vector<std::array<double, 3>> reactions;      ///< N
    std::vector<std::array<double, 3>> probes;         ///< m
    std::vector<series_names::ContactValues> contact;  ///< one per rigid contact body, if any
  };

  /// `conditions`: the names of the Dirichlet conditions, in the case file's order; the probes'
  /// names and the nodes they follow (the same number of each).
  Recorder(std::vector<std::string> conditions, std::vector<std::string> probe_names,
           std::vector<Index> probe_nodes);

  /// Appends one step to the series (time, max_displacement, elastic_energy, the extras,
  /// kinetic_energy, min_volume_ratio, newton_iterations, the reactions, the probes).
  void record(const StepValues& v);

  /// Creates the displacement file (on the rank that writes files; the others never call it).
  void open_displacements(const std::filesystem::path& path);
  /// One field frame: appends U (3 per node, tmlab node order) and t to the displacement file when
  /// it is open, and counts the frame.
  void add_field_frame(double t, const std::vector<double>& U);
  /// Sets the displacement file's unit and layout attributes and closes it; `note` is added to the
  /// layout's parenthesis ("tmlab node order; <note>") when not empty.
  void close_displacements(const std::string& note);

  /// Writes timeseries.h5 (write_series_file).
  void write_timeseries(const std::filesystem::path& path,
                        const std::vector<std::pair<std::string, std::string>>& root_attributes) const;

  /// The standard plots.json: largest displacement, the reactions' norms (when there are
  /// conditions), the energies the table holds, the probes' norms (when there are probes).
  nlohmann::json plots(const std::string& case_name) const;

  /// The summary blocks both runners write: final_time, max_displacement_m, elastic_energy_J,
  /// min_volume_ratio (over all recorded steps), min_volume_ratio_over, field_frames,
  /// final_reactions_N (per condition) and probes (node and final displacement per probe).
  nlohmann::json summary_blocks() const;

  const SeriesTable& table() const { return table_; }
  double min_volume_ratio() const { return min_volume_ratio_; }  ///< over all recorded steps
  int field_frames() const { return field_frames_; }

 private:
  std::vector<std::string> conditions_;
  std::vector<std::string> probe_names_;
  std::vector<Index> probe_nodes_;
  SeriesTable table_;
  double min_volume_ratio_ = 1.0;
  int field_frames_ = 0;
  std::unique_ptr<H5File> displacements_;
};

}  // namespace tmlab
