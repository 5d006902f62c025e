// The request of `tmlab fit`: see fit_request.hpp.
#include "fit_request.hpp"

#include "commands.hpp"

#include "calibration/data/measured_data.hpp"
#include "core/results/unit_checkpoint.hpp"

#include <iostream>
#include <tuple>

namespace tmlab::cli {

namespace {

/// "NAME=VALUE" of --fix / --weight.
std::pair<std::string, double> name_value(const std::string& option, const std::string& s) {
  const std::size_t eq = s.find('=');
  if (eq == std::string::npos || eq == 0) throw UsageError(option + " needs NAME=VALUE, got '" + s + "'");
  return {s.substr(0, eq), parse_double(option + " " + s.substr(0, eq), s.substr(eq + 1))};
}

/// Every --prior NAME=MEAN:SD.
std::vector<fit::Prior> parse_priors(const ParsedOptions& p) {
  std::vector<fit::Prior> priors;
  for (const auto& s : p.all("--prior")) {
    const std::size_t eq = s.find('='), colon = s.find(':', eq == std::string::npos ? 0 : eq);
    if (eq == std::string::npos || eq == 0 || colon == std::string::npos)
      throw UsageError("--prior needs NAME=MEAN:SD, got '" + s + "'");
    fit::Prior q;
    q.parameter = s.substr(0, eq);
    q.mean = parse_double("--prior " + q.parameter + " mean", s.substr(eq + 1, colon - eq - 1));
    q.sd = parse_double("--prior " + q.parameter + " sd", s.substr(colon + 1));
    if (!(q.sd > 0.0)) throw UsageError("--prior " + q.parameter + ": the sd must be positive");
    priors.push_back(q);
  }
  return priors;
}

/// --mesh CELLS,LAYERS and --substeps of the FE-rig forward model.
fit::RigForwardModelOptions parse_fe_rig_options(const ParsedOptions& p) {
  fit::RigForwardModelOptions fe;
  std::tie(fe.mesh.cells, fe.mesh.layers) = parse_cells_layers(p.text("--mesh"));
  fe.substeps = int(p.whole("--substeps"));
  return fe;
}

}  // namespace

FitRequest parse_fit_request(const ParsedOptions& p) {
  FitRequest q;
  q.spec = fit::parse_model_spec(p.text("--model"));
  for (const auto& s : p.all("--fix")) q.fixes.push_back(name_value("--fix", s));
  for (const auto& s : p.all("--weight")) q.weights.push_back(name_value("--weight", s));
  fit::FitOptions& o = q.options;
  q.cost = p.text("--cost");
  if (q.cost == "l1") o.cost = fit::Cost::L1;
  o.starts = int(p.whole("--starts"));
  o.threads = int(p.whole("--threads"));
  o.seed = (unsigned long)p.whole("--seed");
  o.geodesic = p.flag("--geodesic");
  o.profile = !p.flag("--no-profile");
  if (!p.flag("--quiet"))
    o.progress = [](const std::string& line) { std::cout << line << "\n" << std::flush; };
  o.local_runs = int(p.whole("--local-runs"));
  o.siman_evaluations = int(p.whole("--siman-evaluations"));
  q.global = p.text("--global");
  if (q.global == "siman") o.global = fit::GlobalStage::Siman;
  q.priors = parse_priors(p);
  q.fe = parse_fe_rig_options(p);
  // closed_form by default: an FE-rig fit can take minutes, so it is asked for, not fallen into.
  q.forward = p.text("--forward");
  if (p.given("--relaxation-bands")) {
    const std::string v = p.text("--relaxation-bands");
    const auto comma = v.find(',');
    if (comma == std::string::npos)
      throw UsageError("--relaxation-bands needs FLOOR,CEILING (e.g. 0.5,1), got '" + v + "'");
    q.band_floor = parse_double("--relaxation-bands", v.substr(0, comma));
    q.band_ceiling = parse_double("--relaxation-bands", v.substr(comma + 1));
    if (!(q.band_floor > 0.0 && q.band_ceiling > 0.0))
      throw UsageError("--relaxation-bands: FLOOR and CEILING must be positive, got '" + v + "'");
    if (q.spec.prony_terms == 0)
      throw UsageError("--relaxation-bands needs Prony terms in --model (e.g. " + to_string(q.spec.law) +
                       "+prony:2)");
  }
  return q;
}

nlohmann::json fit_fingerprint(const ParsedOptions& p, const FitRequest& q,
                               const std::filesystem::path& csv) {
  nlohmann::json j = p.config(kFingerprint);
  j["max_iterations"] = q.options.max_iterations;  // the engine's, not an option
  j["data"] = {{"csv", file_hash(csv)}, {"metadata", file_hash(measured::metadata_path(csv))}};
  return j;
}

}  // namespace tmlab::cli
