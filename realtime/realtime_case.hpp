// A real-time case file (cases/realtime/*.json; every key in docs/realtime.md): the liver (mesh,
// fixed base, material, Prony series, scheme), the control step, the probe, its trajectory, the
// thread rates and the run length. Read strictly (ConfigReader: unknown keys, wrong types and
// impossible values are errors naming the file and key).
#pragma once

#include "core/mesh/mesh.hpp"
#include "realtime/control_model.hpp"
#include "realtime/haptic_coupling.hpp"
#include "realtime/probe_trajectory.hpp"

#include <memory>
#include <string>
#include <vector>

namespace tmlab::rt {

struct RealtimeCase {
  std::string file;  ///< the case file
  std::string name, description;
  std::string mesh_file;  ///< resolved
  Mesh mesh;
  std::vector<Index> fixed_nodes;
  tm::StVenantKirchhoff material{0.0, 0.0};  ///< long-term
  double young = 0.0, poisson = 0.0, density = 0.0;
  tm::PronySeries prony = tm::PronySeries::from_long_term({0.0}, {1.0});
  tm::ViscoelasticOptions viscoelastic;
  std::string scheme;  ///< the Prony shorthand ("objective", "xu2011", ...)
  ControlOptions control;
  Vec3 surface_point = Vec3::Zero(), direction = -Vec3::UnitZ(), probe_start = Vec3::Zero();
  double clearance = 0.0;
  std::shared_ptr<ProbeTrajectory> trajectory;
  double haptic_hz = 1000.0, visual_hz = 40.0, study_control_hz = 100.0;
  CouplingScheme rendered = CouplingScheme::LocalModel;
  double duration = 0.0;
  int substeps = 1;  ///< model steps per haptic tick (1 / (haptic_hz control.dt), a whole number)
  int image_width = 480, image_height = 360;
  int png_every = 1;  ///< write every k-th visual frame as PNG

  /// A fresh control model of this case (dt from the case, or `dt_override` when > 0).
  std::unique_ptr<ControlModel> make_control(double dt_override = 0.0) const;
};

/// Reads a case file; relative mesh paths resolve against `tmlab_root`, relative trajectory files
/// against the case file's directory.
RealtimeCase load_realtime_case(const std::string& path, const std::string& tmlab_root);

}  // namespace tmlab::rt
