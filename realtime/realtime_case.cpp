#include "realtime/realtime_case.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/config/case_config.hpp"
#include "core/config/config_reader.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "realtime/live_protocol.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace tmlab::rt {

namespace fs = std::filesystem;

namespace {

Vec3 read_vec3(ConfigReader& r, const std::string& key) {
  const auto v = r.require<std::vector<double>>(key);
  if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
    throw r.error(key, "must be 3 finite numbers");
  return {v[0], v[1], v[2]};
}

/// trajectory.file: resolved against the case file's folder (symbolic links followed) and refused
/// unless it stays inside that folder, so a case cannot make tmlab read (and quote in an error) a
/// file from elsewhere on the machine.
fs::path trajectory_file(ConfigReader& tr, const std::string& case_path) {
  const std::string given = tr.require<std::string>("file");
  if (given.empty()) throw tr.error("file", "is empty (a CSV file next to the case file)");
  std::error_code ec;
  const fs::path folder = fs::weakly_canonical(fs::absolute(case_path, ec).parent_path(), ec);
  const fs::path f(given);
  const fs::path resolved = ec ? fs::path() : fs::weakly_canonical(f.is_absolute() ? f : folder / f, ec);
  if (ec) throw tr.error("file", "= '" + printable(given, 100) + "' cannot be resolved: " + ec.message());
  const auto [in_folder, in_resolved] =
      std::mismatch(folder.begin(), folder.end(), resolved.begin(), resolved.end());
  if (in_folder != folder.end() || in_resolved == resolved.end())
    throw tr.error("file", "= '" + printable(given, 100) + "' resolves to " +
                               printable(resolved.string(), 200) + ", outside the case file's folder " +
                               printable(folder.string(), 200) +
                               ": a trajectory file must lie in that folder or below it");
  return resolved;
}

double rate(ConfigReader& r, const std::string& key, double fallback) {
  const double v = r.positive(key, fallback);
  if (v > 20000.0) throw r.error(key, "must be <= 20000 Hz");
  return v;
}

}  // namespace

