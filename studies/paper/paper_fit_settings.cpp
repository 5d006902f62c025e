#include "studies/paper/paper_fit_settings.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/config/config_reader.hpp"
#include "core/constitutive/law_catalogue.hpp"

#include <cmath>

namespace tmlab::tm {

using nlohmann::json;

PaperFitSettings paper_fit_settings(const json& params_in, const std::string& where, bool quick) {
  json params = params_in;
  if (quick) {
    if (!params.contains("quick")) throw Error(where + ": no 'quick' block (needed by --quick)");
    params.merge_patch(params.at("quick"));
  }
  PaperFitSettings s;
  ConfigReader r(params, where);
  if (r.has("quick")) r.raw("quick");
  {
    ConfigReader f = r.child("reference");
    s.indenter_radius = f.positive("indenter_radius");
    s.depths = f.require<std::vector<double>>("depths");
    if (s.depths.empty()) throw f.error("depths", "needs at least one depth");
    for (const double d : s.depths)
      if (!(d > 0.0 && d < s.indenter_radius))
        throw f.error("depths",
                      "each depth must lie in (0, indenter_radius) (got " + significant(d, 4) + ")");
    s.young = f.positive("young");
    s.poisson = f.require<double>("poisson");
    if (!(s.poisson > -1.0 && s.poisson < 0.5)) throw f.error("poisson", "must lie in (-1, 0.5)");
    if (f.has("prony")) {
      // Nava's instantaneous convention g_j (errata eq. 24): alpha_j = g_j / (1 - sum g), E_j = alpha_j
      // E_inf.
      ConfigReader p = f.child("prony");
      const auto conv = p.require<std::string>("convention");
      const json terms = p.raw("terms");
      p.finish();
      if (conv != "instantaneous" && conv != "long_term")
        throw p.error("convention", "must be instantaneous or long_term");
      double gsum = 0.0;
      std::vector<double> w;
      for (std::size_t k = 0; k < terms.size(); ++k) {
        ConfigReader t(terms[k], where, "reference.prony.terms[" + std::to_string(k) + "]");
        w.push_back(t.positive("weight"));
        s.prony_taus.push_back(t.positive("tau"));
        t.finish();
        gsum += w.back();
      }
      if (conv == "instantaneous" && !(gsum < 1.0))
        throw p.error("terms", "instantaneous weights must sum below 1");
      for (const double g : w)
        s.prony_moduli.push_back(s.young * (conv == "instantaneous" ? g / (1.0 - gsum) : g));
    }
    s.ramp = f.positive("ramp");
    s.hold = f.positive("hold");
    s.ramp_samples = f.require<int>("ramp_samples");
    s.hold_samples = f.require<int>("hold_samples");
    if (s.ramp_samples < 2) throw f.error("ramp_samples", "must be >= 2");
    if (s.hold_samples < 1) throw f.error("hold_samples", "must be >= 1");
    s.noise_percent = f.positive("noise_percent_of_peak", true);
    s.seed = f.require<unsigned long>("seed");
    f.finish();
  }
  {
    ConfigReader f = r.child("rig");
    s.patch_factor = f.positive("patch_factor");
    s.patch_cells = f.require<int>("patch_cells");
    s.outer_cells = f.require<int>("outer_cells");
    s.substeps = f.get<int>("substeps", 1);
    s.contact_stiffness_factor = f.get<double>("contact_stiffness_factor", 0.0);
    s.newton_max_iterations = f.get<int>("newton_max_iterations", 40);
    if (s.newton_max_iterations < 1) throw f.error("newton_max_iterations", "must be >= 1");
    if (!(s.contact_stiffness_factor >= 0.0) || !std::isfinite(s.contact_stiffness_factor))
      throw f.error("contact_stiffness_factor", "must be >= 0 (0: the contact solver's default)");
    if (s.patch_cells < 1) throw f.error("patch_cells", "must be >= 1");
    if (s.outer_cells < 1) throw f.error("outer_cells", "must be >= 1");
    if (s.substeps < 1) throw f.error("substeps", "must be >= 1");
    f.finish();
  }
  {
    ConfigReader f = r.child("identification");
    s.laws = f.require<std::vector<std::string>>("laws");
    if (s.laws.empty()) throw f.error("laws", "needs at least one law");
    // The closed-form references see E and nu only: the laws the catalogue gives by E and nu.
    for (const auto& l : s.laws) {
      const std::optional<MaterialLaw> law = material_law_from_string(l);
      if (!law || law_descriptor(*law).bulk != BulkResponse::YoungPoisson)
        throw f.error("laws", "'" + l + "': the indentation study fits stvk and neo_hookean only");
    }
    s.starts = f.require<int>("starts");
    s.local_runs = f.require<int>("local_runs");
    s.max_iterations = f.require<int>("max_iterations");
    s.threads = f.get<int>("threads", 2);
    if (f.has("relaxation")) {
      ConfigReader v = f.child("relaxation");
      PaperFitSettings::Relaxation& x = s.relaxation;
      x.time_floor = v.get<double>("time_floor", 0.0);
      x.time_ceiling = v.get<double>("time_ceiling", 0.0);
      x.jacobian_step = v.get<double>("jacobian_step", 1e-6);
      x.xtol = v.get<double>("xtol", 1e-9);
      x.max_iterations = v.get<int>("max_iterations", 0);
      if (!(x.time_floor >= 0.0) || !std::isfinite(x.time_floor))
        throw v.error("time_floor",
                      "must be >= 0 (a fraction of the shortest sampling interval; 0: no bands)");
      if (!(x.time_ceiling >= 0.0) || !std::isfinite(x.time_ceiling))
        throw v.error("time_ceiling", "must be >= 0 (a multiple of the test's duration; 0: no bands)");
      if ((x.time_floor > 0.0) != (x.time_ceiling > 0.0))
        throw v.error(x.time_floor > 0.0 ? "time_ceiling" : "time_floor",
                      "time_floor and time_ceiling are set together (both 0: no bands)");
      if (!(x.jacobian_step > 0.0 && x.jacobian_step < 0.1))
        throw v.error("jacobian_step", "must lie in (0, 0.1) (a relative finite-difference step)");
      if (!(x.xtol > 0.0 && x.xtol < 0.1)) throw v.error("xtol", "must lie in (0, 0.1)");
      if (x.max_iterations < 0)
        throw v.error("max_iterations", "must be >= 0 (0: identification.max_iterations)");
      v.finish();
    }
    if (s.starts < 1 || s.local_runs < 1 || s.max_iterations < 1 || s.threads < 1)
      throw f.error("starts", "starts, local_runs, max_iterations and threads must be >= 1");
    f.finish();
  }
  {
    ConfigReader f = r.child("usable");
    s.max_rms_percent = f.positive("max_rms_percent");
    s.max_drift_percent = f.positive("max_drift_percent");
    s.max_law_difference_percent = f.positive("max_law_difference_percent");
    f.finish();
  }
  r.finish();
  return s;
}

}  // namespace tmlab::tm
