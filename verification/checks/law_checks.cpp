// Checks of the hyperelastic laws beyond St VK on the fast model's F-based kernel (issue 13):
//   laws.unconfined_compression  the unconfined compression rig (calibration/rigs) of each law,
//                                frictionless platens against the homogeneous closed form
//                                (calibration/closed_forms platen_state) at every load step, and
//                                bonded platens: the barrelling measured as the force ratio.
#include "calibration/closed_forms/homogeneous.hpp"
#include "calibration/rigs/rig.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/config/case_config.hpp"
#include "core/io/hdf5_file.hpp"
#include "runner/case_runner.hpp"
#include "tensormass/materials/law_factory.hpp"
#include "verification/checks/builtin_checks.hpp"
#include "verification/checks/check_support.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace tmlab::verify {

namespace {

namespace fs = std::filesystem;

/// One platen run of the rig: the platen displacement d(t_k) and the platen force |F_z| at every
/// recorded step (t = 0 first), the law the run used and the sample's reference cross-section.
struct PlatenRun {
  std::vector<double> d, force;
  double area = 0.0;
  nlohmann::json summary;
};

PlatenRun run_rig(const CheckContext& ctx, const rigs::RigSpec& spec, double depth) {
  const fs::path case_file = rigs::write_rig(spec, ctx.work_dir / "rigs");
  CaseConfig c = tmlab::load_case(case_file.string(), ctx.source_root.string());
  c.output.vtu = c.output.xdmf = c.output.plots = false;
  RunOptions o;
  o.results_root = (ctx.work_dir / "runs").string();
  o.tmlab_root = ctx.source_root.string();
  o.plots = false;
  const RunResult r = tm::run_case(c, o);
  const H5File h5 = H5File::open_read(r.dir + "/timeseries.h5");
  const std::vector<double> t = h5.read_double("/series/time");
  const std::vector<double> fz = h5.read_double("/series/reaction_top_platen_z");
  PlatenRun run;
  for (std::size_t k = 0; k < t.size(); ++k) {
    run.d.push_back(depth * std::min(t[k] / spec.history.t.back(), 1.0));  // the rig's linear ramp
    run.force.push_back(std::abs(fz[k]));
  }
  // A0 = V / H of the polygonal (meshed) cylinder: the closed form's area is the mesh's, exactly.
  run.area = r.summary.at("mesh").at("volume_m3").get<double>() / spec.height;
  run.summary = r.summary;
  return run;
}

// ------------------------------------------------------------------ laws.unconfined_compression
Measurements unconfined_compression(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const double radius = p.positive("radius"), height = p.positive("height");
  const double compression = p.positive("compression");
  const int cells = p.require<int>("cells"), layers = p.require<int>("layers"),
            steps = p.require<int>("steps");
  const nlohmann::json& laws = p.raw("laws");
  if (!laws.is_object() || laws.empty())
    throw p.error("laws", "must be an object {name: material section} with at least one law");
  p.finish();

  Measurements m;
  double worst = 0.0, min_ratio = std::numeric_limits<double>::infinity();
  const double depth = compression * height;
  for (auto it = laws.begin(); it != laws.end(); ++it) {
    rigs::RigSpec s;
    s.test = rigs::RigTest::UnconfinedCompression;
    s.shape = rigs::SampleShape::Cylinder;
    s.radius = radius, s.height = height, s.cells = cells, s.layers = layers;
    s.history = rigs::DisplacementHistory::ramp_hold(depth, 1.0, 0.0);
    s.steps_per_sample = steps;
    s.material = it.value();
    s.model = "hyperelastic_tl";
    s.name = "unconfined-" + it.key() + "-frictionless";
    s.platens = rigs::Support::Frictionless;
    const PlatenRun free = run_rig(ctx, s, depth);
    s.name = "unconfined-" + it.key() + "-bonded";
    s.platens = rigs::Support::Bonded;
    const PlatenRun bonded = run_rig(ctx, s, depth);

    // The law the runs used, built from the case file the rig wrote (the same parse and factory).
    const CaseConfig c =
        tmlab::load_case((ctx.work_dir / "rigs" / (s.name + ".json")).string(), ctx.source_root.string());
    const std::string law_name = to_string(c.material.law);
    const tm::Law law = tm::make_law(c.material.law, c.material.parameters, it.key());
    double err = 0.0;
    nlohmann::json rows = nlohmann::json::array();
    for (std::size_t k = 1; k < free.d.size(); ++k) {
      const closed_forms::PlatenState h =
          closed_forms::platen_state(law, closed_forms::PlatenTest::Unconfined, height, free.area, free.d[k]);
      err = std::max(err, std::abs(free.force[k] - h.force) / h.force);
      rows.push_back({{"d_m", free.d[k]},
                      {"force_frictionless_N", free.force[k]},
                      {"closed_form_N", h.force},
                      {"lateral_stretch", h.lateral_stretch},
                      {"force_bonded_N", bonded.force[k]}});
    }
    const double ratio = bonded.force.back() / free.force.back();
    worst = std::max(worst, err);
    min_ratio = std::min(min_ratio, ratio);
    m.set(it.key() + "_rel_error_frictionless", err);
    m.set(it.key() + "_bonded_over_frictionless", ratio);
    m.data[it.key()] = {{"law", law_name}, {"steps", rows}};
    ctx.log << "  " << it.key() << " (" << law_name << "): frictionless vs closed form " << scientific(err, 2)
            << ", bonded / frictionless force " << ratio << "\n";
    m.notes.push_back(
        it.key() + " (" + law_name + "), " + std::to_string(static_cast<int>(100 * compression)) +
        " % compression: max rel. error of the frictionless platen force " + scientific(err, 2) +
        "; bonded / frictionless force at the end " + std::to_string(ratio));
  }
  m.set("max_rel_error_frictionless", worst);
  m.set("min_bonded_over_frictionless", min_ratio);
  return m;
}

}  // namespace

void register_law_checks(CheckRegistry& registry) {
  registry.add("laws.unconfined_compression", unconfined_compression);
}

}  // namespace tmlab::verify
