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

/// A whole number 1..10000 for option `key`, `fallback` when it is not given.
int positive_int(const Parsed& p, const std::string& key, int fallback) {
  return p.has(key) ? int(parse_whole(key, p.get(key), 1, 10000)) : fallback;
}

/// Every --prior NAME=MEAN:SD.
std::vector<fit::Prior> parse_priors(const Parsed& p) {
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
fit::FeRigOptions parse_fe_rig_options(const Parsed& p) {
  fit::FeRigOptions fe;
  if (p.has("--mesh")) std::tie(fe.mesh.cells, fe.mesh.layers) = parse_cells_layers(p.get("--mesh"));
  fe.substeps = positive_int(p, "--substeps", fe.substeps);
  return fe;
}

}  // namespace

FitRequest parse_fit_request(const Parsed& p) {
  FitRequest q;
  q.spec = fit::parse_model_spec(p.get("--model"));
  for (const auto& s : p.all("--fix")) q.fixes.push_back(name_value("--fix", s));
  for (const auto& s : p.all("--weight")) q.weights.push_back(name_value("--weight", s));
  fit::FitOptions& o = q.options;
  q.cost = p.get("--cost", "least_squares");
  if (q.cost == "l1")
    o.cost = fit::Cost::L1;
  else if (q.cost != "least_squares")
    throw UsageError("--cost must be least_squares or l1 (got '" + q.cost + "')");
  o.starts = positive_int(p, "--starts", o.starts);
  o.threads = positive_int(p, "--threads", 2);
  o.seed = (unsigned long)positive_int(p, "--seed", 1);
  o.geodesic = p.has("--geodesic");
  o.profile = !p.has("--no-profile");
  if (!p.has("--quiet"))
    o.progress = [](const std::string& line) { std::cout << line << "\n" << std::flush; };
  o.local_runs = positive_int(p, "--local-runs", o.local_runs);
  o.siman_evaluations = positive_int(p, "--siman-evaluations", o.siman_evaluations);
  q.global = p.get("--global", "multistart");
  if (q.global == "siman")
    o.global = fit::GlobalStage::Siman;
  else if (q.global != "multistart")
    throw UsageError("--global must be multistart or siman (got '" + q.global + "')");
  q.priors = parse_priors(p);
  q.fe = parse_fe_rig_options(p);
  // closed_form by default: an FE-rig fit can take minutes, so it is asked for, not fallen into.
  q.forward = p.get("--forward", "closed_form");
  if (q.forward != "auto" && q.forward != "closed_form" && q.forward != "fe_rig")
    throw UsageError("--forward must be auto, closed_form or fe_rig (got '" + q.forward + "')");
  if (p.has("--relaxation-bands")) {
    const std::string v = p.get("--relaxation-bands");
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

nlohmann::json manifest_config(const Parsed& p, const FitRequest& q) {
  const fit::FitOptions& o = q.options;
  return {{"model", q.spec.text},
          {"cost", q.cost},
          {"starts", o.starts},
          {"threads", o.threads},
          {"seed", o.seed},
          {"geodesic", o.geodesic},
          {"profile", o.profile},
          {"fix", p.all("--fix")},
          {"weight", p.all("--weight")},
          {"forward", q.forward},
          {"global", q.global},
          {"prior", p.all("--prior")},
          {"mesh", {q.fe.mesh.cells, q.fe.mesh.layers}},
          {"substeps", q.fe.substeps},
          {"relaxation_bands", p.get("--relaxation-bands", "")}};
}

nlohmann::json fit_fingerprint(const Parsed& p, const FitRequest& q, const std::filesystem::path& csv) {
  nlohmann::json j = manifest_config(p, q);
  const fit::FitOptions& o = q.options;
  j["local_runs"] = o.local_runs;
  j["siman_evaluations"] = o.siman_evaluations;
  j["max_iterations"] = o.max_iterations;
  j["noise"] = p.get("--noise", "");
  j["data"] = {{"csv", file_hash(csv)}, {"metadata", file_hash(measured::metadata_path(csv))}};
  return j;
}

}  // namespace tmlab::cli