RealtimeCase load_realtime_case(const std::string& path, const std::string& tmlab_root) {
  RealtimeCase c;
  c.file = path;
  const nlohmann::json j = ConfigReader::parse_file(path);
  ConfigReader root(j, path);
  c.name = root.require<std::string>("name");
  c.description = root.get<std::string>("description", "");
  c.duration = root.positive("duration");

  {
    ConfigReader liver = root.child("liver");
    const fs::path mesh(liver.require<std::string>("mesh"));
    const fs::path resolved = mesh.is_absolute() ? mesh : (fs::path(tmlab_root) / mesh).lexically_normal();
    if (!fs::exists(resolved)) throw liver.error("mesh", "file not found: " + resolved.string());
    c.mesh_file = resolved.string();
    MeshReport report;
    int repaired = 0;
    c.mesh = load_case_mesh(MeshSpec{c.mesh_file}, report, repaired);
    c.fixed_nodes =
        select_nodes(c.mesh, NodeSelector::from_json(liver.raw("base"), path + ": key 'liver.base'"));
    if (c.fixed_nodes.empty()) throw liver.error("base", "selects no node");
    ConfigReader mat = liver.child("material");
    c.young = mat.positive("E");
    c.poisson = mat.require<double>("nu");
    if (!(c.poisson > -1.0 && c.poisson < 0.5)) throw mat.error("nu", "must be in (-1, 0.5)");
    c.density = mat.positive("density");
    mat.finish();
    c.material = tm::StVenantKirchhoff::from_young_poisson(c.young, c.poisson);
    c.prony = tm::PronySeries::from_json(liver.raw("prony"), path, "liver.prony");
    c.scheme = liver.get<std::string>("scheme", "objective");
    const auto scheme = prony_scheme_from_string(c.scheme);
    if (!scheme) throw liver.error("scheme", "unknown Prony scheme '" + c.scheme + "'");
    c.scheme = to_string(*scheme);  // the current name (xu2011 for the former seed)
    const PronySchemeParts parts = scheme_parts(*scheme);
    c.viscoelastic.history = parts.history;
    c.viscoelastic.integration = parts.integration;
    liver.finish();
  }
  {
    ConfigReader ctl = root.child("control");
    c.control.dt = ctl.positive("dt");
    c.control.mass_damping = ctl.positive("mass_damping", 0.0, true);
    c.control.penalty_stiffness = ctl.positive("penalty_stiffness", 0.0, true);
    c.control.stability_fraction = ctl.positive("stability_fraction", 0.8);
    if (c.control.stability_fraction > 1.0) throw ctl.error("stability_fraction", "must be <= 1");
    c.control.coupling_horizon = ctl.positive("coupling_horizon", 0.0, true);
    ctl.finish();
  }
  {
    ConfigReader probe = root.child("probe");
    c.control.probe_radius = probe.positive("radius");
    c.surface_point = read_vec3(probe, "surface_point");
    c.direction = read_vec3(probe, "direction");
    if (!(c.direction.norm() > 0.0)) throw probe.error("direction", "must be a non-zero vector");
    c.direction.normalize();
    c.clearance = probe.positive("clearance", 0.0, true);
    const Box reach = probe_box(c.mesh, 2.0 * c.control.probe_radius);
    if ((c.surface_point - reach.min).minCoeff() < 0.0 || (reach.max - c.surface_point).minCoeff() < 0.0)
      throw probe.error("surface_point",
                        "lies outside the mesh's bounding box grown by two probe radii: it is "
                        "in metres, in the mesh frame");
    probe.finish();
    c.probe_start = c.surface_point - (c.control.probe_radius + c.clearance) * c.direction;
  }
  {
    ConfigReader tr = root.child("trajectory");
    const std::string type = tr.require<std::string>("type");
    if (type == "poke") {
      c.trajectory = std::make_shared<ProbeTrajectory>(
          ProbeTrajectory::poke(c.probe_start, c.direction, tr.positive("depth"), tr.positive("ramp"),
                                tr.positive("hold", 0.0, true)));
    } else if (type == "ellipse") {
      const Vec3 lateral = tr.has("lateral") ? read_vec3(tr, "lateral") : Vec3::UnitX();
      c.trajectory = std::make_shared<ProbeTrajectory>(ProbeTrajectory::ellipse(
          c.probe_start, c.direction, lateral, tr.positive("depth"), tr.positive("amplitude", 0.0, true),
          tr.positive("period"), tr.get<int>("cycles", 1), tr.positive("ramp")));
    } else if (type == "csv") {
      const fs::path resolved = trajectory_file(tr, path);
      const Box reach = probe_box(c.mesh, 2.0 * c.control.probe_radius);
      const ProbeBounds bounds{reach.min, reach.max, "the mesh's bounding box grown by two probe radii"};
      c.trajectory = std::make_shared<ProbeTrajectory>(ProbeTrajectory::read_csv(resolved.string(), &bounds));
      c.probe_start = c.trajectory->start();
    } else {
      throw tr.error("type", "must be \"poke\", \"ellipse\" or \"csv\" (got \"" + type + "\")");
    }
    tr.finish();
  }
  if (root.has("haptic")) {
    ConfigReader h = root.child("haptic");
    c.haptic_hz = rate(h, "rate_hz", c.haptic_hz);
    c.rendered = parse_coupling(h.get<std::string>("coupling", "local_model"));
    c.study_control_hz = rate(h, "study_control_hz", c.study_control_hz);
    h.finish();
  }
  if (root.has("visual")) {
    ConfigReader v = root.child("visual");
    c.visual_hz = rate(v, "rate_hz", c.visual_hz);
    c.png_every = v.get<int>("png_every", 1);
    if (c.png_every < 1) throw v.error("png_every", "must be >= 1");
    if (v.has("image_size")) {
      const auto s = v.require<std::vector<int>>("image_size");
      if (s.size() != 2 || s[0] < 16 || s[1] < 16 || s[0] > 4096 || s[1] > 4096)
        throw v.error("image_size", "must be [width, height] in 16..4096");
      c.image_width = s[0];
      c.image_height = s[1];
    }
    v.finish();
  }
  root.finish();
  const double ratio = c.haptic_hz / c.study_control_hz;
  if (std::abs(ratio - std::round(ratio)) > 1e-9 || ratio < 1.0)
    throw Error(path + ": key 'haptic.study_control_hz': the haptic rate must be a whole multiple of it");
  const double sub = 1.0 / (c.control.dt * c.haptic_hz);
  if (std::abs(sub - std::round(sub)) > 1e-6 || sub < 0.5)
    throw Error(path +
                ": key 'control.dt': the haptic period 1/haptic.rate_hz must be a whole number of model "
                "steps (the ground truth steps the model at the haptic rate)");
  c.substeps = static_cast<int>(std::lround(sub));
  return c;
}

}  // namespace tmlab::rt
